//! Returns below the ground: reflections off wet road or glass show up as mirror images of cars
//! and façades under the road (Patchwork++ removes such "reflected noise" before fitting), and
//! any ray that leaks through a surface lands below it. A cluster of them would become the
//! lowest returns of its cells and drag the whole slope-filtered ground down with it.
//!
//! A cell's lowest return may lie at most [`DEPTH_M`] below the median of the lowest returns in
//! its 8 m block (the typical ground there: most cells with returns see ground); below that it
//! is discarded and the cell's lows are taken again from the returns above.

use crate::features::grid::GridWindow;
use crate::features::ground_cells::CellLows;

/// Side of a block, in cells: large enough that a mirrored car (2 × 5 m) is a minority of its
/// cells, small enough that a 10 % grade moves the ground by only ±0.4 m across it.
const BLOCK: usize = 8;
/// How far a cell's lowest return may lie below its block's median low, metres: a ditch, a
/// kerb drop and the grade across half a block fit, a car mirrored a metre under the road not.
pub(crate) const DEPTH_M: f64 = 0.5;

/// Lifts the lows of cells whose lowest returns lie more than [`DEPTH_M`] below their block's
/// median low to the lowest returns above that floor (`+∞` if none).
pub(crate) fn lift_pits(points_in_world: &[[f64; 3]], window: &GridWindow, lows: &mut CellLows) {
    let floors = block_floors(&lows.low_m, window);
    let pits: Vec<bool> = lows
        .low_m
        .iter()
        .zip(&floors)
        .map(|(&low, &floor)| low < floor)
        .collect();
    if !pits.contains(&true) {
        return;
    }
    let mut lowest = vec![[f64::INFINITY; 2]; window.len()];
    let mut counts = vec![0u32; window.len()];
    for (p, &k) in points_in_world.iter().zip(&lows.cell_of_point) {
        let k = k as usize;
        if k < pits.len() && pits[k] && p[2] >= floors[k] {
            counts[k] += 1;
            CellLows::keep_lowest(&mut lowest[k], p[2]);
        }
    }
    for (k, &pit) in pits.iter().enumerate() {
        if pit {
            lows.low_m[k] = CellLows::robust_low(&lowest[k], counts[k]);
        }
    }
}

/// The floor of every cell: its block's median low minus [`DEPTH_M`] (`-∞` in blocks without
/// returns).
fn block_floors(low_m: &[f64], window: &GridWindow) -> Vec<f64> {
    let (cols, rows) = (window.cols, window.rows);
    let (block_cols, block_rows) = (cols.div_ceil(BLOCK), rows.div_ceil(BLOCK));
    let mut block_floor = vec![f64::NEG_INFINITY; block_cols * block_rows];
    let mut values = Vec::with_capacity(BLOCK * BLOCK);
    for (b, floor) in block_floor.iter_mut().enumerate() {
        let (bc, br) = (b % block_cols, b / block_cols);
        values.clear();
        for r in br * BLOCK..((br + 1) * BLOCK).min(rows) {
            let row = &low_m[r * cols..(r + 1) * cols];
            let cells = &row[bc * BLOCK..((bc + 1) * BLOCK).min(cols)];
            values.extend(cells.iter().copied().filter(|v| v.is_finite()));
        }
        if !values.is_empty() {
            let mid = values.len() / 2;
            let (_, median, _) = values.select_nth_unstable_by(mid, f64::total_cmp);
            *floor = *median - DEPTH_M;
        }
    }
    (0..cols * rows)
        .map(|k| block_floor[(k / cols / BLOCK) * block_cols + (k % cols) / BLOCK])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mirrored_car_under_the_road_is_dropped_and_the_road_above_it_kept() {
        let w = GridWindow::centred([0.0, 0.0], 8.0, 1.0);
        let mut points = Vec::new();
        for i in 0..64 {
            for j in 0..64 {
                let (x, y) = (-8.0 + 0.25 * f64::from(i), -8.0 + 0.25 * f64::from(j));
                points.push([x, y, 0.02 * x]);
                // A car's mirror image a metre under the road over 2 × 4 m.
                if (0.0..4.0).contains(&x) && (1.0..3.0).contains(&y) {
                    points.push([x, y, -1.2 + 0.02 * x]);
                }
            }
        }
        let mut lows = CellLows::bin(&points, &w);
        let (c, r) = w.cell_of(2.5, 2.5).unwrap();
        assert!(lows.low_m[w.index(c, r)] < -1.0);
        lift_pits(&points, &w, &mut lows);
        for (k, low) in lows.low_m.iter().enumerate() {
            let x = w.centre_of(k % w.cols, k / w.cols)[0];
            assert!((low - 0.02 * x).abs() < 0.03, "cell {k}: {low}");
        }
    }

    #[test]
    fn a_ten_percent_grade_keeps_every_low() {
        let w = GridWindow::centred([0.0, 0.0], 8.0, 1.0);
        let points: Vec<[f64; 3]> = (0..1024)
            .map(|k| {
                let (x, y) = (-8.0 + 0.5 * (k % 32) as f64, -8.0 + 0.5 * (k / 32) as f64);
                [x, y, 0.1 * x]
            })
            .collect();
        let mut lows = CellLows::bin(&points, &w);
        let before = lows.low_m.clone();
        lift_pits(&points, &w, &mut lows);
        assert_eq!(lows.low_m, before);
    }
}
