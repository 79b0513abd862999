//! A building whose façades have depth, as one parry shape: the outline box, with a grid of
//! window openings on its four side faces (bays between piers, storeys between floor bands,
//! a plinth and a parapet) recessed to a glass plane. A ray is clipped by the outline; where it
//! enters through an opening it goes on to the glass, or meets the opening's reveal if it leaves
//! the opening on the way. One collider per building instead of a hundred pier and band boxes
//! keeps the ray-cast tree small. Hits on glass report `FeatureId::Face(1)`, on wall `Face(0)`.

use rapier3d::parry::bounding_volume::Aabb;
use rapier3d::parry::query::{PointProjection, PointQuery, Ray, RayCast, RayIntersection};
use rapier3d::parry::shape::FeatureId;
use rapier3d::prelude::{Real, Vector};

use super::custom_shape::{CustomShape, impl_parry_shape};

/// Feature id of a glass hit.
pub const GLASS_FEATURE: FeatureId = FeatureId::Face(1);
/// Feature id of a wall hit.
const WALL_FEATURE: FeatureId = FeatureId::Face(0);

/// The layout of a façade grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacadeGrid {
    /// Bay width (pier to pier), metres.
    pub bay_m: f32,
    /// Pier width, metres.
    pub pier_m: f32,
    /// Storey height, metres.
    pub floor_m: f32,
    /// Sill height above each floor, metres.
    pub sill_m: f32,
    /// Band below each floor (lintel), metres.
    pub lintel_m: f32,
    /// Solid plinth at the foot, metres.
    pub plinth_m: f32,
    /// Solid parapet at the top, metres.
    pub parapet_m: f32,
    /// Depth of the window recess, metres.
    pub recess_m: f32,
}

/// A building with recessed windows, centred on its box centre.
#[derive(Debug, Clone, PartialEq)]
pub struct FacadeShape {
    half: Vector,
    grid: FacadeGrid,
}

impl FacadeShape {
    /// A building of half extents `half` (z: half the height) with façade `grid`.
    pub fn new(half: [f32; 3], grid: FacadeGrid) -> Self {
        Self {
            half: Vector::new(half[0], half[1], half[2]),
            grid,
        }
    }

    /// The window opening (bay, storey) holding face coordinate `s` (along the face, from its
    /// start) and height `z` (from the foot) on a face `length` long, if any.
    fn opening(&self, s: f32, z: f32, length: f32) -> Option<(i32, i32)> {
        let g = &self.grid;
        let height = 2.0 * self.half.z;
        if z < g.plinth_m.max(g.sill_m) || z > height - g.parapet_m || s < 0.0 || s > length {
            return None;
        }
        let bays = (length / g.bay_m).round().max(1.0);
        let bay = length / bays;
        let (k, f) = ((s / bay).floor(), (z / g.floor_m).floor());
        let (in_bay, in_floor) = (s - k * bay, z - f * g.floor_m);
        let inside = in_bay > g.pier_m / 2.0
            && in_bay < bay - g.pier_m / 2.0
            && in_floor > g.sill_m
            && in_floor < g.floor_m - g.lintel_m;
        inside.then_some((k as i32, f as i32))
    }

    /// Slab clip of the ray with a box of half extents `h`: entry, exit, entry axis.
    fn clip(ray: &Ray, h: Vector) -> Option<(f32, f32, usize)> {
        let (mut t0, mut t1, mut axis) = (f32::MIN, f32::MAX, 0);
        for a in 0..3 {
            let (o, d) = (ray.origin[a], ray.dir[a]);
            if d.abs() < 1e-12 {
                if o.abs() > h[a] {
                    return None;
                }
                continue;
            }
            let (ta, tb) = ((-h[a] - o) / d, (h[a] - o) / d);
            let (near, far) = (ta.min(tb), ta.max(tb));
            if near > t0 {
                t0 = near;
                axis = a;
            }
            t1 = t1.min(far);
        }
        (t0 <= t1).then_some((t0, t1, axis))
    }

    fn face_normal(&self, ray: &Ray, axis: usize) -> Vector {
        let mut n = Vector::ZERO;
        n[axis] = -ray.dir[axis].signum();
        n
    }
}

