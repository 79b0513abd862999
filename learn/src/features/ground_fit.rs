//! The ground height at every cell centre: a least-squares plane through the ground bands of the
//! cells around it (region-wise plane fitting, as Patchwork does per bin), in the smallest
//! square window whose ground cells pin a plane down (enough of them, spread in both
//! directions). Near the sensor the 3 × 3 window smooths over 3 m. A single ring arc does not
//! pin the slope across it, so its window grows to the next ring. A cell without ground of its
//! own (under a car, between far rings, 6 m apart at 40 m) takes the smallest window whose ground
//! surrounds it, up to 9 m; a wider hole is a shadow seen from one side (behind parked cars or
//! a wall), held at the level of the nearest ground's rim.
//!
//! Summed-area tables of the cells' moments give any window's sums in O(1), so the whole grid
//! costs a few operations per cell whatever the window sizes.

use crate::features::grid::GridWindow;
use crate::features::ground_cells::Moments;

/// Window half-sides tried in turn, in cells; past the last, the whole grid.
const RADII: [usize; 6] = [1, 2, 4, 8, 16, 32];
/// How far beyond its ground (in standard deviations of the ground cells' positions) a window's
/// plane is followed: two, about a metre past a strip of two rows.
const RIM_SIGMAS: f64 = 2.0;
/// The largest window half-side a hole is interpolated across, in cells: 9 m windows span the
/// gap between two rings at 40 m and the hole under a truck. Wider holes are shadows (behind
/// parked cars, walls), where a plane through a wide window is tilted by whatever little it sees
/// on the far side (the upper part of a wall whose foot is hidden); they are held at the level
/// of their nearest rim instead.
const MAX_INTERPOLATION_RADIUS: usize = 4;
/// Ground cells a window needs before its plane is trusted.
const MIN_CELLS: f64 = 3.0;
/// Variance of the ground in a window along its narrowest direction, m², before the window's
/// plane is trusted: two neighbouring rows of cells give 0.33, a single ring arc a few hundredths.
const MIN_SPREAD_M2: f64 = 0.1;
/// Ridge on the slopes, m² per cell of weight: keeps the plane level along directions nothing
/// spans (the whole-grid fallback), and biases a trusted window's slopes by at most 1 %.
const RIDGE_M2: f64 = 1e-3;

/// Summed-area tables of per-cell moments: entry `(c, r)` holds the sum over cells `< c, < r`.
pub(crate) struct MomentTable {
    cols: usize,
    rows: usize,
    sums: Vec<Moments>,
}

impl MomentTable {
    /// The table of `moments` (row-major on `window`).
    pub(crate) fn new(moments: &[Moments], window: &GridWindow) -> Self {
        let (cols, rows) = (window.cols, window.rows);
        let stride = cols + 1;
        let mut sums = vec![[0.0; 9]; stride * (rows + 1)];
        for r in 0..rows {
            let mut row_sum = [0.0; 9];
            for c in 0..cols {
                let m = &moments[r * cols + c];
                for k in 0..9 {
                    row_sum[k] += m[k];
                }
                let (above, here) = (r * stride + c + 1, (r + 1) * stride + c + 1);
                for k in 0..9 {
                    sums[here][k] = sums[above][k] + row_sum[k];
                }
            }
        }
        Self { cols, rows, sums }
    }

    /// Sums over columns `c0..c1` and rows `r0..r1` (exclusive ends).
    fn window_sum(&self, c0: usize, c1: usize, r0: usize, r1: usize) -> Moments {
        let stride = self.cols + 1;
        let at = |c: usize, r: usize| &self.sums[r * stride + c];
        let (a, b, c, d) = (at(c1, r1), at(c0, r1), at(c1, r0), at(c0, r0));
        std::array::from_fn(|k| a[k] - b[k] - c[k] + d[k])
    }

    /// Ground height at the centre of every cell; `fallback_m` where the grid holds no ground.
    pub(crate) fn fit_heights(&self, window: &GridWindow, fallback_m: f64) -> Vec<f64> {
        let mut heights = Vec::with_capacity(self.cols * self.rows);
        let whole = self.window_sum(0, self.cols, 0, self.rows);
        for r in 0..self.rows {
            for c in 0..self.cols {
                let centre = [
                    (c as f64 + 0.5) * window.cell_m,
                    (r as f64 + 0.5) * window.cell_m,
                ];
                let height = self
                    .height_at(c, r, centre)
                    .or_else(|| plane_at(&whole, centre))
                    .unwrap_or(fallback_m);
                heights.push(height);
            }
        }
        heights
    }

