//! One static or moving part of the procedural world before it becomes a Rapier collider: its
//! shape, where it sits (relative to the world or to its actor's box centre), its label,
//! reflectivity and material.

use patchflow_dataset::SemanticClass;
use rapier3d::prelude::SharedShape;

use super::Material;
use super::facade_shape::{FacadeGrid, FacadeShape};
use super::plane_hull::PlaneHull;

/// The geometry of a piece, in its own frame (z up; a cylinder's axis along its local y).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum PieceShape {
    /// A box with these half extents.
    Cuboid([f32; 3]),
    /// A ball of this radius.
    Ball(f32),
    /// A cylinder (an octagonal prism): half height along local y, radius.
    Cylinder(f32, f32),
    /// An upright cylinder (an octagonal prism, axis along z): half height, radius.
    Column(f32, f32),
    /// The convex hull of these points.
    Hull(Vec<[f32; 3]>),
    /// A building with recessed windows: half extents and façade grid.
    Facade([f32; 3], FacadeGrid),
}

/// A part of the world.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Piece {
    pub shape: PieceShape,
    /// Centre of the shape's frame: world frame for static pieces, the actor's box frame for parts.
    pub centre_m: [f32; 3],
    /// Yaw of the shape's frame about z, radians.
    pub yaw_rad: f32,
    pub semantic: SemanticClass,
    pub reflectivity: f32,
    pub material: Material,
}

impl Piece {
    /// A yawed box standing on `base_z_m`, `size` = (length, width, height).
    pub(crate) fn block(
        xy: [f64; 2],
        base_z_m: f64,
        size: [f64; 3],
        yaw_rad: f64,
        semantic: SemanticClass,
        reflectivity: f64,
    ) -> Self {
        Self {
            shape: PieceShape::Cuboid([
                size[0] as f32 / 2.0,
                size[1] as f32 / 2.0,
                size[2] as f32 / 2.0,
            ]),
            centre_m: [
                xy[0] as f32,
                xy[1] as f32,
                (base_z_m + size[2] / 2.0) as f32,
            ],
            yaw_rad: yaw_rad as f32,
            semantic,
            reflectivity: reflectivity as f32,
            material: Material::SOLID,
        }
    }

    /// With another material.
    pub(crate) fn with_material(mut self, material: Material) -> Self {
        self.material = material;
        self
    }

    /// True for a box, whose normal the lidar finds analytically.
    pub(crate) fn is_box(&self) -> bool {
        matches!(self.shape, PieceShape::Cuboid(_))
    }

    /// The parry shape, or `None` for a degenerate hull.
    pub(crate) fn shared_shape(&self) -> Option<SharedShape> {
        match &self.shape {
            PieceShape::Cuboid(h) => Some(SharedShape::cuboid(h[0], h[1], h[2])),
            PieceShape::Ball(r) => Some(SharedShape::ball(*r)),
            PieceShape::Cylinder(h, r) => PlaneHull::prism(1, *h, *r).map(SharedShape::new),
            PieceShape::Column(h, r) => PlaneHull::prism(2, *h, *r).map(SharedShape::new),
            PieceShape::Hull(points) => PlaneHull::from_points(points).map(SharedShape::new),
            PieceShape::Facade(half, grid) => {
                Some(SharedShape::new(FacadeShape::new(*half, *grid)))
            }
        }
    }

    /// Extra rotation of the shape in its frame (none: every shape is built upright).
    pub(crate) fn tilt_rad(&self) -> [f32; 3] {
        [0.0; 3]
    }
}
