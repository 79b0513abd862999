//! Hit and miss counts of one sweep's sliced beams on a map window (thesis 2.1.1): a hit in the
//! end cell of every beam ending in the slice, a miss in every other cell Bresenham's line visits.
//!
//! The counts are the hot part of the feature pipeline (about two million cell visits per real
//! sweep), so they live in f32 buffers taken from a small pool of clean buffers and handed back
//! zeroed, and every band of [`BAND_ROWS`] rows remembers which columns it touched: the map pass
//! skips the rest and the clean-up zeroes only those cells.

use crate::features::buffer_pool::BufferPool;
use crate::features::grid::GridWindow;
use crate::features::line::add_misses;
use crate::features::sliced_beam::SlicedBeam;

/// The largest cell coordinate a traced line may have (16.7 million cells, 1,670 km at 0.1 m).
const MAX_CELLS: i64 = 1 << 24;

/// Rows per band of touched-column bookkeeping.
pub(crate) const BAND_ROWS: usize = 16;

/// Clean (all zero) count buffers, reused between sweeps so a map costs no page faults and no
/// full-grid zeroing.
static POOL: BufferPool<f32> = BufferPool::new();

/// One sweep's counts on a window, row-major (`row · cols + col`).
#[derive(Debug)]
pub(crate) struct BeamCounts {
    window: GridWindow,
    hits: Vec<f32>,
    misses: Vec<f32>,
    /// Per band: the smallest and largest column any count of the band lies in (empty when the
    /// smallest exceeds the largest).
    bands: Vec<(usize, usize)>,
}

impl BeamCounts {
    /// Traces every beam onto `window`; the parts outside the window are skipped.
    pub(crate) fn trace(beams: &[SlicedBeam], window: &GridWindow) -> Self {
        let mut counts = Self {
            window: *window,
            hits: clean_buffer(window.len()),
            misses: clean_buffer(window.len()),
            bands: vec![(usize::MAX, 0); window.rows.div_ceil(BAND_ROWS)],
        };
        for beam in beams {
            counts.add_beam(beam);
        }
        counts
    }

    /// The window the counts lie on.
    pub(crate) fn window(&self) -> &GridWindow {
        &self.window
    }

    /// Row `r` of the hits (`channel` 0) or the misses (1).
    pub(crate) fn row(&self, channel: usize, r: usize) -> &[f32] {
        let cols = self.window.cols;
        let counts = if channel == 0 {
            &self.hits
        } else {
            &self.misses
        };
        &counts[r * cols..(r + 1) * cols]
    }

    /// The touched columns `[lo, hi]` of band `b`, if any.
    pub(crate) fn band(&self, b: usize) -> Option<(usize, usize)> {
        self.bands.get(b).copied().filter(|(lo, hi)| lo <= hi)
    }

    /// Adds one beam's hit and misses: the cells of its whole line that lie in the window, so
    /// the counts on any window inside this one are these counts cut to it.
    fn add_beam(&mut self, beam: &SlicedBeam) {
        let finite = beam
            .start_xy
            .iter()
            .chain(&beam.end_xy)
            .all(|v| v.is_finite());
        if !finite {
            return;
        }
        let window = self.window;
        let from = window.local_cell(beam.start_xy[0], beam.start_xy[1]);
        let to = window.local_cell(beam.end_xy[0], beam.end_xy[1]);
        // A line thousands of kilometres long is no sweep's; it would overflow the stepping.
        if [from.0, from.1, to.0, to.1]
            .iter()
            .any(|v| v.unsigned_abs() > MAX_CELLS.unsigned_abs())
        {
            return;
        }
        let inside = |(c, r): (i64, i64)| {
            (0..window.cols as i64).contains(&c) && (0..window.rows as i64).contains(&r)
        };
        if beam.hit && inside(to) {
            let (c, r) = (to.0 as usize, to.1 as usize);
            self.hits[window.index(c, r)] += 1.0;
            self.mark((c, c), (r, r));
        }
        // The end cell of a beam ending in the slice is its hit, not a miss.
        let size = (window.cols, window.rows);
        if let Some((cols, rows)) = add_misses(&mut self.misses, size, from, to, beam.hit) {
            self.mark(cols, rows);
        }
    }