impl RayCast for FacadeShape {
    fn cast_local_ray_and_get_normal(
        &self,
        ray: &Ray,
        max_toi: Real,
        solid: bool,
    ) -> Option<RayIntersection> {
        let (t0, t1, axis) = Self::clip(ray, self.half)?;
        if t1 < 0.0 || t0 > max_toi {
            return None;
        }
        if t0 < 0.0 {
            return solid.then(|| RayIntersection::new(0.0, Vector::ZERO, WALL_FEATURE));
        }
        let wall = RayIntersection::new(t0, self.face_normal(ray, axis), WALL_FEATURE);
        if axis == 2 {
            return Some(wall);
        }
        // The face's own coordinates: `s` along it, `z` up from the foot.
        let along = 1 - axis;
        let length = 2.0 * self.half[along];
        let face = |t: f32| {
            let p = ray.origin + ray.dir * t;
            (p[along] + self.half[along], p.z + self.half.z)
        };
        let (s0, z0) = face(t0);
        let Some(opening) = self.opening(s0, z0, length) else {
            return Some(wall);
        };
        // Through the opening to the glass, set back by the recess.
        let mut inner = self.half;
        inner[axis] -= self.grid.recess_m;
        let Some((g0, _, g_axis)) = Self::clip(ray, inner) else {
            return Some(wall);
        };
        let (s1, z1) = face(g0);
        if g_axis == axis && g0 <= max_toi && self.opening(s1, z1, length) == Some(opening) {
            return Some(RayIntersection::new(
                g0,
                self.face_normal(ray, axis),
                GLASS_FEATURE,
            ));
        }
        // Left the opening on the way: the reveal, where the ray crosses its edge.
        let mut t_edge = g0.max(t0);
        let steps = 8;
        for k in 1..=steps {
            let t = t0 + (g0.max(t0) - t0) * k as f32 / steps as f32;
            let (s, z) = face(t);
            if self.opening(s, z, length) != Some(opening) {
                t_edge = t;
                break;
            }
        }
        (t_edge <= max_toi).then(|| {
            let mut n = Vector::ZERO;
            n[along] = -ray.dir[along].signum();
            RayIntersection::new(t_edge, n, WALL_FEATURE)
        })
    }
}

impl PointQuery for FacadeShape {
    fn project_local_point(&self, pt: Vector, _solid: bool) -> PointProjection {
        let clamped = pt.clamp(-self.half, self.half);
        PointProjection::new(clamped == pt, clamped)
    }

    fn project_local_point_and_get_feature(&self, pt: Vector) -> (PointProjection, FeatureId) {
        (self.project_local_point(pt, false), FeatureId::Unknown)
    }
}

impl CustomShape for FacadeShape {
    fn local_aabb(&self) -> Aabb {
        Aabb::new(-self.half, self.half)
    }

    fn ccd_thickness_m(&self) -> Real {
        self.half.min_element()
    }

    fn ccd_angular_thickness_rad(&self) -> Real {
        std::f32::consts::FRAC_PI_2
    }
}

impl_parry_shape!(FacadeShape);

#[cfg(test)]
mod tests {
    use super::*;

    fn building() -> FacadeShape {
        let grid = FacadeGrid {
            bay_m: 3.0,
            pier_m: 0.6,
            floor_m: 3.0,
            sill_m: 0.9,
            lintel_m: 0.4,
            plinth_m: 0.7,
            parapet_m: 0.8,
            recess_m: 0.25,
        };
        FacadeShape::new([10.0, 6.0, 5.0], grid)
    }

    #[test]
    fn a_ray_through_a_window_meets_the_glass_behind_the_recess_and_one_on_a_pier_the_wall() {
        let b = building();
        // Face y = −6 (length 20 along x, s = x + 10); bay 3.077 m: bay centre s = 1.54 is glass.
        let window = b
            .cast_local_ray_and_get_normal(
                &Ray::new(Vector::new(1.54 - 10.0, -20.0, 2.0 - 5.0), Vector::Y),
                100.0,
                true,
            )
            .unwrap();
        assert_eq!(window.feature, GLASS_FEATURE);
        assert!((window.time_of_impact - 14.25).abs() < 1e-4);
        let pier = b
            .cast_local_ray_and_get_normal(
                &Ray::new(Vector::new(0.0 - 10.0, -20.0, -3.0), Vector::Y),
                100.0,
                true,
            )
            .unwrap();
        assert_eq!(pier.feature, WALL_FEATURE);
        assert!((pier.time_of_impact - 14.0).abs() < 1e-4);
        assert!((pier.normal - Vector::new(0.0, -1.0, 0.0)).length() < 1e-6);
    }

    #[test]
    fn a_grazing_ray_into_an_opening_meets_its_reveal() {
        // Enters the face y = −6 at x = −8.5 (in the first opening, x from −9.7 to −7.44) and
        // would reach the glass at x = −6.0, past the opening's edge: it meets the reveal there.
        let dir = Vector::new(1.0, 0.1, 0.0).normalize();
        let ray = Ray::new(Vector::new(-13.5, -6.5, -3.0), dir);
        let hit = building()
            .cast_local_ray_and_get_normal(&ray, 100.0, true)
            .unwrap();
        assert_eq!(hit.feature, WALL_FEATURE);
        assert!((hit.normal - Vector::new(-1.0, 0.0, 0.0)).length() < 1e-6);
        let x = ray.point_at(hit.time_of_impact).x;
        assert!((-7.8..=-7.0).contains(&x), "reveal met at x = {x}");
    }
}
