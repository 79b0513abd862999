//! The street world's ground as a parry shape, so it is an ordinary Rapier collider: every ray
//! cast through the scene (the lidar's and Rapier's own `QueryPipeline::cast_ray`) meets it
//! through its [`RayCast`] implementation, the two-level walk of [`GroundField::cast`] (parry's
//! `HeightField` tests two triangles in every cell a grazing ray passes over, which costs a
//! sweep several times over). It never takes part in contacts: only fixed and kinematic bodies
//! exist, and Rapier computes no contacts between those.

use std::sync::Arc;

use rapier3d::parry::bounding_volume::{Aabb, BoundingSphere};
use rapier3d::parry::mass_properties::MassProperties;
use rapier3d::parry::query::{PointProjection, PointQuery, Ray, RayCast, RayIntersection};
use rapier3d::parry::shape::{FeatureId, Shape, ShapeType, TypedShape};
use rapier3d::prelude::{Real, Vector};

use super::GroundField;

/// The ground field as a shape (its local frame is the world frame).
#[derive(Debug, Clone)]
pub struct GroundShape(pub Arc<GroundField>);

impl RayCast for GroundShape {
    #[inline]
    fn cast_local_ray(&self, ray: &Ray, max_time_of_impact: Real, _solid: bool) -> Option<Real> {
        let (o, d) = (ray.origin, ray.dir);
        self.0
            .cast([o.x, o.y, o.z], [d.x, d.y, d.z], max_time_of_impact)
            .map(|(t, _)| t)
    }

    fn cast_local_ray_and_get_normal(
        &self,
        ray: &Ray,
        max_time_of_impact: Real,
        _solid: bool,
    ) -> Option<RayIntersection> {
        let (o, d) = (ray.origin, ray.dir);
        let (t, cell) = self
            .0
            .cast([o.x, o.y, o.z], [d.x, d.y, d.z], max_time_of_impact)?;
        let p = o + d * t;
        let n = self.0.normal_at(p.x, p.y);
        Some(RayIntersection::new(
            t,
            Vector::new(n[0], n[1], n[2]),
            FeatureId::Face(cell),
        ))
    }
}

impl PointQuery for GroundShape {
    fn project_local_point(&self, pt: Vector, _solid: bool) -> PointProjection {
        let h = self.0.height_at(pt.x, pt.y);
        PointProjection::new(pt.z < h, Vector::new(pt.x, pt.y, h))
    }

    fn project_local_point_and_get_feature(&self, pt: Vector) -> (PointProjection, FeatureId) {
        (self.project_local_point(pt, false), FeatureId::Unknown)
    }
}

impl Shape for GroundShape {
    fn compute_local_aabb(&self) -> Aabb {
        let (lo, hi) = self.0.bounds();
        Aabb::new(
            Vector::new(lo[0], lo[1], lo[2]),
            Vector::new(hi[0], hi[1], hi[2]),
        )
    }

    fn compute_local_bounding_sphere(&self) -> BoundingSphere {
        self.compute_local_aabb().bounding_sphere()
    }

    fn clone_dyn(&self) -> Box<dyn Shape> {
        Box::new(self.clone())
    }

    fn scale_dyn(&self, _scale: Vector, _num_subdivisions: u32) -> Option<Box<dyn Shape>> {
        None
    }

    fn mass_properties(&self, _density: Real) -> MassProperties {
        MassProperties::default()
    }

    fn shape_type(&self) -> ShapeType {
        ShapeType::Custom
    }

    fn as_typed_shape(&self) -> TypedShape<'_> {
        TypedShape::Custom(self)
    }

    fn ccd_thickness(&self) -> Real {
        0.1
    }

    fn ccd_angular_thickness(&self) -> Real {
        0.1
    }
}
