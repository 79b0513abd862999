//! The moving part of a scene frozen at one instant, computed from the trajectories alone: the
//! pose of every moving collider (the ego car's first, then each actor's parts), each actor's
//! motion state and every moving collider's surface placed there. A rolling-shutter sweep takes
//! one per azimuth block up front and casts every block against its own instant through one
//! shared ray-cast tree, so the blocks need no Rapier step, tree refit or thread barrier between
//! them.

use rapier3d::prelude::Pose;

use super::collider_tables::MoverPart;
use super::{SceneActor, Surface};
use crate::motion::MotionState;

/// The movers of a scene at one instant.
#[derive(Debug, Clone)]
pub struct SceneInstant {
    /// Pose of every moving collider, world frame, in mover order.
    mover_poses: Vec<Pose>,
    /// Motion state of every actor, in actor order.
    actor_states: Vec<MotionState>,
    /// Surface of every moving collider placed at the instant, in mover order.
    mover_surfaces: Vec<Option<Surface>>,
}

impl SceneInstant {
    /// The movers at `t_secs`. A collider's pose is its body's pose times its pose relative to
    /// the body, exactly as Rapier composes it when the body is moved there; `surfaces` is the
    /// scene's surface table.
    pub(super) fn new(
        t_secs: f64,
        (ego, actors): (&SceneActor, &[SceneActor]),
        movers: &[MoverPart],
        surfaces: &[Surface],
    ) -> Self {
        let actor_states: Vec<MotionState> = actors
            .iter()
            .map(|a| a.trajectory.state_at(t_secs))
            .collect();
        let ego_state = ego.trajectory.state_at(t_secs);
        let mut mover_poses = Vec::with_capacity(movers.len());
        let mut mover_surfaces = Vec::with_capacity(movers.len());
        for part in movers {
            let (actor, state) = match part.actor {
                Some(i) => (&actors[i], &actor_states[i]),
                None => (ego, &ego_state),
            };
            let pose = actor.pose_of(state) * part.relative;
            mover_poses.push(pose);
            mover_surfaces.push(surfaces.get(part.surface).map(|s| {
                let mut surface = *s;
                surface.place(pose.translation, state.yaw_rad as f32);
                surface
            }));
        }
        Self {
            mover_poses,
            actor_states,
            mover_surfaces,
        }
    }

    /// Motion state of every actor at the instant, in actor order.
    pub fn actor_states(&self) -> &[MotionState] {
        &self.actor_states
    }

    /// Pose of moving collider `k`, world frame.
    #[inline]
    pub(super) fn mover_pose(&self, k: usize) -> Option<&Pose> {
        self.mover_poses.get(k)
    }

    /// Surface of moving collider `k` placed at the instant.
    #[inline]
    pub(super) fn mover_surface(&self, k: usize) -> Option<&Surface> {
        self.mover_surfaces.get(k)?.as_ref()
    }
}
