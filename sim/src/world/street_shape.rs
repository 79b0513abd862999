//! The whole static street world as one parry shape, so it is one ordinary Rapier collider:
//! the ground (its two-level walk) and the piece grid (its cell walk). A ray meets the ground
//! first, then the pieces up to that distance, so most beams, which end on the ground a few
//! metres away, test only the pieces of a few cells. Every ray cast through the scene (the
//! lidar's and Rapier's own `QueryPipeline::cast_ray`) meets the street world this way. It never
//! takes part in contacts: only fixed and kinematic bodies exist, and Rapier computes no
//! contacts between those.

use std::sync::Arc;

use rapier3d::parry::bounding_volume::Aabb;
use rapier3d::parry::query::{PointProjection, PointQuery, Ray, RayCast, RayIntersection};
use rapier3d::parry::shape::FeatureId;
use rapier3d::prelude::{Real, Vector};

use super::custom_shape::{CustomShape, impl_parry_shape};

use super::piece_grid::HitNormal;
use super::{GroundField, PieceGrid};

/// Sine of the depression below which a beam is cast on the ground first (8°: it meets a flat
/// road within 12 m of a roof-mounted sensor).
const STEEP_SIN: f32 = 0.14;

/// The part of the street world a ray hit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StreetPart {
    /// The ground, at this cell.
    Ground(u32),
    /// Piece `k` of the piece grid.
    Piece(u32),
}

/// The static street world (its local frame is the world frame).
#[derive(Debug, Clone)]
pub struct StreetShape {
    ground: Option<Arc<GroundField>>,
    pieces: Arc<PieceGrid>,
    aabb: Aabb,
}

