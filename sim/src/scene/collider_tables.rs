//! The collider tables while a scene is being built: Rapier bodies and colliders plus the surface
//! each collider stands for, and a dense collider-index → surface-index map so the lidar looks a
//! hit up with one array read instead of going through the Rapier collider.

use patchflow_dataset::SemanticClass;
use rapier3d::prelude::*;

use std::sync::Arc;

use super::{SceneActor, Surface, SurfaceKind};
use crate::motion::Trajectory;
use crate::scenario::ActorConfig;
use crate::world::{GridPiece, GroundField, Piece, PieceGrid, StreetShape, body_parts};

/// The street world's collider: its shape, its arena index, and where its surfaces start.
#[derive(Debug, Clone)]
pub(super) struct StreetCollider {
    pub shape: Arc<StreetShape>,
    /// Arena index of the collider.
    pub collider: u32,
    /// Surface of the ground.
    pub ground_surface: u32,
    /// Surface of piece 0 (piece `k` has `first_piece_surface + k`).
    pub first_piece_surface: u32,
}

/// One moving collider: whose it is (`None`: the ego car), its surface and its pose on its body.
#[derive(Debug, Clone, Copy)]
pub(super) struct MoverPart {
    pub handle: ColliderHandle,
    pub actor: Option<usize>,
    pub surface: usize,
    pub relative: Pose,
}

/// No surface for this collider index (never produced by a scene built here).
const NO_SURFACE: u32 = u32::MAX;

/// Bodies, colliders and surfaces of a scene under construction.
#[derive(Default)]
pub(super) struct ColliderTables {
    pub(super) bodies: RigidBodySet,
    pub(super) colliders: ColliderSet,
    pub(super) surfaces: Vec<Surface>,
    /// Surface index by collider arena index.
    pub(super) surface_of_collider: Vec<u32>,
    /// The moving colliders: the ego car's first, then each actor's parts in actor order.
    pub(super) movers: Vec<MoverPart>,
    /// The street world's ground, once added: every actor added after it stands on it.
    street_ground: Option<Arc<GroundField>>,
}

impl ColliderTables {
    /// Adds a fixed cuboid collider at `pose` (yawed about z only) for `surface`.
    pub(super) fn add_fixed(&mut self, mut surface: Surface, pose: Pose, yaw_rad: f32) {
        let h = surface.half_extents_m;
        surface.place(pose.translation, yaw_rad);
        let collider = ColliderBuilder::cuboid(h[0], h[1], h[2])
            .position(pose)
            .user_data(self.surfaces.len() as u128)
            .build();
        let handle = self.colliders.insert(collider);
        self.register(handle, surface);
    }

    /// The surface of a piece of the street world, placed where it stands.
    fn piece_surface(piece: &Piece) -> Surface {
        let h = match piece.shape {
            crate::world::PieceShape::Cuboid(h) => h,
            _ => [0.0; 3],
        };
        let kind = if piece.is_box() {
            SurfaceKind::Box
        } else {
            SurfaceKind::Shape
        };
        let mut surface =
            Surface::new(piece.semantic, None, h, piece.reflectivity).with(kind, piece.material);
        let [x, y, z] = piece.centre_m;
        surface.place(Vector::new(x, y, z), piece.yaw_rad);
        surface
    }

    /// Adds the street world (its ground, if not flat, and every static piece) as one fixed
    /// collider whose shape casts rays through the ground and the piece grid, with the surface
    /// of its ground and of every piece. Returns the street world.
    pub(super) fn add_street(
        &mut self,
        ground: Option<Arc<GroundField>>,
        pieces: &[Piece],
    ) -> StreetCollider {
        let ground_surface = Surface::new(SemanticClass::Road, None, [0.0; 3], 0.15)
            .with(SurfaceKind::Ground, super::Material::SOLID);
        let (placed, surfaces): (Vec<GridPiece>, Vec<Surface>) = pieces
            .iter()
            .filter_map(|p| Some((GridPiece::new(p)?, Self::piece_surface(p))))
            .unzip();
        self.street_ground = ground.clone();
        let shape = Arc::new(StreetShape::new(ground, PieceGrid::new(placed)));
        let collider = ColliderBuilder::new(SharedShape(shape.clone() as Arc<dyn Shape>))
            .user_data(self.surfaces.len() as u128)
            .build();
        let handle = self.colliders.insert(collider);
        let ground_surface = self.register(handle, ground_surface) as u32;
        let first_piece_surface = self.surfaces.len() as u32;
        self.surfaces.extend(surfaces);
        StreetCollider {
            shape,
            collider: handle.into_raw_parts().0,
            ground_surface,
            first_piece_surface,
        }
    }

