//! A smooth ground-plane path: straight segments between waypoints, corners rounded by circular
//! arcs of one radius, so the heading is continuous and the curvature is 0 or ±1/r.

use patchflow_dataset::wrap_angle_upper_rad;

/// A point of the path: where, which way, how sharply it turns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    /// Position in the ground plane, metres.
    pub position_m: [f64; 2],
    /// Tangent direction, counter-clockwise from +x.
    pub heading_rad: f64,
    /// Signed curvature (positive = turning left), 1/m.
    pub curvature_per_m: f64,
}

#[derive(Debug, Clone, PartialEq)]
enum Element {
    Line {
        start: [f64; 2],
        dir: [f64; 2],
        length: f64,
    },
    Arc {
        centre: [f64; 2],
        radius: f64,
        start_angle: f64,
        sign: f64,
        length: f64,
    },
}

impl Element {
    fn length(&self) -> f64 {
        match self {
            Self::Line { length, .. } | Self::Arc { length, .. } => *length,
        }
    }

    fn at(&self, u: f64) -> PathPoint {
        match *self {
            Self::Line { start, dir, .. } => PathPoint {
                position_m: [start[0] + dir[0] * u, start[1] + dir[1] * u],
                heading_rad: dir[1].atan2(dir[0]),
                curvature_per_m: 0.0,
            },
            Self::Arc {
                centre,
                radius,
                start_angle,
                sign,
                ..
            } => {
                let angle = start_angle + sign * u / radius;
                PathPoint {
                    position_m: [
                        centre[0] + radius * angle.cos(),
                        centre[1] + radius * angle.sin(),
                    ],
                    heading_rad: wrap_angle_upper_rad(angle + sign * std::f64::consts::FRAC_PI_2),
                    curvature_per_m: sign / radius,
                }
            }
        }
    }
}

/// A path by arc length; beyond both ends it continues straight along the end tangents.
#[derive(Debug, Clone, PartialEq)]
pub struct Path {
    elements: Vec<Element>,
    starts_m: Vec<f64>,
    length_m: f64,
}

impl Path {
    /// Builds the path through `points` with corners rounded at `radius_m`. Fails (with a plain
    /// reason) if a corner's arc does not fit between its neighbours or the path doubles back.
    pub fn new(points: &[[f64; 2]], radius_m: f64) -> Result<Self, String> {
        if points.len() < 2 {
            return Err(format!(
                "a path needs at least two points, got {}",
                points.len()
            ));
        }
        let n = points.len();
        let mut dirs = Vec::with_capacity(n - 1);
        let mut lengths = Vec::with_capacity(n - 1);
        for w in points.windows(2) {
            let (dx, dy) = (w[1][0] - w[0][0], w[1][1] - w[0][1]);
            let length = dx.hypot(dy);
            if length < 1e-6 {
                return Err("two consecutive path points coincide".to_owned());
            }
            dirs.push([dx / length, dy / length]);
            lengths.push(length);
        }
        // Turn angle and tangent length at every point (0 at both ends).
        let mut turn = vec![0.0; n];
        let mut tangent = vec![0.0; n];
        for k in 1..n - 1 {
            let (a, b) = (dirs[k - 1], dirs[k]);
            let theta = (a[0] * b[1] - a[1] * b[0]).atan2(a[0] * b[0] + a[1] * b[1]);
            if theta.abs() > 179f64.to_radians() {
                return Err(format!("the path doubles back at point {k}"));
            }
            turn[k] = theta;
            tangent[k] = radius_m * (theta.abs() / 2.0).tan();
        }
        for k in 0..n - 1 {
            if tangent[k] + tangent[k + 1] > lengths[k] + 1e-9 {
                let corner = if tangent[k] >= tangent[k + 1] {
                    k
                } else {
                    k + 1
                };
                return Err(format!(
                    "the corner at path point {corner} (a {:.0}° turn with radius {radius_m} m) needs {:.1} m of straight road, but the segment from point {k} to {} is only {:.1} m long; lower turn_radius_m or move the points apart",
                    turn[corner].abs().to_degrees(),
                    tangent[k] + tangent[k + 1],
                    k + 1,
                    lengths[k]
                ));
            }
        }
        let mut elements = Vec::new();
        for k in 0..n - 1 {
            let d = dirs[k];
            let start = [
                points[k][0] + d[0] * tangent[k],
                points[k][1] + d[1] * tangent[k],
            ];
            let length = lengths[k] - tangent[k] - tangent[k + 1];
            if length > 1e-9 {
                elements.push(Element::Line {
                    start,
                    dir: d,
                    length,
                });
            }
            let corner = k + 1;
            if corner < n - 1 && turn[corner] != 0.0 {
                let arc_start = [
                    points[corner][0] - d[0] * tangent[corner],
                    points[corner][1] - d[1] * tangent[corner],
                ];
                let sign = turn[corner].signum();
                let left = [-d[1], d[0]];
                let centre = [
                    arc_start[0] + sign * radius_m * left[0],
                    arc_start[1] + sign * radius_m * left[1],
                ];
                let start_angle = (arc_start[1] - centre[1]).atan2(arc_start[0] - centre[0]);
                elements.push(Element::Arc {
                    centre,
                    radius: radius_m,
                    start_angle,
                    sign,
                    length: radius_m * turn[corner].abs(),
                });
            }
        }
        let mut starts_m = Vec::with_capacity(elements.len());
        let mut length_m = 0.0;
        for e in &elements {
            starts_m.push(length_m);
            length_m += e.length();
        }
        Ok(Self {
            elements,
            starts_m,
            length_m,
        })
    }

