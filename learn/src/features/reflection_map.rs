//! The reflection map (thesis 2.1.1, Eq. 2.8): per cell hits / (hits + misses), with some of each
//! count spread to the neighbours; and, in the same pass, the difference map (thesis Eq. 2.9).

use rayon::prelude::*;

use crate::features::beam_counts::BAND_ROWS;
use crate::features::counts_view::CountsView;
use crate::features::grid::recycled_values;
use crate::features::spread_kernel::{Kernel, neighbour_rows, ratios, spread_row};

/// Row-major values of one prior's maps on the counts' window.
#[derive(Debug)]
pub(crate) struct MapValues {
    /// m_t: the reflection map of the current sweep.
    pub(crate) reflection: Vec<f64>,
    /// m_t − m_{t−1}.
    pub(crate) difference: Vec<f64>,
}

/// Both sweeps' reflection maps from their counts (on one window), for every prior: the current
/// map and the difference. Not accumulated over time (thesis 2.1.1).
///
/// Both counts are spread with the separable kernel `[spread, 1 − 2·spread, spread]` along x then
/// y (spreading the counts before the ratio equals spreading every single hit and miss); a cell
/// is `hits / (hits + misses)`, or the prior where no mass arrived. The prior only fills the
/// unobserved cells, so one pass serves every prior. Bands of rows no count reaches are filled
/// without arithmetic, and within a band only the touched columns are computed.
pub(crate) fn reflection_and_difference(
    prev: &CountsView<'_>,
    curr: &CountsView<'_>,
    priors: &[f64],
    spread: f64,
) -> Vec<MapValues> {
    let window = *curr.window();
    debug_assert_eq!(prev.window(), curr.window());
    let band_len = BAND_ROWS * window.cols;
    let mut outputs: Vec<MapValues> = priors
        .iter()
        .map(|_| MapValues {
            reflection: recycled_values(window.len()),
            difference: recycled_values(window.len()),
        })
        .collect();
    // Per band, the slices of every prior's two maps.
    let mut bands: Vec<Vec<(&mut [f64], &mut [f64])>> = (0..window.rows.div_ceil(BAND_ROWS))
        .map(|_| Vec::with_capacity(priors.len()))
        .collect();
    for out in &mut outputs {
        let slices = out.reflection.chunks_mut(band_len);
        for (band, pair) in bands
            .iter_mut()
            .zip(slices.zip(out.difference.chunks_mut(band_len)))
        {
            band.push(pair);
        }
    }
    let kernel = Kernel::new(spread);
    bands.into_par_iter().enumerate().for_each(|(b, mut maps)| {
        band_pass(b, [prev, curr], priors, kernel, &mut maps);
    });
    outputs
}

