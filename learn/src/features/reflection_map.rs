//! The reflection map (thesis 2.1.1, Eq. 2.8): per cell hits / (hits + misses), misses from
//! Bresenham tracing of the sliced beams, with some of each count spread to the neighbours.

use rayon::prelude::*;

use crate::features::grid::{GridMap, GridWindow};
use crate::features::line::add_misses;
use crate::features::slice::SlicedBeam;

/// Builds one sweep's reflection map on `window` (not accumulated over time, thesis 2.1.1).
///
/// Steps: count a hit in the end cell of every beam ending in the slice and a miss in every other
/// cell Bresenham's line visits; spread both counts with the separable kernel
/// `[spread, 1 − 2·spread, spread]` along x then y (spreading the counts before the ratio equals
/// spreading every single hit and miss); then `hits / (hits + misses)`, and `prior` where no mass
/// arrived. Cells outside the window read `prior` too.
pub fn reflection_map(
    beams: &[SlicedBeam],
    window: &GridWindow,
    prior: f64,
    spread: f64,
) -> GridMap {
    let mut hits = vec![0f32; window.len()];
    let mut misses = vec![0f32; window.len()];
    for beam in beams {
        trace_beam(beam, window, &mut hits, &mut misses);
    }
    let s = spread as f32;
    rayon::join(
        || smooth_rows(&mut hits, window.cols, s),
        || smooth_rows(&mut misses, window.cols, s),
    );
    let values = smooth_columns_and_divide(&hits, &misses, window, s, prior);
    GridMap::from_values(*window, values, prior).unwrap_or_else(|| GridMap::filled(*window, prior))
}

/// Adds one beam's hit and misses; the part outside the window is skipped.
fn trace_beam(beam: &SlicedBeam, window: &GridWindow, hits: &mut [f32], misses: &mut [f32]) {
    let a = window.to_local(beam.start_xy[0], beam.start_xy[1]);
    let b = window.to_local(beam.end_xy[0], beam.end_xy[1]);
    let (cols, rows) = (window.cols as f64, window.rows as f64);
    let end_cell = (b[0].floor(), b[1].floor());
    let end_inside =
        end_cell.0 >= 0.0 && end_cell.1 >= 0.0 && end_cell.0 < cols && end_cell.1 < rows;
    if beam.hit && end_inside {
        hits[window.index(end_cell.0 as usize, end_cell.1 as usize)] += 1.0;
    }
    let Some((ca, cb)) = clip_to_box(a, b, cols, rows) else {
        return;
    };
    let last = |v: f64, n: f64| (v.floor() as i64).clamp(0, n as i64 - 1);
    let (x0, y0) = (last(ca[0], cols), last(ca[1], rows));
    let (x1, y1) = (last(cb[0], cols), last(cb[1], rows));
    // The end cell is the hit itself when the beam ends in the slice inside the window.
    let skip_last = beam.hit && end_inside && (x1, y1) == (end_cell.0 as i64, end_cell.1 as i64);
    add_misses(misses, window.cols, (x0, y0), (x1, y1), skip_last);
}

/// Clips the segment `a → b` to the box `[0, cols] × [0, rows]` (Liang–Barsky).
fn clip_to_box(a: [f64; 2], b: [f64; 2], cols: f64, rows: f64) -> Option<([f64; 2], [f64; 2])> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-d[0], a[0]),
        (d[0], cols - a[0]),
        (-d[1], a[1]),
        (d[1], rows - a[1]),
    ] {
        if p.abs() < 1e-15 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then(|| {
        let at = |t: f64| [a[0] + t * d[0], a[1] + t * d[1]];
        (at(t0), at(t1))
    })
}

/// Spreads counts along x in place with `[s, 1 − 2s, s]`; mass leaving the window is dropped.
fn smooth_rows(values: &mut [f32], cols: usize, s: f32) {
    if s == 0.0 {
        return;
    }
    let c = 1.0 - 2.0 * s;
    values.par_chunks_mut(cols).for_each(|row| {
        let mut left = 0.0;
        for x in 0..cols {
            let here = row[x];
            let right = if x + 1 < cols { row[x + 1] } else { 0.0 };
            row[x] = c * here + s * (left + right);
            left = here;
        }
    });
}

