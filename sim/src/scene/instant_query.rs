//! Rapier's ray query against the scene as it stands at one [`SceneInstant`]: the scene's
//! colliders, shapes and ray-cast tree with the pose of every mover taken from the instant
//! instead of from its collider, and the ego car left out (the filter of
//! [`Scene::query_pipeline`], read from the mover table instead of the collider). The ray
//! traversal and the ray-shape tests are parry's own (`CompositeShapeRef::cast_local_ray`, which
//! `QueryPipeline::cast_ray` runs too), so the hits are Rapier's exact hits on the scene moved to
//! that instant, provided the tree's leaves cover the movers there (see
//! [`Scene::rebuild_ray_tree_spanning`]). The street world's one collider is cast first and
//! directly (so the hit names the part of it that was hit, and bounds the tree's traversal); the
//! tree then skips it. Unlike a `QueryPipeline` it is `Sync`, so one serves all threads.

use rapier3d::parry::partitioning::Bvh;
use rapier3d::parry::query::details::NormalConstraints;
use rapier3d::parry::shape::{
    CompositeShape, CompositeShapeRef, FeatureId, Shape, TypedCompositeShape,
};
use rapier3d::prelude::{ColliderHandle, ColliderSet, Pose, Ray, Vector};

use super::actor_tree::ActorTree;
use super::{Scene, SceneInstant, Surface};
use crate::world::StreetPart;

/// What a ray hit: a collider of the ray-cast tree (its arena index) or a part of the street
/// world.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HitPart {
    /// A collider (arena index).
    Collider(u32),
    /// A part of the street world.
    Street(StreetPart),
}

/// A unit normal (world frame) and the feature hit, where the cast that found the hit had them.
pub type Normal = Option<crate::world::HitNormal>;

/// Ray queries against a scene at one instant.
pub struct InstantQuery<'a> {
    /// The scene (surfaces and the mover table).
    pub(super) scene: &'a Scene,
    /// Its colliders (fixed colliders stand where they are; movers take the instant's poses).
    pub(super) colliders: &'a ColliderSet,
    /// Its ray-cast tree, spanning the instant (the world of the first release).
    pub(super) bvh: &'a Bvh,
    /// Its tree over the actors, spanning the instant (a street world).
    pub(super) actor_tree: &'a ActorTree,
    /// The movers at the instant.
    pub(super) instant: &'a SceneInstant,
}

