//! The parry `Shape` boilerplate the world's custom shapes (street, plane hull, façade) share:
//! each says what differs (its box, its CCD thicknesses, whether it is convex) by implementing
//! [`CustomShape`], and [`impl_parry_shape!`] writes the `Shape` impl around it. A blanket impl
//! is not allowed for a foreign trait, hence the macro.

use rapier3d::parry::bounding_volume::Aabb;
use rapier3d::prelude::Real;

/// What a custom shape of the world says about itself; the rest of `Shape` is the same for all.
pub(crate) trait CustomShape {
    /// The shape's box in its own frame.
    fn local_aabb(&self) -> Aabb;
    /// Thickness for continuous collision detection.
    fn ccd_thickness_m(&self) -> Real;
    /// Angular thickness for continuous collision detection.
    fn ccd_angular_thickness_rad(&self) -> Real;
    /// Whether the shape is convex.
    fn convex(&self) -> bool {
        false
    }
}

/// `impl Shape for $ty` from its [`CustomShape`]: no scaling, no mass, `ShapeType::Custom`.
macro_rules! impl_parry_shape {
    ($ty:ty) => {
        impl rapier3d::parry::shape::Shape for $ty {
            fn compute_local_aabb(&self) -> rapier3d::parry::bounding_volume::Aabb {
                $crate::world::custom_shape::CustomShape::local_aabb(self)
            }

            fn compute_local_bounding_sphere(
                &self,
            ) -> rapier3d::parry::bounding_volume::BoundingSphere {
                $crate::world::custom_shape::CustomShape::local_aabb(self).bounding_sphere()
            }

            fn clone_dyn(&self) -> Box<dyn rapier3d::parry::shape::Shape> {
                Box::new(self.clone())
            }

            fn scale_dyn(
                &self,
                _scale: rapier3d::prelude::Vector,
                _num_subdivisions: u32,
            ) -> Option<Box<dyn rapier3d::parry::shape::Shape>> {
                None
            }

            fn mass_properties(
                &self,
                _density: rapier3d::prelude::Real,
            ) -> rapier3d::parry::mass_properties::MassProperties {
                rapier3d::parry::mass_properties::MassProperties::default()
            }

            fn shape_type(&self) -> rapier3d::parry::shape::ShapeType {
                rapier3d::parry::shape::ShapeType::Custom
            }

            fn as_typed_shape(&self) -> rapier3d::parry::shape::TypedShape<'_> {
                rapier3d::parry::shape::TypedShape::Custom(self)
            }

            fn ccd_thickness(&self) -> rapier3d::prelude::Real {
                $crate::world::custom_shape::CustomShape::ccd_thickness_m(self)
            }

            fn ccd_angular_thickness(&self) -> rapier3d::prelude::Real {
                $crate::world::custom_shape::CustomShape::ccd_angular_thickness_rad(self)
            }

            fn is_convex(&self) -> bool {
                $crate::world::custom_shape::CustomShape::convex(self)
            }
        }
    };
}

pub(crate) use impl_parry_shape;
