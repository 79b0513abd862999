//! The lidar's tree over the moving actors of a street world. There the static world is one
//! collider cast on its own ([`crate::world::StreetShape`]), so the rays need a tree over the
//! actors only: one leaf per actor (its parts together, spanning its poses at every block instant
//! of the sweep), rebuilt every sweep. A ray that reaches an actor's leaf tests that actor's parts
//! at the instant's poses with parry's own ray casts on their shapes, so a hit is the one Rapier's
//! `QueryPipeline` finds on the scene moved to that instant. The ego car is left out: its own
//! lidar never sees it.

use std::cell::Cell;
use std::ops::Range;

use rapier3d::parry::bounding_volume::{Aabb, BoundingVolume};
use rapier3d::parry::partitioning::{Bvh, BvhBuildStrategy};
use rapier3d::prelude::{ColliderSet, Ray};

use super::SceneInstant;
use super::collider_tables::MoverPart;

/// A tree over the actors; leaf `a` is actor `a`.
#[derive(Clone, Default)]
pub(super) struct ActorTree {
    bvh: Bvh,
    /// The mover indices of each actor's parts.
    parts: Vec<Range<u32>>,
}

impl ActorTree {
    /// The tree's layout for `movers` (the ego car's parts first, then each actor's parts in
    /// actor order), empty until [`ActorTree::rebuild_spanning`].
    pub(super) fn new(movers: &[MoverPart]) -> Self {
        let mut parts: Vec<Range<u32>> = Vec::new();
        for (k, part) in movers.iter().enumerate() {
            let Some(actor) = part.actor else { continue };
            if parts.len() <= actor {
                parts.resize(actor + 1, k as u32..k as u32);
            }
            let range = &mut parts[actor];
            if range.start == range.end {
                *range = k as u32..k as u32 + 1;
            } else {
                range.end = k as u32 + 1;
            }
        }
        Self {
            bvh: Bvh::default(),
            parts,
        }
    }

    /// Builds the tree with every actor's leaf covering its parts at each of `instants`.
    pub(super) fn rebuild_spanning(
        &mut self,
        colliders: &ColliderSet,
        movers: &[MoverPart],
        instants: &[SceneInstant],
    ) {
        let leaves = self.parts.iter().enumerate().filter_map(|(a, range)| {
            let mut aabb: Option<Aabb> = None;
            for k in range.clone() {
                if colliders.get(movers[k as usize].handle).is_none() {
                    continue;
                }
                // The part's box at each instant, as the instant computed it from its pose.
                for part in instants.iter().filter_map(|i| i.mover_box(k as usize)) {
                    aabb = Some(aabb.map_or(*part, |a| a.merged(part)));
                }
            }
            Some((a, aabb?))
        });
        self.bvh = Bvh::from_iter(BvhBuildStrategy::Ploc, leaves);
    }

    /// The first actor part hit by `ray` within `max_toi`: its mover index and time of impact.
    /// `part_toi(k, max)` casts the ray on mover `k` at the instant.
    #[inline]
    pub(super) fn cast(
        &self,
        ray: &Ray,
        max_toi: f32,
        part_toi: impl Fn(u32, f32) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        let best_part = Cell::new(u32::MAX);
        let (_, toi) = self.bvh.cast_ray(ray, max_toi, |actor, best_so_far| {
            let mut best: Option<f32> = None;
            for k in self.parts.get(actor as usize)?.clone() {
                let limit = best.unwrap_or(best_so_far);
                if let Some(t) = part_toi(k, limit)
                    && t < limit
                {
                    best = Some(t);
                    if t < best_so_far {
                        best_part.set(k);
                    }
                }
            }
            best
        })?;
        Some((best_part.get(), toi))
    }
}
