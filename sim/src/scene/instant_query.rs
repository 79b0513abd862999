//! Rapier's ray query against the scene as it stands at one [`SceneInstant`]: the scene's
//! query pipeline (its colliders, shapes, filter and ray-cast tree) with the pose of every mover
//! taken from the instant instead of from its collider. The ray traversal and the ray-shape
//! tests are parry's own (`CompositeShapeRef::cast_local_ray`, which `QueryPipeline::cast_ray`
//! runs too), so the hits are Rapier's exact hits on the scene moved to that instant, provided
//! the tree's leaves cover the movers there (see `Scene::rebuild_ray_tree_spanning`).

use rapier3d::parry::partitioning::Bvh;
use rapier3d::parry::query::details::NormalConstraints;
use rapier3d::parry::shape::{CompositeShape, CompositeShapeRef, Shape, TypedCompositeShape};
use rapier3d::prelude::{ColliderHandle, Pose, QueryPipeline, Ray};

use super::{Scene, SceneInstant, Surface};

/// Ray queries against a scene at one instant.
pub struct InstantQuery<'a> {
    scene: &'a Scene,
    pipeline: QueryPipeline<'a>,
    instant: &'a SceneInstant,
}

impl<'a> InstantQuery<'a> {
    /// Queries against `scene` at `instant` through its ray-cast tree, the ego car excluded.
    pub(super) fn new(scene: &'a Scene, instant: &'a SceneInstant) -> Self {
        Self {
            scene,
            pipeline: scene.query_pipeline(),
            instant,
        }
    }

    /// The first collider hit by `ray` within `max_toi` and the hit's time of impact, as
    /// `QueryPipeline::cast_ray` would give with the scene moved to the instant.
    #[inline]
    pub fn cast_ray(&self, ray: &Ray, max_toi: f32, solid: bool) -> Option<(ColliderHandle, f32)> {
        let (id, toi) = CompositeShapeRef(self).cast_local_ray(ray, max_toi, solid)?;
        let (_, handle) = self.pipeline.colliders.get_unknown_gen(id)?;
        Some((handle, toi))
    }

    /// The surface a collider stands for, placed at the instant (actors) or where it stands.
    #[inline]
    pub fn surface(&self, handle: ColliderHandle) -> Option<&Surface> {
        let surface = self.scene.surface(handle)?;
        match surface.actor {
            Some(actor) => self.instant.actor_surface(actor),
            None => Some(surface),
        }
    }

    /// Motion state of every actor at the instant, in actor order.
    pub fn actor_states(&self) -> &[crate::motion::MotionState] {
        self.instant.actor_states()
    }
}

impl CompositeShape for InstantQuery<'_> {
    fn map_part_at(
        &self,
        shape_id: u32,
        f: &mut dyn FnMut(Option<&Pose>, &dyn Shape, Option<&dyn NormalConstraints>),
    ) {
        self.map_untyped_part_at(shape_id, f);
    }

    fn bvh(&self) -> &Bvh {
        self.pipeline.bvh
    }
}

impl TypedCompositeShape for InstantQuery<'_> {
    type PartNormalConstraints = ();
    type PartShape = dyn Shape;

    #[inline]
    fn map_typed_part_at<T>(
        &self,
        shape_id: u32,
        mut f: impl FnMut(Option<&Pose>, &Self::PartShape, Option<&Self::PartNormalConstraints>) -> T,
    ) -> Option<T> {
        let (collider, handle) = self.pipeline.colliders.get_unknown_gen(shape_id)?;
        if !self
            .pipeline
            .filter
            .test(self.pipeline.bodies, handle, collider)
        {
            return None;
        }
        let pose = match self.scene.mover_of_collider(shape_id) {
            Some(k) => self.instant.mover_pose(k)?,
            None => collider.position(),
        };
        Some(f(Some(pose), collider.shape(), None))
    }

    #[inline]
    fn map_untyped_part_at<T>(
        &self,
        shape_id: u32,
        mut f: impl FnMut(Option<&Pose>, &dyn Shape, Option<&dyn NormalConstraints>) -> T,
    ) -> Option<T> {
        self.map_typed_part_at(shape_id, |pose, shape, _| f(pose, shape, None))
    }
}