/// Fills band `b` of every prior's maps (`maps[k]` belongs to `priors[k]`).
fn band_pass(
    b: usize,
    [prev, curr]: [&CountsView<'_>; 2],
    priors: &[f64],
    kernel: Kernel,
    maps: &mut [(&mut [f64], &mut [f64])],
) {
    let window = curr.window();
    let cols = window.cols;
    let first = b * BAND_ROWS;
    let rows = first..(first + BAND_ROWS).min(window.rows);
    // Columns the 3 × 3 kernel can carry counts of bands b − 1 ..= b + 1 to.
    let touched = (b.saturating_sub(1)..=b + 1)
        .flat_map(|k| [prev.band(k), curr.band(k)])
        .flatten()
        .reduce(|a, c| (a.0.min(c.0), a.1.max(c.1)));
    let span = touched.map(|(lo, hi)| (lo.saturating_sub(1), (hi + 1).min(cols - 1)));
    // Everything outside the span is unobserved in both sweeps: the prior, and no difference.
    for ((reflection, difference), &prior) in maps.iter_mut().zip(priors) {
        match span {
            None => {
                reflection.fill(prior);
                difference.fill(0.0);
            }
            Some((lo, hi)) => {
                for row in reflection.chunks_mut(cols) {
                    row[..lo].fill(prior);
                    row[hi + 1..].fill(prior);
                }
                for row in difference.chunks_mut(cols) {
                    row[..lo].fill(0.0);
                    row[hi + 1..].fill(0.0);
                }
            }
        }
    }
    let Some((lo, hi)) = span else { return };
    let width = hi + 1 - lo;
    // Both counts of both sweeps spread along x, rows first − 1 ..= last + 1 (zero outside the
    // window): `spread[channel][k · width + i]` for row `first − 1 + k`, column `lo + i`.
    let spread_x = |counts: &CountsView<'_>| -> [Vec<f32>; 2] {
        [0, 1].map(|channel| {
            let mut out = vec![0f32; (rows.len() + 2) * width];
            for (k, y) in (rows.start as i64 - 1..=rows.end as i64).enumerate() {
                if y >= 0 && (y as usize) < window.rows {
                    let row = counts.row(channel, y as usize);
                    spread_row(kernel, row, lo, &mut out[k * width..(k + 1) * width]);
                }
            }
            out
        })
    };
    let (sp, sc) = (spread_x(prev), spread_x(curr));
    // Per row, both sweeps' ratios (NaN where unobserved), then every prior's values from them.
    let (mut rp, mut rc) = (vec![0.0; width], vec![0.0; width]);
    for k in 0..rows.len() {
        let [(ph, pm), (ch, cm)] = [&sp, &sc].map(|v| {
            (
                neighbour_rows(&v[0], k, width),
                neighbour_rows(&v[1], k, width),
            )
        });
        ratios(kernel, ph, pm, &mut rp);
        ratios(kernel, ch, cm, &mut rc);
        let cells = k * cols + lo..k * cols + hi + 1;
        for ((reflection, difference), &prior) in maps.iter_mut().zip(priors) {
            let reflection = &mut reflection[cells.clone()];
            let difference = &mut difference[cells.clone()];
            for (((m, d), &c), &p) in reflection.iter_mut().zip(difference).zip(&rc).zip(&rp) {
                let vc = if c.is_nan() { prior } else { c };
                let vp = if p.is_nan() { prior } else { p };
                *m = vc;
                *d = vc - vp;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::features::beam_counts::BeamCounts;
    use crate::features::grid::{GridMap, GridWindow};
    use crate::features::sliced_beam::SlicedBeam;

    fn window() -> GridWindow {
        GridWindow::centred([0.0, 0.0], 2.0, 0.1)
    }

    /// One sweep's reflection map (no previous beams).
    fn reflection_map(beams: &[SlicedBeam], w: &GridWindow, prior: f64, spread: f64) -> GridMap {
        let (prev, curr) = (BeamCounts::trace(&[], w), BeamCounts::trace(beams, w));
        let mut maps = reflection_and_difference(&whole(&prev), &whole(&curr), &[prior], spread);
        GridMap::from_values(*w, maps.remove(0).reflection, prior).unwrap()
    }

    #[test]
    fn a_single_beam_marks_its_end_cell_as_hit_and_the_cells_before_as_missed() {
        let w = window();
        let map = reflection_map(
            &[SlicedBeam::new([0.05, 0.05], [1.05, 0.05], true)],
            &w,
            0.5,
            0.0,
        );
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
        let map = reflection_map(
            &[SlicedBeam::new([0.05, 0.05], [0.05, 0.55], false)],
            &w,
            0.01,
            0.0,
        );
        for k in 0..6 {
            assert_eq!(map.at(0.05, 0.05 + 0.1 * f64::from(k)), 0.0, "cell {k}");
        }
        assert_eq!(map.at(0.05, 0.65), 0.01);
    }

    #[test]
    fn spreading_gives_neighbours_a_share_of_the_hit() {
        let w = window();
        let map = reflection_map(
            &[SlicedBeam::new([0.05, 0.05], [1.05, 0.05], true)],
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
        let map = reflection_map(
            &[SlicedBeam::new([-10.0, 0.05], [10.0, 0.05], false)],
            &w,
            0.5,
            0.0,
        );
        assert!(map.values().iter().filter(|&&v| v == 0.0).count() == w.cols);
    }

    /// The textbook computation on full grids: spread every count along x, then along y, then
    /// divide; no bands, no spans.
    /// The counts on the whole window they were traced on.
    fn whole(counts: &BeamCounts) -> CountsView<'_> {
        CountsView::of(counts, counts.window()).unwrap()
    }

    fn dense_reflection(counts: &BeamCounts, prior: f64, spread: f32) -> Vec<f64> {
        let w = counts.window();
        let (cols, rows) = (w.cols as i64, w.rows as i64);
        let at = |c: i64, r: i64, k: usize| {
            if c < 0 || r < 0 || c >= cols || r >= rows {
                0.0
            } else {
                counts.row(k, r as usize)[c as usize]
            }
        };
        let centre = 1.0 - 2.0 * spread;
        let x_spread = |c: i64, r: i64, k: usize| {
            centre * at(c, r, k) + spread * (at(c - 1, r, k) + at(c + 1, r, k))
        };
        let mut out = Vec::new();
        for r in 0..rows {
            for c in 0..cols {
                let v = |k| {
                    centre * x_spread(c, r, k)
                        + spread * (x_spread(c, r - 1, k) + x_spread(c, r + 1, k))
                };
                let (h, m) = (f64::from(v(0)), f64::from(v(1)));
                out.push(if h + m > 1e-9 { h / (h + m) } else { prior });
            }
        }
        out
    }

    #[test]
    fn banded_maps_equal_the_dense_computation_for_both_priors() {
        // 50 × 50 cells: four bands, beams in some of them and across band edges.
        let w = GridWindow::centred([0.0, 0.0], 2.5, 0.1);
        let prev_beams = [
            SlicedBeam::new([0.0, 0.0], [2.2, 1.55], true),
            SlicedBeam::new([0.0, 0.0], [-2.0, -0.9], false),
        ];
        let curr_beams = [
            SlicedBeam::new([0.1, 0.0], [2.2, 1.65], true),
            SlicedBeam::new([0.1, 0.0], [-0.3, -2.45], true),
            SlicedBeam::new([-3.0, 1.0], [3.0, 1.05], false),
        ];
        let (prev, curr) = (
            BeamCounts::trace(&prev_beams, &w),
            BeamCounts::trace(&curr_beams, &w),
        );
        let maps = reflection_and_difference(&whole(&prev), &whole(&curr), &[0.5, 0.01], 1.0 / 6.0);
        for (out, prior) in maps.iter().zip([0.5, 0.01]) {
            let dense_prev = dense_reflection(&prev, prior, 1.0 / 6.0);
            let dense_curr = dense_reflection(&curr, prior, 1.0 / 6.0);
            for i in 0..w.len() {
                assert_eq!(out.reflection[i], dense_curr[i], "cell {i}");
                assert_eq!(out.difference[i], dense_curr[i] - dense_prev[i], "cell {i}");
            }
        }
    }
}
