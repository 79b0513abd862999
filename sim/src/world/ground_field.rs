//! The ground of a street world as a height field: heights on a regular grid of vertices (each
//! cell two triangles split along its rising diagonal) and a material per cell. Streets are
//! cambered from their crown, the sidewalk band is raised by the curb height (the sidewalk slabs
//! and their curb faces are boxes on top, see `street_furniture.rs`), and the terrain beyond has
//! its own seeded relief; everything rides on gentle grade changes and a short-wavelength
//! roughness. A ray is traced through two grid levels (blocks with their height bounds, then
//! cells) so a grazing ray over a flat street costs a few block steps, not a walk over every cell.

use super::grid_walk::walk_cells;
pub(crate) use super::ground_recipe::{GroundMaterial, GroundRecipe};

#[path = "ground_surface.rs"]
mod surface;

/// Cells per block side of the coarse level.
const BLOCK: usize = 4;

/// Heights and materials on a grid.
#[derive(Debug, Clone)]
pub struct GroundField {
    origin_m: [f64; 2],
    cell_m: f32,
    inverse_cell: f32,
    /// Cells along x and y.
    cells: [usize; 2],
    /// Vertex heights, row by row (y), `(cells[0] + 1) × (cells[1] + 1)`.
    heights: Vec<f32>,
    /// Material and reflectivity (0-255 for 0-1) of every cell, row by row.
    materials: Vec<(GroundMaterial, u8)>,
    /// Blocks along x and y.
    blocks: [usize; 2],
    /// Lowest and highest vertex height of every block.
    block_bounds: Vec<(f32, f32)>,
    z_range: (f32, f32),
}

impl GroundField {
    /// The ground over the rectangle `[min, max]` with cells of `cell_m`.
    pub(crate) fn build(
        recipe: &GroundRecipe<'_>,
        min: [f64; 2],
        max: [f64; 2],
        cell_m: f64,
    ) -> Self {
        let cells = [
            (((max[0] - min[0]) / cell_m).ceil() as usize).max(1),
            (((max[1] - min[1]) / cell_m).ceil() as usize).max(1),
        ];
        let (vx, vy) = (cells[0] + 1, cells[1] + 1);
        let vertex = |i: usize, j: usize| [min[0] + i as f64 * cell_m, min[1] + j as f64 * cell_m];
        let heights: Vec<f32> = (0..vy)
            .flat_map(|j| (0..vx).map(move |i| (i, j)))
            .map(|(i, j)| recipe.sample(vertex(i, j), cell_m).0 as f32)
            .collect();
        let materials = (0..cells[1])
            .flat_map(|j| (0..cells[0]).map(move |i| (i, j)))
            .map(|(i, j)| {
                let c = vertex(i, j);
                let (_, material, reflectivity) =
                    recipe.sample([c[0] + cell_m / 2.0, c[1] + cell_m / 2.0], cell_m);
                (
                    material,
                    (reflectivity.clamp(0.0, 1.0) * 255.0).round() as u8,
                )
            })
            .collect();
        let blocks = [cells[0].div_ceil(BLOCK), cells[1].div_ceil(BLOCK)];
        let mut block_bounds = vec![(f32::MAX, f32::MIN); blocks[0] * blocks[1]];
        for j in 0..vy {
            for i in 0..vx {
                let h = heights[j * vx + i];
                // A vertex bounds every block it is a corner of.
                for bj in [j.saturating_sub(1) / BLOCK, j.min(cells[1] - 1) / BLOCK] {
                    for bi in [i.saturating_sub(1) / BLOCK, i.min(cells[0] - 1) / BLOCK] {
                        let b = &mut block_bounds[bj * blocks[0] + bi];
                        b.0 = b.0.min(h);
                        b.1 = b.1.max(h);
                    }
                }
            }
        }
        let z_range = heights
            .iter()
            .fold((f32::MAX, f32::MIN), |(lo, hi), &h| (lo.min(h), hi.max(h)));
        Self {
            origin_m: min,
            cell_m: cell_m as f32,
            inverse_cell: (1.0 / cell_m) as f32,
            cells,
            heights,
            materials,
            blocks,
            block_bounds,
            z_range,
        }
    }

