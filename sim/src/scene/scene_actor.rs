//! One moving actor (or the ego car) in the scene: its identity, box and motion, and the
//! kinematic body that carries its collider.

use patchflow_dataset::ActorClass;
use rapier3d::prelude::{Pose, RigidBodyHandle, Vector};

use crate::motion::{MotionState, Trajectory};

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
}

impl SceneActor {
    /// Rapier pose of the box centre for a motion state.
    pub fn pose_of(&self, state: &MotionState) -> Pose {
        Pose::new(
            Vector::new(
                state.position_m[0] as f32,
                state.position_m[1] as f32,
                (self.size_m[2] / 2.0) as f32,
            ),
            Vector::new(0.0, 0.0, state.yaw_rad as f32),
        )
    }
}
