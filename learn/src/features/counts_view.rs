//! A window's share of beam counts traced on a larger window of the same grid: a sweep traced
//! once serves its own maps and the next sweep's difference map (thesis 2.1.1-2.1.2).

use crate::features::beam_counts::{BAND_ROWS, BeamCounts};
use crate::features::grid::GridWindow;

/// The counts of `window`, a part of the window the counts were traced on.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CountsView<'a> {
    counts: &'a BeamCounts,
    window: GridWindow,
    /// Where the window's first column and row lie in the traced window.
    col: usize,
    row: usize,
}

impl<'a> CountsView<'a> {
    /// The part of `counts` on `window`, if the traced window holds all of it.
    #[cfg(test)]
    pub(crate) fn of(counts: &'a BeamCounts, window: &GridWindow) -> Option<Self> {
        let offset = window.offset_in(counts.window())?;
        Some(Self::at(counts, window, offset))
    }

    /// The part of `counts` on `window`, whose first cell lies at `(col, row)` of the traced
    /// window (as [`crate::features::traced_counts::TracedCounts::holding`] returns it).
    pub(crate) fn at(
        counts: &'a BeamCounts,
        window: &GridWindow,
        (col, row): (usize, usize),
    ) -> Self {
        debug_assert_eq!(window.offset_in(counts.window()), Some((col, row)));
        Self {
            counts,
            window: *window,
            col,
            row,
        }
    }

    /// The window viewed.
    pub(crate) fn window(&self) -> &GridWindow {
        &self.window
    }

    /// Row `r` of the window's hits (`channel` 0) or misses (1).
    pub(crate) fn row(&self, channel: usize, r: usize) -> &'a [f32] {
        let counts: &'a BeamCounts = self.counts;
        &counts.row(channel, r + self.row)[self.col..self.col + self.window.cols]
    }

    /// The columns `[lo, hi]` of band `b` (rows `b · BAND_ROWS ..`) that may hold counts, if any:
    /// the traced bands' touched columns over those rows, cut to the window.
    pub(crate) fn band(&self, b: usize) -> Option<(usize, usize)> {
        let first = b * BAND_ROWS;
        if first >= self.window.rows {
            return None;
        }
        let last = (first + BAND_ROWS).min(self.window.rows) - 1;
        let traced = (first + self.row) / BAND_ROWS..=(last + self.row) / BAND_ROWS;
        let (lo, hi) = traced
            .filter_map(|k| self.counts.band(k))
            .reduce(|a, c| (a.0.min(c.0), a.1.max(c.1)))?;
        let (lo, hi) = (lo.max(self.col), hi.min(self.col + self.window.cols - 1));
        (lo <= hi).then(|| (lo - self.col, hi - self.col))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::features::sliced_beam::SlicedBeam;

    #[test]
    fn counts_cut_from_a_larger_window_equal_counts_traced_on_the_window() {
        // Beams crossing the small window's edges at shallow and steep angles, some starting
        // and ending outside it; 23 rows so bands of the two windows do not line up.
        let small = GridWindow::centred([0.33, -0.21], 1.15, 0.1);
        let large = small.padded(7);
        let beams = [
            SlicedBeam::new([0.0, 0.0], [3.0, 0.4], true),
            SlicedBeam::new([0.0, 0.0], [-0.2, -2.9], true),
            SlicedBeam::new([-2.0, 1.37], [2.6, 0.91], false),
            SlicedBeam::new([0.5, 0.5], [0.61, 0.52], true),
            SlicedBeam::new([1.3, -1.4], [-1.5, 1.2], false),
        ];
        let direct = BeamCounts::trace(&beams, &small);
        let traced = BeamCounts::trace(&beams, &large);
        let cut = CountsView::of(&traced, &small).unwrap();
        let whole = CountsView::of(&direct, &small).unwrap();
        for r in 0..small.rows {
            for channel in [0, 1] {
                assert_eq!(cut.row(channel, r), whole.row(channel, r), "row {r}");
            }
        }
        for b in 0..small.rows.div_ceil(BAND_ROWS) {
            let (band, exact) = (cut.band(b), whole.band(b));
            // The cut's touched columns may be wider, never narrower.
            if let Some((lo, hi)) = exact {
                let (clo, chi) = band.unwrap();
                assert!(
                    clo <= lo && hi <= chi,
                    "band {b}: {clo}..={chi} misses {lo}..={hi}"
                );
            }
        }
    }

    #[test]
    fn a_window_not_inside_the_traced_one_has_no_view() {
        let small = GridWindow::centred([0.0, 0.0], 1.0, 0.1);
        let traced = BeamCounts::trace(&[], &small);
        assert!(CountsView::of(&traced, &small.padded(1)).is_none());
        let coarse = GridWindow::centred([0.0, 0.0], 1.0, 0.2);
        assert!(CountsView::of(&traced, &coarse).is_none());
    }
}
