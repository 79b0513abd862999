//! Every static piece of a street world (clutter, parked cars, sidewalk slabs, vegetation,
//! façades, structures) in a uniform grid over the ground plane, cast into by walking the cells a
//! ray crosses in order (2-D DDA). A street is a 2.5-D world: a ray from the roof of a car meets
//! the pieces of the next few cells or passes over them (each cell knows the height span of its
//! pieces), so a cast costs a few cell steps and a few piece tests instead of a descent through a
//! tree over thousands of colliders, where every long, low ray overlaps many boxes.

use rapier3d::parry::query::Ray;
use rapier3d::prelude::Vector;

use super::grid_piece::GridPiece;
use super::grid_walk::walk_cells;

/// A unit normal (world frame) and the feature where a ray hit.
pub type HitNormal = (Vector, rapier3d::parry::shape::FeatureId);

/// Side of a grid cell, metres.
const CELL_M: f32 = 4.0;
/// Most cells a side (the grid coarsens beyond, so its tables stay small).
const MAX_CELLS_PER_SIDE: usize = 2048;
/// Pieces recently tested by one ray, skipped when a later cell lists them again.
const MAILBOX: usize = 8;

/// A piece as a cell lists it: its world AABB inline (a ray is tested against it without
/// touching the piece) and its index.
#[derive(Debug, Clone, Copy)]
struct Entry {
    mins: [f32; 3],
    maxs: [f32; 3],
    piece: u32,
}

impl Entry {
    /// True if the ray `o + t·d` (`inverse` = 1/d) passes through the AABB for some `t` in
    /// `[0, max_t]`.
    #[inline]
    fn crossed_by(&self, o: Vector, inverse: Vector, max_t: f32) -> bool {
        let t1 = (Vector::from(self.mins) - o) * inverse;
        let t2 = (Vector::from(self.maxs) - o) * inverse;
        let near = t1.min(t2).max_element().max(0.0);
        let far = t1.max(t2).min_element().min(max_t);
        near <= far
    }
}

/// The pieces and their grid.
#[derive(Debug, Clone)]
pub struct PieceGrid {
    pieces: Vec<GridPiece>,
    origin: [f32; 2],
    cell_m: f32,
    cells: [usize; 2],
    /// Start of each cell's list in `items` (one more entry than cells).
    starts: Vec<u32>,
    /// Piece entries (index and world AABB), cell by cell.
    items: Vec<Entry>,
    /// Lowest and highest point of the pieces of each cell (empty cells: an empty span).
    spans: Vec<(f32, f32)>,
    /// Lowest and highest point of every piece.
    z_range: (f32, f32),
}

impl PieceGrid {
    /// The grid over `pieces`.
    pub(crate) fn new(pieces: Vec<GridPiece>) -> Self {
        let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        for p in &pieces {
            let b = p.aabb();
            for a in 0..3 {
                lo[a] = lo[a].min(b.mins[a]);
                hi[a] = hi[a].max(b.maxs[a]);
            }
        }
        if pieces.is_empty() {
            (lo, hi) = ([0.0; 3], [0.0; 3]);
        }
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(CELL_M);
        let cell_m = CELL_M.max(extent / MAX_CELLS_PER_SIDE as f32);
        let cells = [
            (((hi[0] - lo[0]) / cell_m).ceil() as usize).max(1),
            (((hi[1] - lo[1]) / cell_m).ceil() as usize).max(1),
        ];
        let cell_range = |v: f32, w: f32, axis: usize| {
            let a = ((v - lo[axis]) / cell_m).floor().max(0.0) as usize;
            let b = ((w - lo[axis]) / cell_m).floor().max(0.0) as usize;
            a.min(cells[axis] - 1)..=b.min(cells[axis] - 1)
        };
        let mut counts = vec![0u32; cells[0] * cells[1]];
        let mut spans = vec![(f32::MAX, f32::MIN); counts.len()];
        for p in &pieces {
            let b = p.aabb();
            for j in cell_range(b.mins.y, b.maxs.y, 1) {
                for i in cell_range(b.mins.x, b.maxs.x, 0) {
                    let c = j * cells[0] + i;
                    counts[c] += 1;
                    spans[c] = (spans[c].0.min(b.mins.z), spans[c].1.max(b.maxs.z));
                }
            }
        }
        let mut starts = Vec::with_capacity(counts.len() + 1);
        let mut total = 0u32;
        for &n in &counts {
            starts.push(total);
            total += n;
        }
        starts.push(total);
        let mut fill: Vec<u32> = starts[..counts.len()].to_vec();
        let empty = Entry {
            mins: [0.0; 3],
            maxs: [0.0; 3],
            piece: 0,
        };
        let mut items = vec![empty; total as usize];
        for (k, p) in pieces.iter().enumerate() {
            let b = p.aabb();
            let entry = Entry {
                mins: b.mins.into(),
                maxs: b.maxs.into(),
                piece: k as u32,
            };
            for j in cell_range(b.mins.y, b.maxs.y, 1) {
                for i in cell_range(b.mins.x, b.maxs.x, 0) {
                    let c = j * cells[0] + i;
                    items[fill[c] as usize] = entry;
                    fill[c] += 1;
                }
            }
        }
        Self {
            pieces,
            origin: [lo[0], lo[1]],
            cell_m,
            cells,
            starts,
            items,
            spans,
            z_range: (lo[2], hi[2]),
        }
    }

