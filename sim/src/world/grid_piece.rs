//! One static piece of the street world as the piece grid holds it: its solid (a concrete parry
//! or patchflow shape, so a ray test is a direct call, not a trait-object dispatch), where it
//! stands (centre and yaw about z) and its world AABB for a quick reject.

use rapier3d::parry::bounding_volume::Aabb;
use rapier3d::parry::query::{Ray, RayCast, RayIntersection};
use rapier3d::parry::shape::{Ball, Cuboid};
use rapier3d::prelude::Vector;

use super::facade_shape::FacadeShape;
use super::piece::{Piece, PieceShape};
use super::plane_hull::PlaneHull;

/// The solid of a piece, in its own frame.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Solid {
    Cuboid(Cuboid),
    Ball(Ball),
    Hull(PlaneHull),
    Facade(FacadeShape),
}

impl Solid {
    /// The solid of `piece`, or `None` for a degenerate hull.
    pub(crate) fn of(piece: &Piece) -> Option<Self> {
        Some(match &piece.shape {
            PieceShape::Cuboid(h) => Self::Cuboid(Cuboid::new(Vector::new(h[0], h[1], h[2]))),
            PieceShape::Ball(r) => Self::Ball(Ball::new(*r)),
            PieceShape::Cylinder(h, r) => Self::Hull(PlaneHull::prism(1, *h, *r)?),
            PieceShape::Column(h, r) => Self::Hull(PlaneHull::prism(2, *h, *r)?),
            PieceShape::Hull(points) => Self::Hull(PlaneHull::from_points(points)?),
            PieceShape::Facade(half, grid) => Self::Facade(FacadeShape::new(*half, *grid)),
        })
    }

    #[inline]
    fn cast_local(&self, ray: &Ray, max_toi: f32, solid: bool) -> Option<f32> {
        match self {
            Self::Cuboid(s) => s.cast_local_ray(ray, max_toi, solid),
            Self::Ball(s) => s.cast_local_ray(ray, max_toi, solid),
            Self::Hull(s) => s.cast_local_ray(ray, max_toi, solid),
            Self::Facade(s) => s.cast_local_ray(ray, max_toi, solid),
        }
    }

    #[inline]
    fn cast_local_with_normal(
        &self,
        ray: &Ray,
        max_toi: f32,
        solid: bool,
    ) -> Option<RayIntersection> {
        match self {
            Self::Cuboid(s) => s.cast_local_ray_and_get_normal(ray, max_toi, solid),
            Self::Ball(s) => s.cast_local_ray_and_get_normal(ray, max_toi, solid),
            Self::Hull(s) => s.cast_local_ray_and_get_normal(ray, max_toi, solid),
            Self::Facade(s) => s.cast_local_ray_and_get_normal(ray, max_toi, solid),
        }
    }

    fn local_aabb(&self) -> Aabb {
        use rapier3d::parry::shape::Shape;
        match self {
            Self::Cuboid(s) => s.compute_local_aabb(),
            Self::Ball(s) => s.compute_local_aabb(),
            Self::Hull(s) => s.compute_local_aabb(),
            Self::Facade(s) => s.compute_local_aabb(),
        }
    }
}

/// A piece placed in the world.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct GridPiece {
    solid: Solid,
    centre: Vector,
    /// (cos, sin) of the yaw about z.
    yaw_cos_sin: (f32, f32),
    /// World AABB.
    aabb: Aabb,
}

impl GridPiece {
    /// `piece` placed at its centre and yaw, or `None` for a degenerate hull.
    pub(crate) fn new(piece: &Piece) -> Option<Self> {
        let solid = Solid::of(piece)?;
        let [x, y, z] = piece.centre_m;
        let centre = Vector::new(x, y, z);
        let (s, c) = piece.yaw_rad.sin_cos();
        let local = solid.local_aabb();
        // The world AABB of the yawed local box: its eight corners.
        let (mut lo, mut hi) = (Vector::splat(f32::MAX), Vector::splat(f32::MIN));
        for k in 0..8 {
            let p = Vector::new(
                if k & 1 == 0 {
                    local.mins.x
                } else {
                    local.maxs.x
                },
                if k & 2 == 0 {
                    local.mins.y
                } else {
                    local.maxs.y
                },
                if k & 4 == 0 {
                    local.mins.z
                } else {
                    local.maxs.z
                },
            );
            let w = centre + Vector::new(c * p.x - s * p.y, s * p.x + c * p.y, p.z);
            lo = lo.min(w);
            hi = hi.max(w);
        }
        Some(Self {
            solid,
            centre,
            yaw_cos_sin: (c, s),
            aabb: Aabb::new(lo, hi),
        })
    }

    /// World AABB.
    pub(crate) fn aabb(&self) -> &Aabb {
        &self.aabb
    }