    /// Lowest and highest corner of the field: `([x, y, z] min, [x, y, z] max)`.
    pub(crate) fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        let (x0, y0) = (self.origin_m[0] as f32, self.origin_m[1] as f32);
        (
            [x0, y0, self.z_range.0],
            [
                x0 + self.cells[0] as f32 * self.cell_m,
                y0 + self.cells[1] as f32 * self.cell_m,
                self.z_range.1,
            ],
        )
    }

    /// First hit of the ray `origin + t·dir` with `t ≤ max_t`: its `t` and the hit cell's index.
    pub(crate) fn cast(&self, origin: [f32; 3], dir: [f32; 3], max_t: f32) -> Option<(f32, u32)> {
        let (lo, hi) = self.bounds();
        let (mut t0, mut t1) = (0.0f32, max_t);
        for a in 0..3 {
            if dir[a].abs() < 1e-12 {
                if origin[a] < lo[a] || origin[a] > hi[a] {
                    return None;
                }
                continue;
            }
            let inv = 1.0 / dir[a];
            let (ta, tb) = ((lo[a] - origin[a]) * inv, (hi[a] - origin[a]) * inv);
            t0 = t0.max(ta.min(tb));
            t1 = t1.min(ta.max(tb));
        }
        if t0 > t1 {
            return None;
        }
        let block_m = self.cell_m * BLOCK as f32;
        let ox = origin[0] - self.origin_m[0] as f32;
        let oy = origin[1] - self.origin_m[1] as f32;
        let mut hit = None;
        walk_cells(
            [ox, oy],
            [dir[0], dir[1]],
            block_m,
            self.blocks,
            (t0, t1),
            |bi, bj, ta, tb| {
                let (bmin, bmax) = self.block_bounds[bj * self.blocks[0] + bi];
                let (za, zb) = (origin[2] + dir[2] * ta, origin[2] + dir[2] * tb);
                if za.min(zb) > bmax || za.max(zb) < bmin {
                    return false;
                }
                let (mut sa, mut sb) = (ta, tb);
                if dir[2].abs() > 1e-12 {
                    let (tz0, tz1) = ((bmax - origin[2]) / dir[2], (bmin - origin[2]) / dir[2]);
                    sa = sa.max(tz0.min(tz1));
                    sb = sb.min(tz0.max(tz1));
                }
                if sa > sb {
                    return false;
                }
                let first = [bi * BLOCK, bj * BLOCK];
                let cells = [
                    BLOCK.min(self.cells[0] - first[0]),
                    BLOCK.min(self.cells[1] - first[1]),
                ];
                let local = [
                    ox - first[0] as f32 * self.cell_m,
                    oy - first[1] as f32 * self.cell_m,
                ];
                walk_cells(
                    local,
                    [dir[0], dir[1]],
                    self.cell_m,
                    cells,
                    (sa, sb),
                    |ci, cj, ca, cb| {
                        let (i, j) = (first[0] + ci, first[1] + cj);
                        match self.cast_cell(i, j, origin, dir, ca, cb) {
                            Some(t) => {
                                hit = Some((t, (j * self.cells[0] + i) as u32));
                                true
                            }
                            None => false,
                        }
                    },
                )
            },
        );
        hit
    }

    /// The ray's hit on cell `(i, j)` within `[ta, tb]`: each triangle's plane solved for `t`.
    #[inline]
    fn cast_cell(
        &self,
        i: usize,
        j: usize,
        o: [f32; 3],
        d: [f32; 3],
        ta: f32,
        tb: f32,
    ) -> Option<f32> {
        let (h00, h10, h01, h11) = (
            self.h(i, j),
            self.h(i + 1, j),
            self.h(i, j + 1),
            self.h(i + 1, j + 1),
        );
        let u0 = (o[0] - self.origin_m[0] as f32) * self.inverse_cell - i as f32;
        let v0 = (o[1] - self.origin_m[1] as f32) * self.inverse_cell - j as f32;
        let (du, dv) = (d[0] * self.inverse_cell, d[1] * self.inverse_cell);
        let eps = 1e-4 * (tb - ta).abs().max(1e-3);
        let solve = |h: f32, a: f32, b: f32, lower: bool| {
            // o.z + d.z t = h + a (u0 + du t) + b (v0 + dv t)
            let f0 = o[2] - h - a * u0 - b * v0;
            let f1 = d[2] - a * du - b * dv;
            if f1.abs() < 1e-12 {
                return None;
            }
            let t = -f0 / f1;
            if t < ta - eps || t > tb + eps {
                return None;
            }
            let (u, v) = (u0 + du * t, v0 + dv * t);
            let inside = if lower { u >= v - 1e-4 } else { v >= u - 1e-4 };
            inside.then_some(t)
        };
        let lower = solve(h00, h10 - h00, h11 - h10, true);
        let upper = solve(h00, h11 - h01, h01 - h00, false);
        match (lower, upper) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }
}

#[cfg(test)]
#[path = "ground_field_tests.rs"]
mod tests;
