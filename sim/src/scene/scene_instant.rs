//! The moving part of a scene frozen at one instant, computed from the trajectories alone: the
//! pose and world AABB of every moving collider (the ego car's first, then each actor's parts),
//! each actor's motion state and every moving collider's surface placed there. A rolling-shutter sweep takes
//! one per azimuth block up front and casts every block against its own instant through one
//! shared ray-cast tree, so the blocks need no Rapier step, tree refit or thread barrier between
//! them.

use rapier3d::parry::bounding_volume::Aabb;
use rapier3d::prelude::{ColliderSet, Pose, Ray, Vector};

use super::collider_tables::MoverPart;
use super::{SceneActor, Surface};
use crate::motion::MotionState;

/// Margin around a mover's box in [`SceneInstant::may_hit`], metres (rays are unit).
const BOX_MARGIN_M: f32 = 0.01;

/// The movers of a scene at one instant.
#[derive(Debug, Clone)]
pub struct SceneInstant {
    /// Pose of every moving collider, world frame, in mover order.
    mover_poses: Vec<Pose>,
    /// World AABB of every moving collider at its pose, in mover order (an empty box for a
    /// collider the set does not hold).
    mover_boxes: Vec<Aabb>,
    /// Motion state of every actor, in actor order.
    actor_states: Vec<MotionState>,
    /// Surface of every moving collider placed at the instant, in mover order.
    mover_surfaces: Vec<Option<Surface>>,
}

impl SceneInstant {
    /// The movers at `t_secs`. A collider's pose is its body's pose times its pose relative to
    /// the body, exactly as Rapier composes it when the body is moved there; `surfaces` is the
    /// scene's surface table, `colliders` its colliders.
    pub(super) fn new(
        t_secs: f64,
        (ego, actors): (&SceneActor, &[SceneActor]),
        movers: &[MoverPart],
        (surfaces, colliders): (&[Surface], &ColliderSet),
    ) -> Self {
        let actor_states: Vec<MotionState> = actors
            .iter()
            .map(|a| a.trajectory.state_at(t_secs))
            .collect();
        let ego_state = ego.trajectory.state_at(t_secs);
        let mut mover_poses = Vec::with_capacity(movers.len());
        let mut mover_surfaces = Vec::with_capacity(movers.len());
        let mut mover_boxes = Vec::with_capacity(movers.len());
        for part in movers {
            let (actor, state) = match part.actor {
                Some(i) => (&actors[i], &actor_states[i]),
                None => (ego, &ego_state),
            };
            let pose = actor.pose_of(state) * part.relative;
            mover_poses.push(pose);
            mover_boxes.push(
                colliders
                    .get(part.handle)
                    .map_or_else(Aabb::new_invalid, |c| c.shape().compute_aabb(&pose)),
            );
            mover_surfaces.push(surfaces.get(part.surface).map(|s| {
                let mut surface = *s;
                surface.place(pose.translation, state.yaw_rad as f32);
                surface
            }));
        }
        Self {
            mover_poses,
            mover_boxes,
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

    /// World AABB of moving collider `k` at the instant.
    #[inline]
    pub(super) fn mover_box(&self, k: usize) -> Option<&Aabb> {
        self.mover_boxes.get(k)
    }

    /// False only if `ray` surely misses moving collider `k` within `max_toi`: it passes
    /// outside the collider's box at the instant grown by [`BOX_MARGIN_M`] (so rounding in the
    /// box test can never reject a ray that hits the collider). The spanning tree's leaf of an
    /// actor covers all its parts over the whole sweep (metres for a fast car); this test keeps
    /// the rays that reach the leaf but not the part at this instant from a full shape cast.
    /// The slab test runs on whole vectors: a zero direction component gives infinite slab
    /// times (or NaN for an origin exactly on the grown box's face, where the ray stays outside
    /// the box proper), which the lane-wise min and max resolve to a rejection only where the
    /// ray cannot meet the box.
    #[inline]
    pub(super) fn may_hit(&self, k: usize, ray: &Ray, max_toi: f32) -> bool {
        self.mover_boxes
            .get(k)
            .is_none_or(|b| meets_grown_box(b, ray, max_toi))
    }

    /// Surface of moving collider `k` placed at the instant.
    #[inline]
    pub(super) fn mover_surface(&self, k: usize) -> Option<&Surface> {
        self.mover_surfaces.get(k)?.as_ref()
    }
}

/// True unless `ray` passes outside `b` grown by [`BOX_MARGIN_M`] or only meets it beyond
/// `max_toi` (+ the margin); see [`SceneInstant::may_hit`].
#[inline]
fn meets_grown_box(b: &Aabb, ray: &Ray, max_toi: f32) -> bool {
    let inverse = Vector::ONE / ray.dir;
    let t1 = (b.mins - Vector::splat(BOX_MARGIN_M) - ray.origin) * inverse;
    let t2 = (b.maxs + Vector::splat(BOX_MARGIN_M) - ray.origin) * inverse;
    let near = t1.min(t2).max_element().max(0.0);
    let far = t1.max(t2).min_element().min(max_toi + BOX_MARGIN_M);
    near <= far
}

#[cfg(test)]
mod tests {
    use super::*;
    use rapier3d::parry::query::RayCast;
    use rapier3d::parry::shape::{Cuboid, Shape};

    #[test]
    fn no_ray_that_hits_a_shape_within_reach_misses_its_grown_box() {
        let car = Cuboid::new(Vector::new(2.0, 0.9, 0.7));
        let pose = Pose::new(Vector::new(12.0, 3.0, 0.7), Vector::new(0.0, 0.0, 0.4));
        let b = car.compute_aabb(&pose);
        let (mut hits, mut rejected) = (0, 0);
        for k in 0..20_000 {
            let a = k as f32 * 0.000_37;
            // Directions with zero components too (rays parallel to the box faces).
            let dir = match k % 4 {
                0 => Vector::new(1.0, 0.0, 0.0),
                1 => Vector::new(a.cos(), a.sin(), 0.0),
                _ => Vector::new(a.cos(), a.sin(), -0.02 * (k % 7) as f32).normalize(),
            };
            let origin = Vector::new(0.0, (k % 9) as f32 - 1.0, 0.1 * (k % 13) as f32);
            let ray = Ray::new(origin, dir);
            let reach = 5.0 + (k % 11) as f32 * 2.0;
            let meets = meets_grown_box(&b, &ray, reach);
            if car.cast_ray(&pose, &ray, reach, true).is_some() {
                hits += 1;
                assert!(meets, "ray {k} hits the car but not its box");
            }
            rejected += usize::from(!meets);
        }
        assert!(
            hits > 1000 && rejected > 1000,
            "{hits} hits, {rejected} rejected"
        );
    }
}