    /// Adds a kinematic body for an actor (or the ego car, `index = None`): one cuboid collider,
    /// or with `shapes` one collider per part of its class's shape (the ego car stays a box: its
    /// own lidar never sees it), its side glass from `belt_m` up where the fleet drew it.
    /// Returns the actor. An error names the bad field.
    pub(super) fn add_actor(
        &mut self,
        config: &ActorConfig,
        (id, index): (u16, Option<usize>),
        shapes: bool,
        belt_m: Option<f64>,
    ) -> std::result::Result<SceneActor, String> {
        let size = config.size_m.unwrap_or([4.5, 1.8, 1.5]);
        let trajectory = config
            .trajectory()
            .map_err(|(field, reason)| format!("{}.{field}: {reason}", config.name))?;
        let body = self
            .bodies
            .insert(RigidBodyBuilder::kinematic_position_based().build());
        let reflectivity = config.reflectivity.unwrap_or(0.5) as f32;
        if shapes
            && index.is_some()
            && let Some(mesh) = &config.mesh_data
        {
            // The user's own model: one triangle-mesh collider filling the actor's box.
            let vertices = mesh.fitted_to(size).into_iter().map(Vector::from).collect();
            let shape = SharedShape::trimesh(vertices, mesh.triangles.clone())
                .map_err(|e| format!("{}.mesh: {}: {e}", config.name, mesh.source.display()))?;
            let mut surface =
                Surface::new(config.class.semantic(false), index, [0.0; 3], reflectivity)
                    .with(SurfaceKind::Shape, super::Material::SOLID);
            surface.mover = Some(self.movers.len() as u32);
            let collider = ColliderBuilder::new(shape)
                .user_data(self.surfaces.len() as u128)
                .build();
            let handle = self
                .colliders
                .insert_with_parent(collider, body, &mut self.bodies);
            let surface_index = self.register(handle, surface);
            self.movers.push(MoverPart {
                handle,
                actor: index,
                surface: surface_index,
                relative: Pose::IDENTITY,
            });
            return Ok(self.scene_actor(config, id, size, trajectory, body));
        }
        let parts = if shapes && index.is_some() {
            body_parts(config.class, size, belt_m, reflectivity)
        } else {
            vec![Piece::block(
                [0.0; 2],
                -size[2] / 2.0,
                size,
                0.0,
                config.class.semantic(false),
                f64::from(reflectivity),
            )]
        };
        for part in parts {
            let Some(shape) = part.shared_shape() else {
                continue;
            };
            let [x, y, z] = part.centre_m;
            let relative =
                Pose::translation(x, y, z) * Pose::new(Vector::ZERO, Vector::from(part.tilt_rad()));
            let h = match part.shape {
                crate::world::PieceShape::Cuboid(h) => h,
                _ => [0.0; 3],
            };
            let kind = if part.is_box() {
                SurfaceKind::Box
            } else {
                SurfaceKind::Shape
            };
            let mut surface =
                Surface::new(config.class.semantic(false), index, h, part.reflectivity)
                    .with(kind, part.material);
            surface.mover = Some(self.movers.len() as u32);
            let mut builder = ColliderBuilder::new(shape).user_data(self.surfaces.len() as u128);
            if relative != Pose::IDENTITY {
                builder = builder.position(relative);
            }
            let handle = self
                .colliders
                .insert_with_parent(builder.build(), body, &mut self.bodies);
            let surface_index = self.register(handle, surface);
            self.movers.push(MoverPart {
                handle,
                actor: index,
                surface: surface_index,
                relative,
            });
        }
        Ok(self.scene_actor(config, id, size, trajectory, body))
    }

    /// The scene's record of an actor whose colliders are in place: its truth is its box.
    fn scene_actor(
        &self,
        config: &ActorConfig,
        id: u16,
        size: [f64; 3],
        trajectory: Trajectory,
        body: RigidBodyHandle,
    ) -> SceneActor {
        SceneActor {
            id,
            name: config.name.clone(),
            class: config.class,
            target: config.target,
            size_m: size,
            trajectory,
            body,
            ground: self.street_ground.clone(),
        }
    }

    /// The ground slab's surface: a road box whose top face is z = 0.
    pub(super) fn ground(half_m: f32, reflectivity: f32) -> Surface {
        Surface::new(
            SemanticClass::Road,
            None,
            [half_m, half_m, 0.5],
            reflectivity,
        )
    }

    fn register(&mut self, handle: ColliderHandle, surface: Surface) -> usize {
        let index = self.surfaces.len();
        let slot = handle.into_raw_parts().0 as usize;
        if self.surface_of_collider.len() <= slot {
            self.surface_of_collider.resize(slot + 1, NO_SURFACE);
        }
        self.surface_of_collider[slot] = index as u32;
        self.surfaces.push(surface);
        index
    }
}