/// Row `r` of a row-major grid with `cols` columns, if `r` is given.
fn row_of(values: &[f32], r: Option<usize>, cols: usize) -> Option<&[f32]> {
    r.map(|r| &values[r * cols..(r + 1) * cols])
}

/// Spreads both counts along y with `[s, 1 − 2s, s]` and returns hits / (hits + misses) per
/// cell, `prior` where no mass arrived (thesis Eq. 2.8).
fn smooth_columns_and_divide(
    hits: &[f32],
    misses: &[f32],
    window: &GridWindow,
    s: f32,
    prior: f64,
) -> Vec<f64> {
    let (cols, rows, c) = (window.cols, window.rows, 1.0 - 2.0 * s);
    let mut out = vec![prior; window.len()];
    out.par_chunks_mut(cols).enumerate().for_each(|(y, out)| {
        let row = |v, r| row_of(v, r, cols);
        let (below, above) = (y.checked_sub(1), (y + 1 < rows).then_some(y + 1));
        let (h, m) = (row(hits, Some(y)), row(misses, Some(y)));
        let (hb, mb, ha, ma) = (
            row(hits, below),
            row(misses, below),
            row(hits, above),
            row(misses, above),
        );
        let (Some(h), Some(m)) = (h, m) else { return };
        for x in 0..cols {
            let side = |v: Option<&[f32]>| v.map_or(0.0, |r| r[x]);
            let hx = c * h[x] + s * (side(hb) + side(ha));
            let mx = c * m[x] + s * (side(mb) + side(ma));
            let total = f64::from(hx) + f64::from(mx);
            if total > 1e-9 {
                out[x] = f64::from(hx) / total;
            }
        }
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn window() -> GridWindow {
        GridWindow::centred([0.0, 0.0], 2.0, 0.1)
    }

    fn beam(start: [f64; 2], end: [f64; 2], hit: bool) -> SlicedBeam {
        SlicedBeam {
            start_xy: start,
            end_xy: end,
            hit,
        }
    }

    #[test]
    fn a_single_beam_marks_its_end_cell_as_hit_and_the_cells_before_as_missed() {
        let w = window();
        let map = reflection_map(&[beam([0.05, 0.05], [1.05, 0.05], true)], &w, 0.5, 0.0);
        let (ec, er) = w.cell_of(1.05, 0.05).unwrap();
        assert_eq!(map.get(ec as i64, er as i64), 1.0);
        for k in 0..10 {
            let (c, r) = w.cell_of(0.05 + 0.1 * f64::from(k), 0.05).unwrap();
            assert_eq!(map.get(c as i64, r as i64), 0.0, "cell {k} before the hit");
        }
        assert_eq!(
            map.get(ec as i64 + 1, er as i64),
            0.5,
            "behind the hit stays at the prior"
        );
        assert_eq!(
            map.get(ec as i64, er as i64 + 1),
            0.5,
            "beside the beam stays at the prior"
        );
    }

    #[test]
    fn a_beam_leaving_the_slice_marks_every_cell_it_crosses_as_missed() {
        let w = window();
        let map = reflection_map(&[beam([0.05, 0.05], [0.05, 0.55], false)], &w, 0.01, 0.0);
        for k in 0..6 {
            assert_eq!(map.at(0.05, 0.05 + 0.1 * f64::from(k)), 0.0, "cell {k}");
        }
        assert_eq!(map.at(0.05, 0.65), 0.01);
    }

    #[test]
    fn spreading_gives_neighbours_a_share_of_the_hit() {
        let w = window();
        let map = reflection_map(
            &[beam([0.05, 0.05], [1.05, 0.05], true)],
            &w,
            0.5,
            1.0 / 6.0,
        );
        // Beside the hit cell the hit's spread (1/9) meets the spread of the misses beside it.
        let side = map.at(1.05, 0.15);
        assert!(side > 0.0 && side < 1.0, "{side}");
        assert!(
            map.at(1.05, 0.05) > 0.6,
            "the hit cell stays mostly occupied"
        );
        assert_eq!(map.at(1.05, 0.45), 0.5, "three cells away nothing arrives");
    }

    #[test]
    fn beams_outside_the_window_are_clipped_not_wrapped() {
        let w = window();
        let map = reflection_map(&[beam([-10.0, 0.05], [10.0, 0.05], false)], &w, 0.5, 0.0);
        assert!(map.values().iter().filter(|&&v| v == 0.0).count() == w.cols);
    }
}