impl InstantQuery<'_> {
    /// The first part hit by `ray` within `max_toi` and its time of impact: in a street world the
    /// street first, then the actors before that hit; otherwise every collider through the tree.
    #[inline]
    fn first_hit(&self, ray: &Ray, max_toi: f32, solid: bool) -> Option<(HitPart, f32)> {
        let Some(street) = &self.scene.street else {
            let (id, toi) = CompositeShapeRef(self).cast_local_ray(ray, max_toi, solid)?;
            return Some((HitPart::Collider(id), toi));
        };
        let hit = street
            .shape
            .cast(ray, max_toi)
            .map(|(t, part)| (HitPart::Street(part), t));
        self.first_actor_hit_before(ray, hit, max_toi, solid)
    }

    /// [`InstantQuery::first_hit`] (solid) with the normal and feature of a street piece hit,
    /// from the same shape tests (`None` for the ground and the actors).
    #[inline]
    fn first_hit_with_normal(&self, ray: &Ray, max_toi: f32) -> Option<(HitPart, f32, Normal)> {
        let Some(street) = &self.scene.street else {
            let (part, toi) = self.first_hit(ray, max_toi, true)?;
            return Some((part, toi, None));
        };
        let hit = street.shape.cast_with_normal(ray, max_toi);
        let (part, toi) = self.first_actor_hit_before(
            ray,
            hit.map(|(t, p, _)| (HitPart::Street(p), t)),
            max_toi,
            true,
        )?;
        let normal = match (part, hit) {
            (HitPart::Street(_), Some((_, _, normal))) => normal,
            _ => None,
        };
        Some((part, toi, normal))
    }

    /// The first actor hit before the street's hit `hit` (if any, else within `max_toi`), or
    /// that street hit.
    #[inline]
    fn first_actor_hit_before(
        &self,
        ray: &Ray,
        hit: Option<(HitPart, f32)>,
        max_toi: f32,
        solid: bool,
    ) -> Option<(HitPart, f32)> {
        let limit = hit.map_or(max_toi, |(_, t)| t);
        let actor = self.actor_tree.cast(ray, limit, |k, max| {
            let part = self.scene.movers.get(k as usize)?;
            let pose = self.instant.mover_pose(k as usize)?;
            if !self.instant.may_hit(k as usize, ray, max) {
                return None;
            }
            let collider = self.colliders.get(part.handle)?;
            collider.shape().cast_ray(pose, ray, max, solid)
        });
        match actor {
            Some((k, t)) if hit.is_none_or(|(_, s)| t < s) => {
                let handle = self.scene.movers.get(k as usize)?.handle;
                Some((HitPart::Collider(handle.into_raw_parts().0), t))
            }
            _ => hit,
        }
    }

    /// The first collider hit by `ray` within `max_toi` and the hit's time of impact, as
    /// `QueryPipeline::cast_ray` would give with the scene moved to the instant.
    #[inline]
    pub fn cast_ray(&self, ray: &Ray, max_toi: f32, solid: bool) -> Option<(ColliderHandle, f32)> {
        let (part, toi) = self.first_hit(ray, max_toi, solid)?;
        let id = match part {
            HitPart::Collider(id) => id,
            HitPart::Street(_) => self.scene.street.as_ref()?.collider,
        };
        let (_, handle) = self.colliders.get_unknown_gen(id)?;
        Some((handle, toi))
    }

    /// The surface first hit by `ray` within `max_toi` (placed at the instant) and the hit's
    /// time of impact: [`InstantQuery::cast_ray`] and [`InstantQuery::surface`] in one step,
    /// straight from the tree's leaf index.
    #[inline]
    pub fn cast_ray_to_surface(
        &self,
        ray: &Ray,
        max_toi: f32,
        solid: bool,
    ) -> Option<(&Surface, f32)> {
        let (part, toi) = self.first_hit(ray, max_toi, solid)?;
        Some((self.surface_of(part)?, toi))
    }

    /// The surface a collider stands for, placed at the instant (actors) or where it stands.
    #[inline]
    pub fn surface(&self, handle: ColliderHandle) -> Option<&Surface> {
        self.surface_at(self.scene.surface(handle)?)
    }

    /// The surface of a hit part, placed at the instant.
    #[inline]
    fn surface_of(&self, part: HitPart) -> Option<&Surface> {
        match part {
            HitPart::Collider(id) => self.surface_at(self.scene.surface_at(id)?),
            HitPart::Street(part) => {
                let street = self.scene.street.as_ref()?;
                let index = match part {
                    StreetPart::Ground(_) => street.ground_surface,
                    StreetPart::Piece(k) => street.first_piece_surface + k,
                };
                self.scene.surfaces.get(index as usize)
            }
        }
    }

    /// `surface` itself for fixed colliders, or the same moving collider's surface placed at
    /// the instant.
    #[inline]
    fn surface_at<'s>(&'s self, surface: &'s Surface) -> Option<&'s Surface> {
        match surface.mover {
            Some(k) => self.instant.mover_surface(k as usize),
            None => Some(surface),
        }
    }

    /// The surface first hit by `ray` within `max_toi`, the hit's time of impact, the part hit
    /// and, for a street piece, its normal and feature there (else [`InstantQuery::normal`]
    /// gives them).
    #[inline]
    pub fn cast_ray_to_hit(
        &self,
        ray: &Ray,
        max_toi: f32,
    ) -> Option<(&Surface, f32, HitPart, Normal)> {
        let (part, toi, normal) = self.first_hit_with_normal(ray, max_toi)?;
        Some((self.surface_of(part)?, toi, part, normal))
    }

    /// Unit normal, world frame, of the hit `part` (at the instant) where `ray` meets it near
    /// `toi`, and the hit feature, as parry's own ray cast on that one shape reports them.
    pub fn normal(&self, part: HitPart, ray: &Ray, toi: f32) -> Option<(Vector, FeatureId)> {
        let id = match part {
            HitPart::Collider(id) => id,
            HitPart::Street(part) => {
                return self.scene.street.as_ref()?.shape.normal(part, ray, toi);
            }
        };
        let mut normal = None;
        self.map_typed_part_at(id, |pose, shape, _| {
            let pose = pose.copied().unwrap_or(Pose::IDENTITY);
            normal = shape
                .cast_ray_and_get_normal(&pose, ray, toi + 0.01, true)
                .map(|hit| (hit.normal, hit.feature));
        });
        normal
    }

    /// Time of impact where `ray`, starting inside the hit `part` (a porous volume), leaves it.
    pub fn exit_toi(&self, part: HitPart, ray: &Ray, max_toi: f32) -> Option<f32> {
        let id = match part {
            HitPart::Collider(id) => id,
            HitPart::Street(StreetPart::Piece(k)) => {
                return self.scene.street.as_ref()?.shape.exit_toi(k, ray, max_toi);
            }
            HitPart::Street(StreetPart::Ground(_)) => return None,
        };
        let mut exit = None;
        self.map_typed_part_at(id, |pose, shape, _| {
            let pose = pose.copied().unwrap_or(Pose::IDENTITY);
            exit = shape.cast_ray(&pose, ray, max_toi, false);
        });
        exit
    }

    /// The scene queried.
    pub fn scene(&self) -> &Scene {
        self.scene
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
        self.bvh
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
        // The street world is cast first, on its own (see `first_hit`).
        if self
            .scene
            .street
            .as_ref()
            .is_some_and(|s| s.collider == shape_id)
        {
            return None;
        }
        let mover_pose = match self.scene.mover_of_collider(shape_id) {
            // The ego car's own lidar never sees it.
            Some((_, true)) => return None,
            Some((k, false)) => Some(self.instant.mover_pose(k)?),
            None => None,
        };
        let (collider, _) = self.colliders.get_unknown_gen(shape_id)?;
        let pose = mover_pose.unwrap_or_else(|| collider.position());
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

#[cfg(test)]
#[path = "instant_query_tests.rs"]
mod tests;
