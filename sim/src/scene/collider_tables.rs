//! The collider tables while a scene is being built: Rapier bodies and colliders plus the surface
//! each collider stands for, and a dense collider-index → surface-index map so the lidar looks a
//! hit up with one array read instead of going through the Rapier collider.

use patchflow_dataset::SemanticClass;
use rapier3d::prelude::*;

use super::{SceneActor, Surface};
use crate::motion::Trajectory;
use crate::scenario::ActorConfig;

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

    /// Adds a kinematic body with a cuboid collider for an actor (or the ego car, `index = None`);
    /// returns the actor and the index of its surface. An error names the bad field.
    pub(super) fn add_actor(
        &mut self,
        config: &ActorConfig,
        id: u16,
        index: Option<usize>,
    ) -> std::result::Result<(SceneActor, usize), String> {
        let size = config.size_m.unwrap_or([4.5, 1.8, 1.5]);
        let trajectory = Trajectory::from_config(config)
            .map_err(|(field, reason)| format!("{}.{field}: {reason}", config.name))?;
        let body = self
            .bodies
            .insert(RigidBodyBuilder::kinematic_position_based().build());
        let surface = Surface::new(
            config.class.semantic(false),
            index,
            [
                size[0] as f32 / 2.0,
                size[1] as f32 / 2.0,
                size[2] as f32 / 2.0,
            ],
            config.reflectivity.unwrap_or(0.5) as f32,
        );
        let h = surface.half_extents_m;
        let collider = ColliderBuilder::cuboid(h[0], h[1], h[2])
            .user_data(self.surfaces.len() as u128)
            .build();
        let handle = self
            .colliders
            .insert_with_parent(collider, body, &mut self.bodies);
        let surface_index = self.register(handle, surface);
        let actor = SceneActor {
            id,
            name: config.name.clone(),
            class: config.class,
            target: config.target,
            size_m: size,
            trajectory,
            body,
        };
        Ok((actor, surface_index))
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
