//! Uneven ground for synthetic sweeps: a raised, sloped base with a gentle swell, and a straight
//! road with a crowned (cambered) surface and raised sidewalks behind curbs, with exact ray
//! intersection. The truth the ground estimate is tested against.

use nalgebra::Vector3;

/// A straight road: its surface falls from the crown line to both edges (camber), and beyond the
/// edges sidewalks stand a curb height above the edge of the road.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SyntheticRoad {
    /// A point on the crown line, world x, y.
    pub centre_xy: [f64; 2],
    /// Direction of the crown line, counter-clockwise from world +x.
    pub yaw_rad: f64,
    /// Crown line to curb, metres.
    pub half_width_m: f64,
    /// Cross slope of the road surface (0.02 is the usual 2 %).
    pub camber: f64,
    /// Height of the curb face, metres.
    pub curb_m: f64,
}

impl SyntheticRoad {
    /// A 7 m wide road along `yaw_rad` through `centre_xy`, 2 % camber, 0.15 m curbs.
    pub fn street(centre_xy: [f64; 2], yaw_rad: f64) -> Self {
        Self {
            centre_xy,
            yaw_rad,
            half_width_m: 3.5,
            camber: 0.02,
            curb_m: 0.15,
        }
    }

    /// Signed distance of `xy` from the crown line (positive to the left).
    fn lateral_m(&self, xy: [f64; 2]) -> f64 {
        let (s, c) = self.yaw_rad.sin_cos();
        -s * (xy[0] - self.centre_xy[0]) + c * (xy[1] - self.centre_xy[1])
    }
}

/// The ground height field `base + grade · (x, y) + swell · sin(2π x / λ) + road profile`.
///
/// `SyntheticGround::default()` is the flat plane z = 0 of the original synthetic world, and is
/// intersected exactly as before.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SyntheticGround {
    /// Height at the world origin, metres.
    pub base_m: f64,
    /// Constant slope (dz/dx, dz/dy).
    pub grade: [f64; 2],
    /// Amplitude of a swell along world x (gentle grade changes), metres.
    pub swell_m: f64,
    /// Wavelength of the swell, metres (ignored when `swell_m` is 0).
    pub swell_wavelength_m: f64,
    /// A road with camber and curbs, if any; without one the whole ground is road.
    pub road: Option<SyntheticRoad>,
}

/// What a ray hit on the ground.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct GroundHit {
    /// Distance along the (unit) ray, metres.
    pub(crate) t: f64,
    /// True on the road surface, false on a sidewalk or curb face.
    pub(crate) on_road: bool,
}

impl SyntheticGround {
    /// True height of the ground at world `(x, y)`.
    pub fn height_m(&self, x_m: f64, y_m: f64) -> f64 {
        self.height_on(x_m, y_m, self.on_road(x_m, y_m))
    }

    /// Height at `(x, y)` of the road surface (`on_road`) or the sidewalk, each continued
    /// smoothly across the curb line.
    fn height_on(&self, x_m: f64, y_m: f64, on_road: bool) -> f64 {
        let mut z = self.smooth_m(x_m, y_m);
        if let Some(road) = &self.road {
            let l = road.lateral_m([x_m, y_m]);
            z += if on_road {
                -road.camber * l.abs()
            } else {
                -road.camber * road.half_width_m + road.curb_m
            };
        }
        z
    }

    /// True if `(x, y)` lies on the road surface (not on a sidewalk).
    pub fn on_road(&self, x_m: f64, y_m: f64) -> bool {
        self.road
            .is_none_or(|r| r.lateral_m([x_m, y_m]).abs() <= r.half_width_m)
    }

    /// Base, grade and swell: everything but the road profile.
    fn smooth_m(&self, x_m: f64, y_m: f64) -> f64 {
        let mut z = self.base_m + self.grade[0] * x_m + self.grade[1] * y_m;
        if self.swell_m != 0.0 {
            z += self.swell_m * (std::f64::consts::TAU * x_m / self.swell_wavelength_m).sin();
        }
        z
    }

    /// True for the plane z = 0 (intersected in closed form).
    fn is_flat(&self) -> bool {
        self == &Self::default()
    }

    /// A bound on |∇ height| away from the curbs.
    fn lipschitz(&self) -> f64 {
        let swell = if self.swell_m == 0.0 {
            0.0
        } else {
            self.swell_m.abs() * std::f64::consts::TAU / self.swell_wavelength_m.abs()
        };
        let camber = self.road.map_or(0.0, |r| r.camber.abs());
        self.grade[0].hypot(self.grade[1]) + swell + camber
    }