    /// The piece as a world box for the static truth: a box piece exactly (centre, full size,
    /// yaw, `true`), any other solid as its world AABB (yaw 0, `false`).
    pub(crate) fn world_box(&self) -> ([f64; 3], [f64; 3], f64, bool) {
        if let Solid::Cuboid(cuboid) = &self.solid {
            let (c, s) = self.yaw_cos_sin;
            let h = cuboid.half_extents;
            return (
                [self.centre.x, self.centre.y, self.centre.z].map(f64::from),
                [h.x, h.y, h.z].map(|v| 2.0 * f64::from(v)),
                f64::from(s).atan2(f64::from(c)),
                true,
            );
        }
        let (lo, hi) = (self.aabb.mins, self.aabb.maxs);
        (
            [lo.x + hi.x, lo.y + hi.y, lo.z + hi.z].map(|v| f64::from(v) / 2.0),
            [hi.x - lo.x, hi.y - lo.y, hi.z - lo.z].map(f64::from),
            0.0,
            false,
        )
    }

    /// The world ray in the piece's frame.
    #[inline]
    fn to_local(&self, ray: &Ray) -> Ray {
        let (c, s) = self.yaw_cos_sin;
        let o = ray.origin - self.centre;
        let d = ray.dir;
        Ray::new(
            Vector::new(c * o.x + s * o.y, c * o.y - s * o.x, o.z),
            Vector::new(c * d.x + s * d.y, c * d.y - s * d.x, d.z),
        )
    }

    /// Time of impact of the world ray `ray` within `max_toi`, if it hits the solid.
    #[inline]
    pub(crate) fn cast_solid(&self, ray: &Ray, max_toi: f32) -> Option<f32> {
        self.solid.cast_local(&self.to_local(ray), max_toi, true)
    }

    /// Time of impact, world normal and feature of the world ray `ray`, as the solid reports
    /// them (`solid = false`: a ray starting inside finds where it leaves).
    pub(crate) fn cast_with_normal(
        &self,
        ray: &Ray,
        max_toi: f32,
        solid: bool,
    ) -> Option<RayIntersection> {
        let mut hit = self.cast_with_local_normal(ray, max_toi, solid)?;
        hit.normal = self.world_normal(hit.normal);
        Some(hit)
    }

    /// [`GridPiece::cast_with_normal`] with the normal left in the piece's frame (a cell walk
    /// turns only the first hit's normal into the world frame, with [`GridPiece::world_normal`]).
    #[inline]
    pub(crate) fn cast_with_local_normal(
        &self,
        ray: &Ray,
        max_toi: f32,
        solid: bool,
    ) -> Option<RayIntersection> {
        self.solid
            .cast_local_with_normal(&self.to_local(ray), max_toi, solid)
    }

    /// A normal in the piece's frame turned into the world frame.
    #[inline]
    pub(crate) fn world_normal(&self, n: Vector) -> Vector {
        let (c, s) = self.yaw_cos_sin;
        Vector::new(c * n.x - s * n.y, s * n.x + c * n.y, n.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::Material;
    use patchflow_dataset::SemanticClass;
    use rapier3d::prelude::Pose;

    #[test]
    fn a_yawed_piece_is_hit_where_parry_hits_the_same_shape_at_the_same_pose() {
        let piece = Piece {
            shape: PieceShape::Cuboid([2.0, 0.8, 0.7]),
            centre_m: [10.0, 3.0, 0.7],
            yaw_rad: 0.6,
            semantic: SemanticClass::Car,
            reflectivity: 0.5,
            material: Material::SOLID,
        };
        let ours = GridPiece::new(&piece).unwrap();
        let shape = piece.shared_shape().unwrap();
        let pose = Pose::new(Vector::new(10.0, 3.0, 0.7), Vector::new(0.0, 0.0, 0.6));
        let mut hits = 0;
        for k in 0..400 {
            let a = k as f32 * 0.01 - 2.0;
            let dir = Vector::new(a.cos(), a.sin(), -0.05).normalize();
            let ray = Ray::new(Vector::new(0.0, 0.0, 1.0), dir);
            let got = ours.cast_solid(&ray, 50.0);
            let expected = shape.cast_ray(&pose, &ray, 50.0, true);
            assert_eq!(got.is_some(), expected.is_some(), "ray {k}");
            if let (Some(g), Some(e)) = (got, expected) {
                hits += 1;
                assert!((g - e).abs() < 1e-4, "ray {k}: {g} vs {e}");
                let normal = ours.cast_with_normal(&ray, 50.0, true).unwrap().normal;
                let parry = shape.cast_ray_and_get_normal(&pose, &ray, 50.0, true);
                assert!((normal - parry.unwrap().normal).length() < 1e-4);
            }
        }
        assert!(hits > 20, "{hits} hits");
    }
}
