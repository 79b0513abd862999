//! A small convex polyhedron as the intersection of its face planes, a parry shape with an
//! analytic ray cast (clip the ray by every plane: a few flops per face). parry casts rays on its
//! `ConvexPolyhedron` and `Cylinder` with GJK iterations, which cost a street of car bodies,
//! wheels, trunks and poles several times the rest of a sweep; every non-box part of the street
//! world (hulls, and cylinders as octagonal prisms) is one of these instead.

use rapier3d::parry::bounding_volume::Aabb;
use rapier3d::parry::query::{PointProjection, PointQuery, Ray, RayCast, RayIntersection};
use rapier3d::parry::shape::FeatureId;
use rapier3d::prelude::{Real, Vector};

use super::custom_shape::{CustomShape, impl_parry_shape};

/// Sides of the prism standing in for a cylinder.
const PRISM_SIDES: usize = 8;

/// A convex polyhedron: outward unit normals `n` and offsets `c` with `n · p ≤ c` inside.
#[derive(Debug, Clone, PartialEq)]
pub struct PlaneHull {
    planes: Vec<(Vector, f32)>,
    aabb: Aabb,
}

impl PlaneHull {
    /// The convex hull of `points` (at least four, not all in one plane), or `None`.
    pub fn from_points(points: &[[f32; 3]]) -> Option<Self> {
        let p: Vec<Vector> = points
            .iter()
            .map(|q| Vector::new(q[0], q[1], q[2]))
            .collect();
        let scale = p.iter().map(|q| q.length()).fold(1.0f32, f32::max);
        let eps = 1e-4 * scale;
        let mut planes: Vec<(Vector, f32)> = Vec::new();
        for i in 0..p.len() {
            for j in i + 1..p.len() {
                for k in j + 1..p.len() {
                    let n = (p[j] - p[i]).cross(p[k] - p[i]);
                    if n.length() < 1e-9 * scale * scale {
                        continue;
                    }
                    let n = n.normalize();
                    let c = n.dot(p[i]);
                    let (above, below) = p.iter().fold((0, 0), |(a, b), q| {
                        let s = n.dot(*q) - c;
                        (a + usize::from(s > eps), b + usize::from(s < -eps))
                    });
                    let plane = match (above, below) {
                        (0, _) => (n, c),
                        (_, 0) => (-n, -c),
                        _ => continue,
                    };
                    if !planes
                        .iter()
                        .any(|(m, d)| m.dot(plane.0) > 1.0 - 1e-5 && (d - plane.1).abs() < eps)
                    {
                        planes.push(plane);
                    }
                }
            }
        }
        if planes.len() < 4 {
            return None;
        }
        let mins = p.iter().fold(Vector::splat(f32::MAX), |m, q| m.min(*q));
        let maxs = p.iter().fold(Vector::splat(f32::MIN), |m, q| m.max(*q));
        Some(Self {
            planes,
            aabb: Aabb::new(mins, maxs),
        })
    }

    /// An octagonal prism around a cylinder of `radius` and `half_height` along local axis
    /// `axis` (1: y, a wheel; 2: z, a post).
    pub fn prism(axis: usize, half_height: f32, radius: f32) -> Option<Self> {
        // The circumscribed octagon's vertices: its faces touch the cylinder.
        let r = radius / (std::f32::consts::PI / PRISM_SIDES as f32).cos();
        let mut points = Vec::with_capacity(2 * PRISM_SIDES);
        for k in 0..PRISM_SIDES {
            let a = std::f32::consts::TAU * (k as f32 + 0.5) / PRISM_SIDES as f32;
            let (u, v) = (r * a.cos(), r * a.sin());
            for h in [-half_height, half_height] {
                points.push(if axis == 1 { [u, h, v] } else { [u, v, h] });
            }
        }
        Self::from_points(&points)
    }

    /// Entry and exit `t` of the ray and the entering face's normal.
    #[inline]
    fn clip(&self, ray: &Ray) -> Option<(f32, f32, Vector)> {
        let (mut t0, mut t1) = (f32::MIN, f32::MAX);
        let mut normal = -ray.dir;
        for &(n, c) in &self.planes {
            let denominator = n.dot(ray.dir);
            let distance = c - n.dot(ray.origin);
            if denominator.abs() < 1e-12 {
                if distance < 0.0 {
                    return None;
                }
                continue;
            }
            let t = distance / denominator;
            if denominator < 0.0 {
                if t > t0 {
                    t0 = t;
                    normal = n;
                }
            } else if t < t1 {
                t1 = t;
            }
            if t0 > t1 {
                return None;
            }
        }
        Some((t0, t1, normal))
    }
}

