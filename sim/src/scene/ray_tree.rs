//! The bounding-volume tree the lidar's rays traverse. Rapier's broad-phase BVH is tuned for
//! contact pairs: its incremental optimizer reshapes the tree as bodies move, and after a few
//! hundred scene moves ray casts through it cost 25–35 % more than through the fresh tree (and
//! the cost then depends on the scene's history, not only on the instant). So the scene keeps its
//! own parry `Bvh` over the tight collider AABBs, rebuilt from scratch with the ray-cast oriented
//! PLOC builder at the start of every sweep and refitted in place for the few moving colliders at
//! every block (they move at most metres within one sweep). Rapier's `QueryPipeline` is queried
//! through this tree, so the hits are Rapier's exact ray-shape hits.

use rapier3d::parry::partitioning::{Bvh, BvhBuildStrategy};
use rapier3d::prelude::{ColliderHandle, ColliderSet};

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
    moving: Vec<ColliderHandle>,
}

impl RayTree {
    /// A tree over `colliders` whose `moving` colliders will be refitted by [`RayTree::refit_moving`].
    pub(super) fn new(colliders: &ColliderSet, moving: Vec<ColliderHandle>) -> Self {
        let mut tree = Self {
            bvh: Bvh::default(),
            moving,
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
