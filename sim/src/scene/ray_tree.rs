//! The bounding-volume tree the lidar's rays traverse. Rapier's broad-phase BVH is tuned for
//! contact pairs: its incremental optimizer reshapes the tree as bodies move, and after a few
//! hundred scene moves ray casts through it cost 25–35 % more than through the fresh tree (and
//! the cost then depends on the scene's history, not only on the instant). So the scene keeps its
//! own parry `Bvh` over the tight collider AABBs, rebuilt from scratch with the ray-cast oriented
//! PLOC builder at the start of every sweep, with the leaf of each of the few moving colliders
//! spanning its poses at all block instants of the sweep (they move at most metres within one
//! sweep), so one tree serves every block; [`Scene::move_to`](super::Scene::move_to) refits those
//! leaves in place. Rapier's `QueryPipeline` (and the lidar's per-instant query) traverse this
//! tree, so the hits are Rapier's exact ray-shape hits.

use rapier3d::parry::bounding_volume::BoundingVolume;
use rapier3d::parry::partitioning::{Bvh, BvhBuildStrategy};
use rapier3d::prelude::{ColliderHandle, ColliderSet};

use super::SceneInstant;

/// No mover for this collider index (a fixed collider).
const NOT_MOVING: u32 = u32::MAX;

/// Which bounding-volume tree a query pipeline traverses (the hits are the same).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QueryTree {
    /// The scene's ray-cast tree, rebuilt every sweep (what the lidar uses).
    RayCast,
    /// Rapier's own broad-phase BVH, shaped by its incremental optimizer.
    RapierBroadPhase,
}

/// A ray-cast BVH over every collider, leaf index = collider arena index (as Rapier's own).
#[derive(Clone, Default)]
pub(super) struct RayTree {
    bvh: Bvh,
    /// The moving colliders, mover order (the ego car first, then the actors).
    moving: Vec<ColliderHandle>,
    /// Mover index by collider arena index ([`NOT_MOVING`] for fixed colliders).
    mover_of_collider: Vec<u32>,
}

impl RayTree {
    /// A tree over `colliders` whose `moving` colliders will be refitted by [`RayTree::refit_moving`].
    pub(super) fn new(colliders: &ColliderSet, moving: Vec<ColliderHandle>) -> Self {
        let mut mover_of_collider = Vec::new();
        for (k, handle) in moving.iter().enumerate() {
            let slot = handle.into_raw_parts().0 as usize;
            if mover_of_collider.len() <= slot {
                mover_of_collider.resize(slot + 1, NOT_MOVING);
            }
            mover_of_collider[slot] = k as u32;
        }
        let mut tree = Self {
            bvh: Bvh::default(),
            moving,
            mover_of_collider,
        };
        tree.rebuild(colliders);
        tree
    }

    /// Builds the tree from scratch over the colliders as they stand.
    pub(super) fn rebuild(&mut self, colliders: &ColliderSet) {
        self.bvh = Bvh::from_iter(
            BvhBuildStrategy::Ploc,
            colliders
                .iter()
                .map(|(h, c)| (h.into_raw_parts().0 as usize, c.compute_aabb())),
        );
    }

    /// Builds the tree from scratch with the leaf of every mover covering it where it stands and
    /// at each of `instants`, so one tree serves ray casts at any of those instants.
    pub(super) fn rebuild_spanning(&mut self, colliders: &ColliderSet, instants: &[SceneInstant]) {
        self.bvh = Bvh::from_iter(
            BvhBuildStrategy::Ploc,
            colliders.iter().map(|(h, c)| {
                let index = h.into_raw_parts().0;
                let mut aabb = c.compute_aabb();
                if let Some(k) = self.mover_of(index) {
                    for pose in instants.iter().filter_map(|i| i.mover_pose(k)) {
                        aabb.merge(&c.shape().compute_aabb(pose));
                    }
                }
                (index as usize, aabb)
            }),
        );
    }

    /// The mover index (position in the scene's mover list) of the collider at arena index `index`.
    #[inline]
    pub(super) fn mover_of(&self, index: u32) -> Option<usize> {
        match self.mover_of_collider.get(index as usize) {
            Some(&k) if k != NOT_MOVING => Some(k as usize),
            _ => None,
        }
    }

    /// Moves the leaves of the moving colliders to their current AABBs and refits their ancestors.
    pub(super) fn refit_moving(&mut self, colliders: &ColliderSet) {
        for &handle in &self.moving {
            if let Some(collider) = colliders.get(handle) {
                self.bvh.update_partially_if_present(
                    collider.compute_aabb(),
                    handle.into_raw_parts().0,
                    0.0,
                );
            }
        }
        self.bvh.refit_without_opt();
    }

    /// The tree.
    pub(super) fn bvh(&self) -> &Bvh {
        &self.bvh
    }
}