    /// Number of pieces.
    pub(crate) fn len(&self) -> usize {
        self.pieces.len()
    }

    /// Piece `k`.
    pub(crate) fn piece(&self, k: u32) -> Option<&GridPiece> {
        self.pieces.get(k as usize)
    }

    /// Lowest and highest corner of all pieces.
    pub(crate) fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        (
            [self.origin[0], self.origin[1], self.z_range.0],
            [
                self.origin[0] + self.cells[0] as f32 * self.cell_m,
                self.origin[1] + self.cells[1] as f32 * self.cell_m,
                self.z_range.1,
            ],
        )
    }

    /// The first piece the ray `origin + t·dir` hits with `t ≤ max_toi`: its `t` and index.
    #[inline]
    pub(crate) fn cast(&self, ray: &Ray, max_toi: f32) -> Option<(f32, u32)> {
        self.walk(ray, max_toi, |piece, best_t| {
            Some((piece.cast_solid(ray, best_t)?, ()))
        })
        .map(|(t, k, ())| (t, k))
    }

    /// [`PieceGrid::cast`] with the world normal and feature of the hit, from the same shape
    /// tests (the labelled sweep needs the incidence; a second cast of the piece hit would cost
    /// as much again).
    #[inline]
    pub(crate) fn cast_with_normal(
        &self,
        ray: &Ray,
        max_toi: f32,
    ) -> Option<(f32, u32, HitNormal)> {
        let (t, k, (normal, feature)) = self.walk(ray, max_toi, |piece, best_t| {
            let hit = piece.cast_with_local_normal(ray, best_t, true)?;
            Some((hit.time_of_impact, (hit.normal, hit.feature)))
        })?;
        // Only the first hit's normal is turned into the world frame.
        let normal = self.pieces.get(k as usize)?.world_normal(normal);
        Some((t, k, (normal, feature)))
    }

    /// The cell walk shared by both casts: `test(piece, best_t)` casts the ray on one piece and
    /// gives its `t` (at most `best_t`) and whatever else the caller keeps of the hit.
    #[inline]
    fn walk<T: Copy>(
        &self,
        ray: &Ray,
        max_toi: f32,
        mut test: impl FnMut(&GridPiece, f32) -> Option<(f32, T)>,
    ) -> Option<(f32, u32, T)> {
        if self.pieces.is_empty() {
            return None;
        }
        let (lo, hi) = self.bounds();
        let (o, d) = (ray.origin, ray.dir);
        let (mut t0, mut t1) = (0.0f32, max_toi);
        for a in 0..3 {
            if d[a].abs() < 1e-12 {
                if o[a] < lo[a] || o[a] > hi[a] {
                    return None;
                }
                continue;
            }
            let (ta, tb) = ((lo[a] - o[a]) / d[a], (hi[a] - o[a]) / d[a]);
            t0 = t0.max(ta.min(tb));
            t1 = t1.min(ta.max(tb));
        }
        if t0 > t1 {
            return None;
        }
        let inverse_dir = Vector::ONE / d;
        let o = ray.origin;
        let mut best: Option<(f32, u32, T)> = None;
        let mut best_t = max_toi;
        let mut mailbox = [u32::MAX; MAILBOX];
        let mut next_slot = 0;
        let local = [o.x - self.origin[0], o.y - self.origin[1]];
        walk_cells(
            local,
            [d.x, d.y],
            self.cell_m,
            self.cells,
            (t0, t1),
            |i, j, ta, tb| {
                if ta > best_t {
                    return true;
                }
                let c = j * self.cells[0] + i;
                let (zlo, zhi) = self.spans[c];
                let (za, zb) = (o.z + d.z * ta, o.z + d.z * tb.min(best_t));
                if za.min(zb) > zhi || za.max(zb) < zlo {
                    return false;
                }
                let list = &self.items[self.starts[c] as usize..self.starts[c + 1] as usize];
                for entry in list {
                    let k = entry.piece;
                    if !entry.crossed_by(o, inverse_dir, best_t) || mailbox.contains(&k) {
                        continue;
                    }
                    mailbox[next_slot] = k;
                    next_slot = (next_slot + 1) % MAILBOX;
                    if let Some((t, extra)) = test(&self.pieces[k as usize], best_t)
                        && (t < best_t || best.is_none())
                    {
                        best = Some((t, k, extra));
                        best_t = t;
                    }
                }
                // A hit inside this cell (or before) is the first: every piece a ray can meet
                // earlier is listed in a cell crossed earlier.
                best_t <= tb
            },
        );
        best
    }
}

#[cfg(test)]
#[path = "piece_grid_tests.rs"]
mod tests;