impl StreetShape {
    /// The street world of `ground` (none: a flat slab collider stands in) and `pieces`.
    pub(crate) fn new(ground: Option<Arc<GroundField>>, pieces: PieceGrid) -> Self {
        let (mut lo, mut hi) = pieces.bounds();
        if pieces.len() == 0 {
            (lo, hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        }
        if let Some(g) = &ground {
            let (glo, ghi) = g.bounds();
            for a in 0..3 {
                lo[a] = lo[a].min(glo[a]);
                hi[a] = hi[a].max(ghi[a]);
            }
        }
        if lo[0] > hi[0] {
            (lo, hi) = ([0.0; 3], [0.0; 3]);
        }
        Self {
            ground,
            pieces: Arc::new(pieces),
            aabb: Aabb::new(Vector::from(lo), Vector::from(hi)),
        }
    }

    /// The ground, if the street world has one.
    pub fn ground(&self) -> Option<&GroundField> {
        self.ground.as_deref()
    }

    /// The pieces.
    pub fn pieces(&self) -> &PieceGrid {
        &self.pieces
    }

    /// The first part the ray hits within `max_toi` (a piece where a piece and the ground are
    /// hit at the same distance). A steep beam ends on the ground a few metres away: the ground
    /// is cast first and bounds the pieces' walk. A flatter one more often meets a piece before
    /// the ground (or passes over it): the pieces go first and bound the ground's walk.
    #[inline]
    pub fn cast(&self, ray: &Ray, max_toi: f32) -> Option<(f32, StreetPart)> {
        let (o, d) = (ray.origin, ray.dir);
        let ground = |max: f32| {
            self.ground
                .as_ref()
                .and_then(|g| g.cast([o.x, o.y, o.z], [d.x, d.y, d.z], max))
        };
        if d.z < -STEEP_SIN {
            let ground = ground(max_toi);
            let limit = ground.map_or(max_toi, |(t, _)| t);
            match (self.pieces.cast(ray, limit), ground) {
                (Some((t, k)), Some((g, _))) if t <= g => Some((t, StreetPart::Piece(k))),
                (Some((t, k)), None) => Some((t, StreetPart::Piece(k))),
                (_, Some((g, cell))) => Some((g, StreetPart::Ground(cell))),
                (None, None) => None,
            }
        } else {
            let piece = self.pieces.cast(ray, max_toi);
            let limit = piece.map_or(max_toi, |(t, _)| t);
            match (ground(limit), piece) {
                (Some((g, cell)), Some((t, _))) if g < t => Some((g, StreetPart::Ground(cell))),
                (Some((g, cell)), None) => Some((g, StreetPart::Ground(cell))),
                (_, Some((t, k))) => Some((t, StreetPart::Piece(k))),
                (None, None) => None,
            }
        }
    }

    /// [`StreetShape::cast`] with the world normal and feature where a piece is hit (`None` on
    /// the ground, whose normal [`GroundField::normal_at`] gives at the hit point), from the same
    /// shape tests as the hit itself.
    #[inline]
    pub fn cast_with_normal(
        &self,
        ray: &Ray,
        max_toi: f32,
    ) -> Option<(f32, StreetPart, Option<HitNormal>)> {
        let (o, d) = (ray.origin, ray.dir);
        let ground = |max: f32| {
            self.ground
                .as_ref()
                .and_then(|g| g.cast([o.x, o.y, o.z], [d.x, d.y, d.z], max))
        };
        let piece_hit = |(t, k, n)| Some((t, StreetPart::Piece(k), Some(n)));
        if d.z < -STEEP_SIN {
            let ground = ground(max_toi);
            let limit = ground.map_or(max_toi, |(t, _)| t);
            match (self.pieces.cast_with_normal(ray, limit), ground) {
                (Some(hit), Some((g, _))) if hit.0 <= g => piece_hit(hit),
                (Some(hit), None) => piece_hit(hit),
                (_, Some((g, cell))) => Some((g, StreetPart::Ground(cell), None)),
                (None, None) => None,
            }
        } else {
            let piece = self.pieces.cast_with_normal(ray, max_toi);
            let limit = piece.map_or(max_toi, |(t, _, _)| t);
            match (ground(limit), piece) {
                (Some((g, cell)), Some((t, _, _))) if g < t => {
                    Some((g, StreetPart::Ground(cell), None))
                }
                (Some((g, cell)), None) => Some((g, StreetPart::Ground(cell), None)),
                (_, Some(hit)) => piece_hit(hit),
                (None, None) => None,
            }
        }
    }

    /// The world normal and feature where `ray` meets `part` near `toi`.
    pub fn normal(&self, part: StreetPart, ray: &Ray, toi: f32) -> Option<(Vector, FeatureId)> {
        match part {
            StreetPart::Ground(cell) => {
                let p = ray.origin + ray.dir * toi;
                let n = self.ground.as_ref()?.normal_at(p.x, p.y);
                Some((Vector::new(n[0], n[1], n[2]), FeatureId::Face(cell)))
            }
            StreetPart::Piece(k) => {
                let hit = self
                    .pieces
                    .piece(k)?
                    .cast_with_normal(ray, toi + 0.01, true)?;
                Some((hit.normal, hit.feature))
            }
        }
    }

    /// Where `ray`, starting inside piece `k` (a porous volume), leaves it.
    pub fn exit_toi(&self, k: u32, ray: &Ray, max_toi: f32) -> Option<f32> {
        let hit = self
            .pieces
            .piece(k)?
            .cast_with_normal(ray, max_toi, false)?;
        Some(hit.time_of_impact)
    }
}

impl RayCast for StreetShape {
    #[inline]
    fn cast_local_ray(&self, ray: &Ray, max_time_of_impact: Real, _solid: bool) -> Option<Real> {
        self.cast(ray, max_time_of_impact).map(|(t, _)| t)
    }

    fn cast_local_ray_and_get_normal(
        &self,
        ray: &Ray,
        max_time_of_impact: Real,
        _solid: bool,
    ) -> Option<RayIntersection> {
        let (t, part) = self.cast(ray, max_time_of_impact)?;
        let (normal, feature) = self.normal(part, ray, t)?;
        Some(RayIntersection::new(t, normal, feature))
    }
}

impl PointQuery for StreetShape {
    fn project_local_point(&self, pt: Vector, _solid: bool) -> PointProjection {
        // The ground only (nothing asks the street world for projections).
        let h = self
            .ground
            .as_ref()
            .map_or(0.0, |g| g.height_at(pt.x, pt.y));
        PointProjection::new(pt.z < h, Vector::new(pt.x, pt.y, h))
    }

    fn project_local_point_and_get_feature(&self, pt: Vector) -> (PointProjection, FeatureId) {
        (self.project_local_point(pt, false), FeatureId::Unknown)
    }
}

impl CustomShape for StreetShape {
    fn local_aabb(&self) -> Aabb {
        self.aabb
    }

    fn ccd_thickness_m(&self) -> Real {
        0.1
    }

    fn ccd_angular_thickness_rad(&self) -> Real {
        0.1
    }
}

impl_parry_shape!(StreetShape);