impl RayCast for PlaneHull {
    fn cast_local_ray_and_get_normal(
        &self,
        ray: &Ray,
        max_time_of_impact: Real,
        solid: bool,
    ) -> Option<RayIntersection> {
        let (t0, t1, normal) = self.clip(ray)?;
        if t1 < 0.0 {
            return None;
        }
        if t0 >= 0.0 {
            return (t0 <= max_time_of_impact)
                .then(|| RayIntersection::new(t0, normal, FeatureId::Unknown));
        }
        // The origin is inside.
        if solid {
            return Some(RayIntersection::new(0.0, Vector::ZERO, FeatureId::Unknown));
        }
        (t1 <= max_time_of_impact)
            .then(|| RayIntersection::new(t1, Vector::ZERO, FeatureId::Unknown))
    }
}

impl PointQuery for PlaneHull {
    fn project_local_point(&self, pt: Vector, _solid: bool) -> PointProjection {
        // Conservative: the nearest face plane (exact inside and off faces, not at edges).
        let (n, c) = self
            .planes
            .iter()
            .copied()
            .max_by(|a, b| (a.0.dot(pt) - a.1).total_cmp(&(b.0.dot(pt) - b.1)))
            .unwrap_or((Vector::Z, 0.0));
        let s = n.dot(pt) - c;
        PointProjection::new(s <= 0.0, pt - n * s)
    }

    fn project_local_point_and_get_feature(&self, pt: Vector) -> (PointProjection, FeatureId) {
        (self.project_local_point(pt, false), FeatureId::Unknown)
    }
}

impl CustomShape for PlaneHull {
    fn local_aabb(&self) -> Aabb {
        self.aabb
    }

    fn ccd_thickness_m(&self) -> Real {
        self.aabb.half_extents().min_element()
    }

    fn ccd_angular_thickness_rad(&self) -> Real {
        std::f32::consts::FRAC_PI_4
    }

    fn convex(&self) -> bool {
        true
    }
}

impl_parry_shape!(PlaneHull);

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> PlaneHull {
        let points: Vec<[f32; 3]> = (0..8)
            .map(|k| {
                [
                    if k & 1 == 0 { -1.0 } else { 1.0 },
                    if k & 2 == 0 { -1.0 } else { 1.0 },
                    if k & 4 == 0 { -1.0 } else { 1.0 },
                ]
            })
            .collect();
        PlaneHull::from_points(&points).unwrap()
    }

    #[test]
    fn a_cube_has_six_faces_and_a_ray_meets_it_where_parrys_cuboid_does() {
        let hull = cube();
        assert_eq!(hull.planes.len(), 6);
        let cuboid = rapier3d::parry::shape::Cuboid::new(Vector::splat(1.0));
        for k in 0..200 {
            let a = k as f32 * 0.1;
            let ray = Ray::new(
                Vector::new(5.0 * a.cos(), 5.0 * a.sin(), 0.3 * (a * 3.0).sin()),
                Vector::new(-a.cos(), -a.sin() + 0.1, 0.05).normalize(),
            );
            let ours = hull.cast_local_ray_and_get_normal(&ray, 100.0, true);
            let parry = cuboid.cast_local_ray_and_get_normal(&ray, 100.0, true);
            assert_eq!(ours.is_some(), parry.is_some(), "ray {k}");
            if let (Some(o), Some(p)) = (ours, parry) {
                assert!(
                    (o.time_of_impact - p.time_of_impact).abs() < 1e-4,
                    "ray {k}"
                );
                assert!((o.normal - p.normal).length() < 1e-4, "ray {k}");
            }
        }
    }

    #[test]
    fn a_ray_from_inside_exits_through_the_far_face_when_not_solid() {
        let ray = Ray::new(Vector::ZERO, Vector::X);
        assert_eq!(cube().cast_local_ray(&ray, 10.0, true), Some(0.0));
        assert_eq!(cube().cast_local_ray(&ray, 10.0, false), Some(1.0));
    }

    #[test]
    fn a_prism_touches_its_cylinder() {
        let wheel = PlaneHull::prism(1, 0.1, 0.3).unwrap();
        assert_eq!(wheel.planes.len(), 10);
        let toi = wheel.cast_local_ray(
            &Ray::new(Vector::new(-2.0, 0.0, 0.0), Vector::X),
            10.0,
            true,
        );
        assert!((toi.unwrap() - 1.7).abs() < 1e-5, "{toi:?}");
    }
}