    /// The first point where the unit ray `origin + t·dir`, `0 < t < max_t`, meets the ground.
    ///
    /// The ray is cut where it crosses a curb line; on each piece the height is smooth, and
    /// sphere tracing with the gradient bound steps to the surface without passing it. Entering
    /// a piece below its surface means the ray hit the curb face.
    pub(crate) fn intersect(
        &self,
        origin: &Vector3<f64>,
        dir: &Vector3<f64>,
        max_t: f64,
    ) -> Option<GroundHit> {
        if self.is_flat() {
            // The original closed form, bit for bit.
            let t = -origin.z / dir.z;
            return (dir.z < -1e-9 && t < max_t).then_some(GroundHit { t, on_road: true });
        }
        let at = |t: f64| origin + dir * t;
        let mut cuts = self.curb_crossings(origin, dir, max_t);
        cuts.push(max_t);
        let climb = self.lipschitz() * dir.x.hypot(dir.y) - dir.z;
        let mut t = 0.0;
        for end in cuts {
            // The piece lies on one side of every curb: its height is smooth.
            let mid = at(0.5 * (t + end));
            let on_road = self.on_road(mid.x, mid.y);
            let gap = |t: f64| {
                let p = at(t);
                p.z - self.height_on(p.x, p.y, on_road)
            };
            if t > 0.0 && gap(t) < 0.0 {
                // Entering the piece below its surface: the curb face.
                return Some(GroundHit { t, on_road: false });
            }
            for _ in 0..10_000 {
                let g = gap(t);
                if g < 1e-6 {
                    return Some(GroundHit { t, on_road });
                }
                if climb <= 0.0 {
                    break;
                }
                t += g / climb;
                if t >= end {
                    break;
                }
            }
            t = end;
        }
        None
    }

    /// Ray distances in `(0, max_t)` at which the ray crosses a curb line, sorted.
    fn curb_crossings(&self, origin: &Vector3<f64>, dir: &Vector3<f64>, max_t: f64) -> Vec<f64> {
        let Some(road) = &self.road else {
            return Vec::new();
        };
        let l0 = road.lateral_m([origin.x, origin.y]);
        let (s, c) = road.yaw_rad.sin_cos();
        let dl = -s * dir.x + c * dir.y;
        if dl.abs() < 1e-12 {
            return Vec::new();
        }
        let mut cuts: Vec<f64> = [road.half_width_m, -road.half_width_m]
            .iter()
            .map(|edge| (edge - l0) / dl)
            .filter(|&t| t > 0.0 && t < max_t)
            .collect();
        cuts.sort_by(f64::total_cmp);
        cuts
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn street() -> SyntheticGround {
        SyntheticGround {
            base_m: 1.0,
            grade: [0.04, -0.01],
            swell_m: 0.3,
            swell_wavelength_m: 80.0,
            road: Some(SyntheticRoad::street([0.0, 0.0], 0.0)),
        }
    }

    #[test]
    fn the_road_falls_by_its_camber_from_the_crown_and_the_sidewalk_stands_a_curb_higher() {
        let g = SyntheticGround {
            road: Some(SyntheticRoad::street([0.0, 0.0], 0.0)),
            ..SyntheticGround::default()
        };
        assert_eq!(g.height_m(5.0, 0.0), 0.0);
        assert!((g.height_m(5.0, 2.0) + 0.04).abs() < 1e-12);
        assert!((g.height_m(5.0, -3.5) + 0.07).abs() < 1e-12);
        assert!((g.height_m(5.0, 4.0) - 0.08).abs() < 1e-12);
        assert!(g.on_road(0.0, 3.4) && !g.on_road(0.0, -3.6));
    }

    #[test]
    fn a_ray_down_onto_uneven_ground_stops_on_its_surface() {
        let g = street();
        let origin = Vector3::new(0.0, 0.0, g.height_m(0.0, 0.0) + 1.73);
        for (azimuth, elevation_deg) in [(0.0, -5.0), (1.0, -12.0), (2.5, -9.0), (-1.2, -20.0)] {
            let el: f64 = f64::to_radians(elevation_deg);
            let dir = Vector3::new(
                el.cos() * f64::cos(azimuth),
                el.cos() * f64::sin(azimuth),
                el.sin(),
            );
            let hit = g.intersect(&origin, &dir, 120.0).unwrap();
            let p = origin + dir * hit.t;
            // On a curb face (the road runs along x) the point lies between the heights of the
            // road and the sidewalk either side.
            let (a, b) = (g.height_m(p.x, p.y - 0.01), g.height_m(p.x, p.y + 0.01));
            assert!(
                p.z > a.min(b) - 1e-3 && p.z < a.max(b) + 1e-3,
                "{azimuth} {elevation_deg}: z {} between {a} and {b}",
                p.z
            );
        }
    }

    #[test]
    fn a_ray_across_the_curb_at_kerb_height_hits_the_curb_face() {
        let g = SyntheticGround {
            road: Some(SyntheticRoad::street([0.0, 0.0], 0.0)),
            ..SyntheticGround::default()
        };
        // Level rays from above the crown towards the sidewalk (y > 3.5, 0.08 m high).
        let across = Vector3::new(0.0, 1.0, 0.0);
        let over = g.intersect(&Vector3::new(0.0, 0.0, 0.1), &across, 50.0);
        assert!(over.is_none(), "a ray above the sidewalk passes: {over:?}");
        let hit = g
            .intersect(&Vector3::new(0.0, 0.0, 0.05), &across, 50.0)
            .unwrap();
        assert!((hit.t - 3.5).abs() < 1e-9 && !hit.on_road, "{hit:?}");
    }

    #[test]
    fn the_flat_default_is_the_plane_z_0() {
        let g = SyntheticGround::default();
        let dir = Vector3::new(0.9, 0.0, -0.1).normalize();
        let hit = g
            .intersect(&Vector3::new(0.0, 0.0, 1.73), &dir, 120.0)
            .unwrap();
        assert_eq!(hit.t, -1.73 / dir.z);
        assert_eq!(g.height_m(30.0, -7.0), 0.0);
    }
}