    /// Records that columns `[c0, c1]` of rows `[r0, r1]` may hold counts.
    fn mark(&mut self, (c0, c1): (usize, usize), (r0, r1): (usize, usize)) {
        for band in &mut self.bands[r0 / BAND_ROWS..=r1 / BAND_ROWS] {
            band.0 = band.0.min(c0);
            band.1 = band.1.max(c1);
        }
    }
}

impl Drop for BeamCounts {
    /// Zeroes the touched cells and hands the buffer back to the pool.
    fn drop(&mut self) {
        let cols = self.window.cols;
        for (b, &(lo, hi)) in self.bands.iter().enumerate() {
            if lo > hi {
                continue;
            }
            let rows = b * BAND_ROWS..((b + 1) * BAND_ROWS).min(self.window.rows);
            for r in rows {
                self.hits[r * cols + lo..=r * cols + hi].fill(0.0);
                self.misses[r * cols + lo..=r * cols + hi].fill(0.0);
            }
        }
        POOL.give(std::mem::take(&mut self.hits));
        POOL.give(std::mem::take(&mut self.misses));
    }
}

/// A zeroed buffer of `len` cells: a pooled one of that length, or a new one.
fn clean_buffer(len: usize) -> Vec<f32> {
    POOL.take(len).unwrap_or_else(|| vec![0.0; len])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn total(counts: &BeamCounts) -> [f32; 2] {
        let sum = |channel| {
            (0..counts.window().rows)
                .flat_map(|r| counts.row(channel, r).iter())
                .sum()
        };
        [sum(0), sum(1)]
    }

    #[test]
    fn a_hit_beam_counts_one_hit_and_a_miss_in_every_cell_before_it() {
        let w = GridWindow::centred([0.0, 0.0], 2.0, 0.1);
        let counts = BeamCounts::trace(&[SlicedBeam::new([0.05, 0.05], [1.05, 0.05], true)], &w);
        assert_eq!(total(&counts), [1.0, 10.0]);
        let (c, r) = w.cell_of(1.05, 0.05).unwrap();
        assert_eq!((counts.row(0, r)[c], counts.row(1, r)[c]), (1.0, 0.0));
    }

    #[test]
    fn every_count_lies_inside_the_touched_columns_of_its_band() {
        let w = GridWindow::centred([0.0, 0.0], 4.0, 0.1);
        let beams = [
            SlicedBeam::new([0.0, 0.0], [3.0, 2.5], true),
            SlicedBeam::new([-1.0, -3.5], [-3.9, 1.0], false),
            SlicedBeam::new([-10.0, 0.35], [10.0, 0.35], false),
        ];
        let counts = BeamCounts::trace(&beams, &w);
        for r in 0..w.rows {
            let band = counts.band(r / BAND_ROWS);
            let (hits, misses) = (counts.row(0, r), counts.row(1, r));
            for (c, (h, m)) in hits.iter().zip(misses).enumerate() {
                if h + m > 0.0 {
                    let (lo, hi) = band.unwrap();
                    assert!(lo <= c && c <= hi, "row {r} col {c} outside {lo}..={hi}");
                }
            }
        }
    }

    #[test]
    fn a_beam_reaching_thousands_of_kilometres_away_counts_nothing() {
        let w = GridWindow::centred([0.0, 0.0], 2.0, 0.1);
        let beams = [
            SlicedBeam::new([0.05, 0.05], [-1e30, 0.05], true),
            SlicedBeam::new([1e300, 0.05], [0.05, 0.05], false),
        ];
        assert_eq!(total(&BeamCounts::trace(&beams, &w)), [0.0, 0.0]);
    }

    #[test]
    fn a_buffer_comes_back_from_the_pool_clean() {
        // An odd size no other test uses, so the pooled buffer is this test's own.
        let w = GridWindow::centred([0.0, 0.0], 1.3, 0.1);
        let beams = [SlicedBeam::new([-1.2, -1.0], [1.1, 1.2], true)];
        drop(BeamCounts::trace(&beams, &w));
        let empty = BeamCounts::trace(&[], &w);
        assert_eq!(total(&empty), [0.0, 0.0]);
        assert!((0..w.rows.div_ceil(BAND_ROWS)).all(|b| empty.band(b).is_none()));
    }
}