    /// The plane of the smallest window around cell `(c, r)` that pins one down. A cell without
    /// ground of its own takes the smallest window whose ground also surrounds it; if none does
    /// (a shadow seen from one side only), the smallest window's plane is followed to the rim of
    /// its ground and held level beyond. `None` if no window pins a plane.
    fn height_at(&self, c: usize, r: usize, centre: [f64; 2]) -> Option<f64> {
        // Below any real cell's weight; the table's differences leave rounding dust.
        let hole = self.window_sum(c, c + 1, r, r + 1)[0] < 1e-9;
        let mut one_sided = None;
        for k in RADII {
            let sums = self.window_sum(
                c.saturating_sub(k),
                (c + k + 1).min(self.cols),
                r.saturating_sub(k),
                (r + k + 1).min(self.rows),
            );
            if !pins_a_plane(&sums) {
                continue;
            }
            if !hole || (k <= MAX_INTERPOLATION_RADIUS && surrounds(&sums, centre)) {
                return plane_at(&sums, centre);
            }
            one_sided.get_or_insert(sums);
        }
        one_sided.and_then(|sums| plane_at(&sums, rim_point(&sums, centre)))
    }
}

/// Mean and covariance `(vxx, vxy, vyy)` of the window's ground positions.
fn spread(s: &Moments) -> ([f64; 2], [f64; 3]) {
    let w = s[0];
    let (mx, my) = (s[1] / w, s[2] / w);
    let cov = [s[4] / w - mx * mx, s[5] / w - mx * my, s[6] / w - my * my];
    ([mx, my], cov)
}

/// Squared Mahalanobis distance of `p` from the window's ground positions.
fn mahalanobis2(s: &Moments, p: [f64; 2]) -> f64 {
    let ([mx, my], [vxx, vxy, vyy]) = spread(s);
    let det = vxx * vyy - vxy * vxy;
    let (dx, dy) = (p[0] - mx, p[1] - my);
    (vyy * dx * dx - 2.0 * vxy * dx * dy + vxx * dy * dy) / det
}

/// True if `centre` lies within [`RIM_SIGMAS`] standard deviations (Mahalanobis) of the window's
/// ground cells: the plane then interpolates across the hole, or extends a little beyond its
/// ground, instead of carrying the slope of a strip along its rim (the foot of a wall) far into a
/// shadow.
fn surrounds(s: &Moments, centre: [f64; 2]) -> bool {
    mahalanobis2(s, centre) <= RIM_SIGMAS * RIM_SIGMAS
}

/// The point [`RIM_SIGMAS`] standard deviations from the ground's mean towards `centre`.
fn rim_point(s: &Moments, centre: [f64; 2]) -> [f64; 2] {
    let ([mx, my], _) = spread(s);
    let scale = (mahalanobis2(s, centre).sqrt() / RIM_SIGMAS)
        .max(1.0)
        .recip();
    [mx + (centre[0] - mx) * scale, my + (centre[1] - my) * scale]
}

/// True if the window's ground cells are enough and spread in both directions.
fn pins_a_plane(s: &Moments) -> bool {
    if s[0] < MIN_CELLS {
        return false;
    }
    let (_, [vxx, vxy, vyy]) = spread(s);
    let half_trace = 0.5 * (vxx + vyy);
    let smallest = half_trace - (0.25 * (vxx - vyy).powi(2) + vxy * vxy).sqrt();
    smallest >= MIN_SPREAD_M2
}

