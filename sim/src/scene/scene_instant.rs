//! The moving part of a scene frozen at one instant, computed from the trajectories alone: the
//! collider pose of every mover (ego car first, then the actors), each actor's motion state and
//! its surface placed there. A rolling-shutter sweep takes one per azimuth block up front and
//! casts every block against its own instant through one shared ray-cast tree, so the blocks
//! need no Rapier step, tree refit or thread barrier between them.

use rapier3d::prelude::{ColliderSet, Pose, RigidBodySet};

use super::{SceneActor, Surface};
use crate::motion::MotionState;

/// The movers of a scene at one instant.
#[derive(Debug, Clone)]
pub struct SceneInstant {
    /// Collider pose of every mover, world frame: index 0 the ego car, `1 + i` actor `i`.
    mover_poses: Vec<Pose>,
    /// Motion state of every actor, in actor order.
    actor_states: Vec<MotionState>,
    /// Surface of every actor placed at the instant, in actor order.
    actor_surfaces: Vec<Option<Surface>>,
}

impl SceneInstant {
    /// The movers at `t_secs`. A collider's pose is its body's pose times its pose relative to
    /// the body, exactly as Rapier composes it when the body is moved there; `surfaces` are the
    /// scene's surface table and `actor_surfaces` the index of each actor's surface in it.
    pub(super) fn new(
        t_secs: f64,
        (ego, actors): (&SceneActor, &[SceneActor]),
        (bodies, colliders): (&RigidBodySet, &ColliderSet),
        surfaces: &[Surface],
        actor_surfaces: &[usize],
    ) -> Self {
        let actor_states: Vec<MotionState> = actors
            .iter()
            .map(|a| a.trajectory.state_at(t_secs))
            .collect();
        let ego_state = ego.trajectory.state_at(t_secs);
        let collider_pose = |actor: &SceneActor, state: &MotionState| {
            let body_pose = actor.pose_of(state);
            let relative = bodies
                .get(actor.body)
                .and_then(|b| b.colliders().first())
                .and_then(|&h| colliders.get(h))
                .and_then(|c| c.position_wrt_parent().copied())
                .unwrap_or(Pose::IDENTITY);
            body_pose * relative
        };
        let mover_poses = std::iter::once(collider_pose(ego, &ego_state))
            .chain(
                actors
                    .iter()
                    .zip(&actor_states)
                    .map(|(a, s)| collider_pose(a, s)),
            )
            .collect();
        let actor_surfaces = actors
            .iter()
            .zip(&actor_states)
            .zip(actor_surfaces)
            .map(|((actor, state), &i)| {
                let mut surface = *surfaces.get(i)?;
                surface.place(actor.pose_of(state).translation, state.yaw_rad as f32);
                Some(surface)
            })
            .collect();
        Self {
            mover_poses,
            actor_states,
            actor_surfaces,
        }
    }

    /// Motion state of every actor at the instant, in actor order.
    pub fn actor_states(&self) -> &[MotionState] {
        &self.actor_states
    }

    /// Collider pose of mover `k` (0 the ego car, `1 + i` actor `i`), world frame.
    #[inline]
    pub(super) fn mover_pose(&self, k: usize) -> Option<&Pose> {
        self.mover_poses.get(k)
    }

    /// Surface of actor `i` placed at the instant.
    #[inline]
    pub(super) fn actor_surface(&self, i: usize) -> Option<&Surface> {
        self.actor_surfaces.get(i)?.as_ref()
    }
}
