//! The first steps of the ground estimate: each coarse cell's lowest robust return, and the
//! moments of its ground band (the returns a little above that lowest one).
//!
//! As in grid-based ground segmentation (GroundGrid, Steinke et al. 2024; the elevation maps of
//! Himmelsbach et al. 2010), the lowest returns in a cell of a metre or two are the ground
//! wherever the ground is seen at all: objects stand on it, canopies hang over it.

use rayon::prelude::*;

use crate::features::grid::GridWindow;

/// Least points of a parallel task that maps points to their cells.
const TASK_POINTS: usize = 8192;
/// Runs of points binned in parallel, then merged (a window's worth of cells each).
const RUNS: usize = 2;

/// A cell's lowest robust height: the single lowest return is dropped once the cell holds this
/// many returns (one noisy or mixed return must not set the ground).
const DROP_LOWEST_FROM: u32 = 4;
/// Returns this far above the cell's lowest robust height belong to its ground band: the lower
/// half of a cell on a 10 % grade, and only the foot of a wall or car face standing in the cell
/// (whose returns would lift the band's mean height by half the band).
pub(crate) const BAND_M: f64 = 0.03;
/// Returns this far below the lowest robust height still count (range noise).
const BELOW_M: f64 = 0.05;
/// Returns between these heights above the lowest robust height make a cell look like the foot of
/// a vertical face (a wall, a car, a hedge) rather than open ground: above any grade or curb
/// across one cell, within the first metre of the face.
const FACE_M: [f64; 2] = [0.25, 1.0];

/// Per cell of a window: how many returns fell in it and its lowest robust height (`+∞` if
/// empty). Row-major like every grid here.
#[derive(Debug, Clone)]
pub(crate) struct CellLows {
    /// Cell of every point (`u32::MAX` outside the window), in point order.
    pub(crate) cell_of_point: Vec<u32>,
    /// Lowest robust height per cell, world z, metres.
    pub(crate) low_m: Vec<f64>,
}

impl CellLows {
    /// Bins world points into `window`'s cells and keeps each cell's two lowest heights.
    /// Runs of points in parallel tasks, merged: a cell's two lowest heights are the two lowest
    /// of its runs' two lowest, and its count their sum, so the result is the one-task loop's.
    pub(crate) fn bin(points_in_world: &[[f64; 3]], window: &GridWindow) -> Self {
        let inv_cell = 1.0 / window.cell_m;
        let (x0, y0) = (
            window.origin_col as f64 * window.cell_m,
            window.origin_row as f64 * window.cell_m,
        );
        let (cols, rows) = (window.cols as f64, window.rows as f64);
        let cell_of_point: Vec<u32> = points_in_world
            .par_iter()
            .with_min_len(TASK_POINTS)
            .map(|p| {
                // Truncation is the floor here: negative coordinates are outside.
                let (u, v) = ((p[0] - x0) * inv_cell, (p[1] - y0) * inv_cell);
                if !(u >= 0.0 && v >= 0.0 && u < cols && v < rows) {
                    return u32::MAX;
                }
                (v as usize * window.cols + u as usize) as u32
            })
            .collect();
        let run = points_in_world.len().div_ceil(RUNS).max(1);
        let parts: Vec<(Vec<[f64; 2]>, Vec<u32>)> = points_in_world
            .par_chunks(run)
            .zip(cell_of_point.par_chunks(run))
            .map(|(points, cells)| {
                let mut lowest = vec![[f64::INFINITY; 2]; window.len()];
                let mut counts = vec![0u32; window.len()];
                for (p, &k) in points.iter().zip(cells) {
                    if let Some(low) = lowest.get_mut(k as usize) {
                        counts[k as usize] += 1;
                        Self::keep_lowest(low, p[2]);
                    }
                }
                (lowest, counts)
            })
            .collect();
        let mut parts = parts.into_iter();
        let (mut lowest, mut counts) = parts.next().unwrap_or_else(|| {
            (
                vec![[f64::INFINITY; 2]; window.len()],
                vec![0; window.len()],
            )
        });
        for (part_lowest, part_counts) in parts {
            for (low, part) in lowest.iter_mut().zip(&part_lowest) {
                part.iter().for_each(|&z| Self::keep_lowest(low, z));
            }
            counts
                .iter_mut()
                .zip(&part_counts)
                .for_each(|(n, m)| *n += m);
        }
        let low_m = lowest
            .iter()
            .zip(&counts)
            .map(|(low, &n)| Self::robust_low(low, n))
            .collect();
        Self {
            cell_of_point,
            low_m,
        }
    }

    /// Keeps the two lowest heights seen, lowest first.
    pub(crate) fn keep_lowest(low: &mut [f64; 2], z: f64) {
        if z < low[0] {
            *low = [z, low[0]];
        } else if z < low[1] {
            low[1] = z;
        }
    }

    /// The lowest robust height of a cell with `count` returns whose two lowest are `low`.
    pub(crate) fn robust_low(low: &[f64; 2], count: u32) -> f64 {
        if count >= DROP_LOWEST_FROM {
            low[1]
        } else {
            low[0]
        }
    }
}

/// Moments of one cell's ground band in window-local metres, `[1, x, y, z, xx, xy, yy, xz, yz]`,
/// each averaged over the band and weighted by the cell's share of open ground (below).
pub(crate) type Moments = [f64; 9];

