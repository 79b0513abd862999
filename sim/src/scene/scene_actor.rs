//! One moving actor (or the ego car) in the scene: its identity, box and motion, and the
//! kinematic body that carries its collider.

use std::sync::Arc;

use patchflow_dataset::ActorClass;
use rapier3d::prelude::{Pose, RigidBodyHandle, Vector};

use crate::motion::{MotionState, Trajectory};
use crate::world::GroundField;

/// One moving actor (or the ego car) in the scene.
#[derive(Debug, Clone)]
pub struct SceneActor {
    /// Instance id in labels and object truth (never 0; the ego car has 0 and is never hit).
    pub id: u16,
    /// Name from the scenario.
    pub name: String,
    /// Class.
    pub class: ActorClass,
    /// True for the benchmark target.
    pub target: bool,
    /// Length, width, height, metres.
    pub size_m: [f64; 3],
    /// Its motion.
    pub trajectory: Trajectory,
    /// The kinematic body carrying its collider.
    pub body: RigidBodyHandle,
    /// The street world's ground it stands on (`None`: the flat road, z = 0).
    pub(crate) ground: Option<Arc<GroundField>>,
}

impl SceneActor {
    /// Height of the box centre at world `(x, y)`: the box stands on the ground under its centre
    /// (the street world's ground, or the flat road at z = 0).
    pub fn centre_z_m(&self, x_m: f64, y_m: f64) -> f64 {
        let ground_m = self
            .ground
            .as_ref()
            .map_or(0.0, |g| f64::from(g.height_at(x_m as f32, y_m as f32)));
        ground_m + self.size_m[2] / 2.0
    }

    /// Rapier pose of the box centre for a motion state.
    pub fn pose_of(&self, state: &MotionState) -> Pose {
        let [x, y] = state.position_m;
        Pose::new(
            Vector::new(x as f32, y as f32, self.centre_z_m(x, y) as f32),
            Vector::new(0.0, 0.0, state.yaw_rad as f32),
        )
    }
}