    /// Total length between the first and last waypoint, metres.
    pub fn length_m(&self) -> f64 {
        self.length_m
    }

    /// The point at arc length `s_m`; negative or beyond the end continues straight.
    pub fn at(&self, s_m: f64) -> PathPoint {
        let (Some(first), Some(last)) = (self.elements.first(), self.elements.last()) else {
            return PathPoint {
                position_m: [0.0, 0.0],
                heading_rad: 0.0,
                curvature_per_m: 0.0,
            };
        };
        if s_m <= 0.0 {
            return straight_from(first.at(0.0), s_m);
        }
        if s_m >= self.length_m {
            return straight_from(last.at(last.length()), s_m - self.length_m);
        }
        let i = self
            .starts_m
            .partition_point(|&start| start <= s_m)
            .saturating_sub(1);
        self.elements[i].at(s_m - self.starts_m[i])
    }
}

/// Continues straight from `p` by `u` metres (negative = backwards).
fn straight_from(p: PathPoint, u: f64) -> PathPoint {
    let (sin, cos) = p.heading_rad.sin_cos();
    PathPoint {
        position_m: [p.position_m[0] + cos * u, p.position_m[1] + sin * u],
        heading_rad: p.heading_rad,
        curvature_per_m: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn l_turn() -> Path {
        Path::new(&[[0.0, 0.0], [40.0, 0.0], [40.0, 40.0], [0.0, 60.0]], 8.0).unwrap()
    }

    #[test]
    fn heading_and_position_are_continuous_along_the_path() {
        let path = l_turn();
        let ds = 0.01;
        let mut s = -5.0;
        while s < path.length_m() + 5.0 {
            let (a, b) = (path.at(s), path.at(s + ds));
            assert!(
                wrap_angle_upper_rad(b.heading_rad - a.heading_rad).abs() < ds / 8.0 + 1e-9,
                "heading jumps at s = {s}"
            );
            let step = (b.position_m[0] - a.position_m[0]).hypot(b.position_m[1] - a.position_m[1]);
            assert!((step - ds).abs() < 1e-6, "position jumps at s = {s}");
            s += ds;
        }
    }

    #[test]
    fn arcs_have_the_requested_radius() {
        let path = l_turn();
        let curvatures: Vec<f64> = (0..2000)
            .map(|i| path.at(i as f64 * path.length_m() / 2000.0).curvature_per_m)
            .filter(|k| *k != 0.0)
            .collect();
        assert!(!curvatures.is_empty());
        assert!(
            curvatures
                .iter()
                .all(|k| (k.abs() - 1.0 / 8.0).abs() < 1e-12)
        );
        // The first corner turns left (+90°), reached from heading 0 to heading 90°.
        let after = path.at(40.0 + 5.0);
        assert!((after.heading_rad - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
    }

    #[test]
    fn the_path_passes_near_its_corners_and_through_its_ends() {
        let path = l_turn();
        let end = path.at(path.length_m()).position_m;
        assert!((end[0] - 0.0).abs() < 1e-9 && (end[1] - 60.0).abs() < 1e-9);
        // A 90° fillet of radius r passes r(√2 − 1) from the corner.
        let closest = (0..4000)
            .map(|i| path.at(i as f64 * 0.02))
            .map(|p| (p.position_m[0] - 40.0).hypot(p.position_m[1]))
            .fold(f64::MAX, f64::min);
        assert!(
            (closest - 8.0 * (2f64.sqrt() - 1.0)).abs() < 0.02,
            "closest {closest}"
        );
    }

    #[test]
    fn a_corner_that_does_not_fit_is_an_error() {
        let err = Path::new(&[[0.0, 0.0], [5.0, 0.0], [5.0, 40.0]], 10.0).unwrap_err();
        assert!(err.contains("corner at path point 1"), "{err}");
    }
}