/// The least-squares plane `z = a + b·(x − cx) + c·(y − cy)` through the moment sums, with the
/// slope ridge, evaluated at the centre: `a`. `None` without weight.
fn plane_at(s: &Moments, [cx, cy]: [f64; 2]) -> Option<f64> {
    let w = s[0];
    if w <= 0.0 {
        return None;
    }
    // Moments about the centre.
    let sx = s[1] - cx * w;
    let sy = s[2] - cy * w;
    let sz = s[3];
    let sxx = s[4] - 2.0 * cx * s[1] + cx * cx * w + RIDGE_M2 * w;
    let sxy = s[5] - cx * s[2] - cy * s[1] + cx * cy * w;
    let syy = s[6] - 2.0 * cy * s[2] + cy * cy * w + RIDGE_M2 * w;
    let sxz = s[7] - cx * sz;
    let syz = s[8] - cy * sz;
    // Normal equations [[w, sx, sy], [sx, sxx, sxy], [sy, sxy, syy]] · (a, b, c) = (sz, sxz, syz),
    // solved for a by eliminating the slopes (their 2 × 2 block is positive definite).
    let det = sxx * syy - sxy * sxy;
    if det <= 0.0 || !det.is_finite() {
        return Some(sz / w);
    }
    // (b, c) = B⁻¹ (g − a·h) with B the slope block, g = (sxz, syz), h = (sx, sy).
    let inv = [syy / det, -sxy / det, sxx / det];
    let bh = [inv[0] * sx + inv[1] * sy, inv[1] * sx + inv[2] * sy];
    let bg = [inv[0] * sxz + inv[1] * syz, inv[1] * sxz + inv[2] * syz];
    let denom = w - (sx * bh[0] + sy * bh[1]);
    if denom <= 1e-12 * w {
        return Some(sz / w);
    }
    Some((sz - (sx * bg[0] + sy * bg[1])) / denom)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Moments of one cell whose ground band is the points `pts` (window-local x, y; world z).
    fn cell(pts: &[[f64; 3]]) -> Moments {
        let mut m = [0.0; 9];
        for &[x, y, z] in pts {
            for (slot, v) in m
                .iter_mut()
                .zip([1.0, x, y, z, x * x, x * y, y * y, x * z, y * z])
            {
                *slot += v;
            }
        }
        let n = pts.len() as f64;
        m.map(|v| v / n)
    }

    #[test]
    fn a_sloped_plane_is_recovered_at_the_centres_of_empty_cells_too() {
        let w = GridWindow::centred([0.0, 0.0], 10.0, 1.0);
        let truth = |x: f64, y: f64| 1.0 + 0.05 * x - 0.03 * y;
        // Ground seen in every third column only, from off-centre points.
        let moments: Vec<Moments> = (0..w.len())
            .map(|k| {
                let (c, r) = (k % w.cols, k / w.cols);
                if c % 3 != 0 {
                    return [0.0; 9];
                }
                let (x, y) = (c as f64 + 0.2, r as f64 + 0.7);
                cell(&[
                    [x, y, truth(x, y)],
                    [x + 0.5, y - 0.4, truth(x + 0.5, y - 0.4)],
                ])
            })
            .collect();
        let heights = MomentTable::new(&moments, &w).fit_heights(&w, 0.0);
        for (k, h) in heights.iter().enumerate() {
            let (c, r) = (k % w.cols, k / w.cols);
            if r == 0 || r + 1 == w.rows {
                // Beyond the outermost rows of ground the height is held level.
                continue;
            }
            let expected = truth(c as f64 + 0.5, r as f64 + 0.5);
            // The slope ridge biases the extrapolation by well under a millimetre.
            assert!(
                (h - expected).abs() < 1e-3,
                "cell {c},{r}: {h} vs {expected}"
            );
        }
    }

    #[test]
    fn a_single_arc_of_ground_sets_a_level_height_across_it() {
        let w = GridWindow::centred([0.0, 0.0], 3.0, 1.0);
        // Ground only along row 2, at 0.4 m: nothing constrains the slope across the row, so
        // every window falls back to the whole grid.
        let moments: Vec<Moments> = (0..w.len())
            .map(|k| {
                let (c, r) = (k % w.cols, k / w.cols);
                let x = c as f64 + 0.5;
                if r == 2 {
                    cell(&[[x, 2.5, 0.4]])
                } else {
                    [0.0; 9]
                }
            })
            .collect();
        let heights = MomentTable::new(&moments, &w).fit_heights(&w, 0.0);
        assert!(
            heights.iter().all(|h| (h - 0.4).abs() < 1e-9),
            "{heights:?}"
        );
    }

    #[test]
    fn a_grid_without_ground_takes_the_fallback() {
        let w = GridWindow::centred([0.0, 0.0], 2.0, 1.0);
        let heights = MomentTable::new(&vec![[0.0; 9]; w.len()], &w).fit_heights(&w, -0.3);
        assert!(heights.iter().all(|&h| h == -0.3));
    }
}