/// The ground band moments of every accepted cell (zeros elsewhere).
///
/// A cell weighs `(band / (band + face))²`, where `band` and `face` count its returns in the band
/// and in [`FACE_M`]: 1 for open ground however densely it is hit, less at the foot of a face,
/// and nothing once the face has as many returns as the band: then the lowest return is most
/// likely the lowest *visible* stretch of a wall or car whose foot is hidden (behind a parked
/// car, or between far rings), which the slope filter cannot tell from ground seen nowhere near
/// other ground. On the `ideal` world (flat ground) a linear weight left 10 % of the cells
/// within 40 m more than 0.2 m off z = 0 and 4 % more returns in the slice than above z = 0.
pub(crate) fn band_moments(
    points_in_world: &[[f64; 3]],
    window: &GridWindow,
    lows: &CellLows,
    ground: &[bool],
) -> Vec<Moments> {
    let mut sums = vec![[0.0; 9]; window.len()];
    let mut face = vec![0u32; window.len()];
    let (x0, y0) = (
        window.origin_col as f64 * window.cell_m,
        window.origin_row as f64 * window.cell_m,
    );
    for (p, &k) in points_in_world.iter().zip(&lows.cell_of_point) {
        let k = k as usize;
        if k >= sums.len() || !ground[k] {
            continue;
        }
        let low = lows.low_m[k];
        if p[2] < low - BELOW_M || p[2] > low + BAND_M {
            if (low + FACE_M[0]..=low + FACE_M[1]).contains(&p[2]) {
                face[k] += 1;
            }
            continue;
        }
        let (x, y, z) = (p[0] - x0, p[1] - y0, p[2]);
        let m = &mut sums[k];
        for (slot, v) in m
            .iter_mut()
            .zip([1.0, x, y, z, x * x, x * y, y * y, x * z, y * z])
        {
            *slot += v;
        }
    }
    for (m, &face) in sums.iter_mut().zip(&face) {
        let band = m[0];
        if band > 0.0 {
            let face = f64::from(face);
            let weight = if face >= band {
                0.0
            } else {
                (band / (band + face)).powi(2)
            };
            m.iter_mut().for_each(|v| *v *= weight / band);
        }
    }
    sums
}

#[cfg(test)]
mod tests {
    use super::*;

    fn window() -> GridWindow {
        GridWindow::centred([0.0, 0.0], 2.0, 1.0)
    }

    #[test]
    fn a_cell_keeps_its_lowest_return_and_drops_a_lone_outlier_once_it_has_four() {
        let w = window();
        let few = CellLows::bin(&[[0.5, 0.5, 0.3], [0.5, 0.6, 0.1]], &w);
        let k = w.index(
            w.cell_of(0.5, 0.5).unwrap().0,
            w.cell_of(0.5, 0.5).unwrap().1,
        );
        assert_eq!(few.low_m[k], 0.1);
        let many = CellLows::bin(
            &[
                [0.5, 0.5, 0.3],
                [0.5, 0.6, -0.8],
                [0.2, 0.6, 0.02],
                [0.4, 0.1, 0.9],
            ],
            &w,
        );
        assert_eq!(many.low_m[k], 0.02);
        assert!(many.low_m.iter().filter(|v| v.is_finite()).count() == 1);
    }

    #[test]
    fn binning_in_parallel_runs_gives_the_one_run_loop_exactly() {
        let w = GridWindow::centred([0.0, 0.0], 6.0, 1.0);
        // Points over the window and beyond it, heights repeating so cells hold ties.
        let points: Vec<[f64; 3]> = (0..20_001)
            .map(|k| {
                let t = k as f64;
                [
                    7.5 * (0.37 * t).sin(),
                    7.5 * (0.23 * t).cos(),
                    0.1 * (k % 13) as f64 - 0.4,
                ]
            })
            .collect();
        let binned = CellLows::bin(&points, &w);
        let (mut lowest, mut counts) = (vec![[f64::INFINITY; 2]; w.len()], vec![0u32; w.len()]);
        for (p, &k) in points.iter().zip(&binned.cell_of_point) {
            let expected = w
                .cell_of(p[0], p[1])
                .map_or(u32::MAX, |(c, r)| w.index(c, r) as u32);
            assert_eq!(k, expected, "{p:?}");
            if let Some(low) = lowest.get_mut(k as usize) {
                counts[k as usize] += 1;
                CellLows::keep_lowest(low, p[2]);
            }
        }
        let serial: Vec<f64> = lowest
            .iter()
            .zip(&counts)
            .map(|(low, &n)| CellLows::robust_low(low, n))
            .collect();
        assert_eq!(binned.low_m, serial, "bit for bit");
        assert!(counts.iter().filter(|&&n| n >= DROP_LOWEST_FROM).count() > 20);
    }

    #[test]
    fn band_moments_average_the_returns_near_the_lowest_and_weigh_the_cell_by_its_open_ground() {
        let w = window();
        let points = [
            [0.25, 0.5, 0.0],
            [0.75, 0.5, 0.02],
            [0.5, 0.5, 1.2],
            [0.5, 0.6, 0.3],
        ];
        let lows = CellLows::bin(&points, &w);
        let (c, r) = w.cell_of(0.5, 0.5).unwrap();
        let k = w.index(c, r);
        let mut accepted = vec![false; w.len()];
        accepted[k] = true;
        let m = band_moments(&points, &w, &lows, &accepted);
        let x0 = w.origin_col as f64;
        // Two band returns and one face return (0.3 m), the 1.2 m one left out: weight (2/3)².
        assert!((m[k][0] - 4.0 / 9.0).abs() < 1e-12);
        assert!(
            (m[k][1] / m[k][0] - (0.5 - x0)).abs() < 1e-12,
            "mean x of the band"
        );
        assert!(
            (m[k][3] / m[k][0] - 0.01).abs() < 1e-12,
            "mean z of the band"
        );
        accepted[k] = false;
        assert_eq!(band_moments(&points, &w, &lows, &accepted)[k], [0.0; 9]);
    }
}
