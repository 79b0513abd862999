//! How the lidar queries the scene: the per-sweep ray-cast tree (rebuilt, or spanning the
//! instants of a rolling-shutter sweep), the scene at one instant, and Rapier query pipelines
//! through either tree with the ego car excluded.

use rapier3d::prelude::*;

use super::ray_tree::QueryTree;
use super::{InstantQuery, Scene, SceneInstant};

impl Scene {
    /// Rebuilds the ray-cast tree from scratch over the scene as last moved; the lidar calls it
    /// once per sweep, so a sweep's cost does not depend on what the scene did before.
    pub fn rebuild_ray_tree(&mut self) {
        self.ray_tree.rebuild(&self.colliders);
    }

    /// The movers of the scene at `t_secs` (from their trajectories; the scene is not moved).
    pub fn instant(&self, t_secs: f64) -> SceneInstant {
        SceneInstant::new(
            t_secs,
            (&self.ego, &self.actors),
            &self.movers,
            (&self.surfaces, &self.colliders),
        )
    }

    /// Rebuilds the lidar's tree from scratch with every mover's leaf covering it as last moved
    /// and at each of `instants`, so [`Scene::query_at`] gives exact hits at any of them: the
    /// ray-cast tree over every collider, or in a street world the tree over the actors (the
    /// static world is cast on its own).
    pub fn rebuild_ray_tree_spanning(&mut self, instants: &[SceneInstant]) {
        match self.street {
            Some(_) => self
                .actor_tree
                .rebuild_spanning(&self.colliders, &self.movers, instants),
            None => self.ray_tree.rebuild_spanning(&self.colliders, instants),
        }
    }

    /// Ray queries against the scene at `instant` through the ray-cast tree, ego car excluded;
    /// the tree must have been built spanning `instant` ([`Scene::rebuild_ray_tree_spanning`]).
    pub fn query_at<'a>(&'a self, instant: &'a SceneInstant) -> InstantQuery<'a> {
        InstantQuery {
            scene: self,
            colliders: &self.colliders,
            bvh: self.ray_tree.bvh(),
            actor_tree: &self.actor_tree,
            instant,
        }
    }

    /// The mover index of the collider at arena index `index` and whether it is the ego car's.
    #[inline]
    pub(super) fn mover_of_collider(&self, index: u32) -> Option<(usize, bool)> {
        let k = self.ray_tree.mover_of(index)?;
        Some((k, self.movers.get(k).is_some_and(|m| m.actor.is_none())))
    }

    /// The street world's ground, if the scene has one.
    pub fn ground(&self) -> Option<&crate::world::GroundField> {
        self.street.as_ref()?.shape.ground()
    }

    /// The street world (ground and static pieces as one shape), if the scene has one.
    pub fn street(&self) -> Option<&crate::world::StreetShape> {
        self.street.as_ref().map(|s| &*s.shape)
    }

    /// A query pipeline over the scene as last moved, through the ray-cast tree, with the ego
    /// car excluded from its rays.
    pub fn query_pipeline(&self) -> QueryPipeline<'_> {
        self.query_pipeline_on(QueryTree::RayCast)
    }

    /// A query pipeline over the scene as last moved through the given tree, ego car excluded.
    pub fn query_pipeline_on(&self, tree: QueryTree) -> QueryPipeline<'_> {
        let filter = QueryFilter::default().exclude_rigid_body(self.ego.body);
        let rapier = self.broad_phase.as_query_pipeline(
            self.narrow_phase.query_dispatcher(),
            &self.bodies,
            &self.colliders,
            filter,
        );
        match tree {
            QueryTree::RayCast => QueryPipeline {
                bvh: self.ray_tree.bvh(),
                ..rapier
            },
            QueryTree::RapierBroadPhase => rapier,
        }
    }
}
