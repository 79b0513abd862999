//! World-aligned grid windows and the maps stored on them (thesis 2.1: the data association
//! between maps is given by cell positions, so every map lives on one global lattice).

use crate::features::buffer_pool::BufferPool;

/// A rectangular window onto the global lattice of square cells of side `cell_m`.
///
/// Global cell `(gx, gy)` covers world `x ∈ [gx·cell_m, (gx+1)·cell_m)` and likewise for y, so
/// the windows of two sweeps line up by an integer offset. Local cell `(col, row)` of a window is
/// global cell `(origin_col + col, origin_row + row)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridWindow {
    /// Global column of local column 0.
    pub origin_col: i64,
    /// Global row of local row 0.
    pub origin_row: i64,
    /// Number of columns (x direction).
    pub cols: usize,
    /// Number of rows (y direction).
    pub rows: usize,
    /// Side of a cell, metres.
    pub cell_m: f64,
}

impl GridWindow {
    /// The window of `2·half_extent_m` a side (rounded up to whole cells) around `centre_xy`.
    pub fn centred(centre_xy: [f64; 2], half_extent_m: f64, cell_m: f64) -> Self {
        let side = (2.0 * half_extent_m / cell_m).ceil() as usize;
        let half = (side / 2) as i64;
        Self {
            origin_col: (centre_xy[0] / cell_m).floor() as i64 - half,
            origin_row: (centre_xy[1] / cell_m).floor() as i64 - half,
            cols: side,
            rows: side,
            cell_m,
        }
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.cols * self.rows
    }

    /// True if the window has no cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Continuous local cell coordinates of a world point: cell `(c, r)` spans `[c, c+1)`.
    pub fn to_local(&self, x_m: f64, y_m: f64) -> [f64; 2] {
        [
            x_m / self.cell_m - self.origin_col as f64,
            y_m / self.cell_m - self.origin_row as f64,
        ]
    }

    /// The local cell holding a world point, if it lies inside the window.
    pub fn cell_of(&self, x_m: f64, y_m: f64) -> Option<(usize, usize)> {
        let [u, v] = self.to_local(x_m, y_m);
        let (c, r) = (u.floor(), v.floor());
        (c >= 0.0 && r >= 0.0 && (c as usize) < self.cols && (r as usize) < self.rows)
            .then_some((c as usize, r as usize))
    }

    /// World coordinates of the centre of local cell `(col, row)`.
    pub fn centre_of(&self, col: usize, row: usize) -> [f64; 2] {
        [
            (self.origin_col + col as i64) as f64 * self.cell_m + 0.5 * self.cell_m,
            (self.origin_row + row as i64) as f64 * self.cell_m + 0.5 * self.cell_m,
        ]
    }

    /// Row-major index of local cell `(col, row)`.
    pub fn index(&self, col: usize, row: usize) -> usize {
        row * self.cols + col
    }

    /// The local cell `(col, row)` of a finite world point, inside the window or not: the grid's
    /// cell less the origin, in integers, so every window of one grid names the same cell
    /// (saturating far outside).
    pub(crate) fn local_cell(&self, x_m: f64, y_m: f64) -> (i64, i64) {
        (
            floor(x_m / self.cell_m).saturating_sub(self.origin_col),
            floor(y_m / self.cell_m).saturating_sub(self.origin_row),
        )
    }

    /// This window grown by `cells` on every side, on the same grid.
    pub(crate) fn padded(&self, cells: usize) -> Self {
        Self {
            origin_col: self.origin_col - cells as i64,
            origin_row: self.origin_row - cells as i64,
            cols: self.cols + 2 * cells,
            rows: self.rows + 2 * cells,
            cell_m: self.cell_m,
        }
    }

    /// Where this window's first cell lies in `outer` (column, row), if `outer` is on the same
    /// grid and holds every cell of this one.
    pub(crate) fn offset_in(&self, outer: &GridWindow) -> Option<(usize, usize)> {
        let (dc, dr) = (
            self.origin_col - outer.origin_col,
            self.origin_row - outer.origin_row,
        );
        let fits = |d: i64, n: usize, m: usize| d >= 0 && d as usize + n <= m;
        (self.cell_m.to_bits() == outer.cell_m.to_bits()
            && fits(dc, self.cols, outer.cols)
            && fits(dr, self.rows, outer.rows))
        .then_some((dc as usize, dr as usize))
    }
}

/// `v.floor()` as an integer for finite `v` (saturating far outside any window), without the
/// library call `f64::floor` costs on baseline x86-64.
fn floor(v: f64) -> i64 {
    let i = v as i64;
    if (i as f64) > v {
        i.saturating_sub(1)
    } else {
        i
    }
}

/// Values on a [`GridWindow`], row-major (`row · cols + col`), with one value for every cell
/// outside the window (the prior for reflection maps, 0 for difference maps).
///
/// A dropped map hands its storage to a small pool that the map builders draw from, so a sweep's
/// maps (5 MB each at the default size) cost neither fresh pages nor zeroing.
#[derive(Debug, Clone, PartialEq)]
pub struct GridMap {
    window: GridWindow,
    values: Vec<f64>,
    outside: f64,
}

/// Storage of dropped maps.
static RECYCLED: BufferPool<f64> = BufferPool::new();
/// Buffers below this length are not worth pooling.
const RECYCLED_MIN_LEN: usize = 1 << 14;

/// A buffer of `len` values for a map whose every cell the caller will overwrite: recycled
/// storage of a dropped map if one fits (its old values still in it), or a new zeroed one.
pub(crate) fn recycled_values(len: usize) -> Vec<f64> {
    RECYCLED.take(len).unwrap_or_else(|| vec![0.0; len])
}

impl Drop for GridMap {
    fn drop(&mut self) {
        if self.values.len() < RECYCLED_MIN_LEN {
            return;
        }
        RECYCLED.give(std::mem::take(&mut self.values));
    }
}

impl GridMap {
    /// A map with every cell, inside and outside, at `value`.
    pub fn filled(window: GridWindow, value: f64) -> Self {
        Self {
            window,
            values: vec![value; window.len()],
            outside: value,
        }
    }

    /// A map from row-major values; `None` if the count does not match the window.
    pub fn from_values(window: GridWindow, values: Vec<f64>, outside: f64) -> Option<Self> {
        (values.len() == window.len()).then_some(Self {
            window,
            values,
            outside,
        })
    }

    /// The window.
    pub fn window(&self) -> &GridWindow {
        &self.window
    }

    /// Row-major cell values.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Row-major cell values, mutable.
    pub fn values_mut(&mut self) -> &mut [f64] {
        &mut self.values
    }

    /// Value of every cell outside the window.
    pub fn outside(&self) -> f64 {
        self.outside
    }

    /// Sets the value of cells outside the window.
    pub fn set_outside(&mut self, value: f64) {
        self.outside = value;
    }

    /// Value of local cell `(col, row)`, given as signed so neighbours of edge cells read the
    /// outside value.
    pub fn get(&self, col: i64, row: i64) -> f64 {
        let w = &self.window;
        if col < 0 || row < 0 || col >= w.cols as i64 || row >= w.rows as i64 {
            self.outside
        } else {
            self.values[row as usize * w.cols + col as usize]
        }
    }

    /// Value of the cell holding a world point (no interpolation).
    pub fn at(&self, x_m: f64, y_m: f64) -> f64 {
        let [u, v] = self.window.to_local(x_m, y_m);
        self.get(u.floor() as i64, v.floor() as i64)
    }

    /// Bilinear interpolation between cell centres at a world point.
    pub fn sample_bilinear(&self, x_m: f64, y_m: f64) -> f64 {
        let [u, v] = self.window.to_local(x_m, y_m);
        let (u, v) = (u - 0.5, v - 0.5);
        let (c0, r0) = (u.floor(), v.floor());
        let (tu, tv) = (u - c0, v - r0);
        let (c, r) = (c0 as i64, r0 as i64);
        let top = self.get(c, r) * (1.0 - tu) + self.get(c + 1, r) * tu;
        let bottom = self.get(c, r + 1) * (1.0 - tu) + self.get(c + 1, r + 1) * tu;
        top * (1.0 - tv) + bottom * tv
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_around_nearby_centres_line_up_by_whole_cells() {
        let a = GridWindow::centred([10.03, -4.96], 40.0, 0.1);
        let b = GridWindow::centred([10.57, -4.11], 40.0, 0.1);
        assert_eq!((a.cols, a.rows), (800, 800));
        let ca = a.centre_of(100, 200);
        let (col, row) = b.cell_of(ca[0], ca[1]).unwrap();
        let cb = b.centre_of(col, row);
        assert!((ca[0] - cb[0]).abs() < 1e-9 && (ca[1] - cb[1]).abs() < 1e-9);
    }

    #[test]
    fn a_window_covers_its_half_extent_in_every_direction() {
        let w = GridWindow::centred([3.0, 7.0], 40.0, 0.1);
        for (dx, dy) in [(-39.9, 0.0), (39.9, 0.0), (0.0, -39.9), (0.0, 39.9)] {
            assert!(w.cell_of(3.0 + dx, 7.0 + dy).is_some(), "{dx} {dy}");
        }
        assert!(w.cell_of(3.0 + 40.2, 7.0).is_none());
    }

    #[test]
    fn bilinear_sampling_is_exact_at_centres_and_linear_between() {
        let w = GridWindow::centred([0.0, 0.0], 0.5, 0.1);
        let mut map = GridMap::filled(w, 0.0);
        let i = w.index(4, 5);
        map.values_mut()[i] = 1.0;
        let c = w.centre_of(4, 5);
        assert!((map.sample_bilinear(c[0], c[1]) - 1.0).abs() < 1e-12);
        assert!((map.sample_bilinear(c[0] + 0.05, c[1]) - 0.5).abs() < 1e-12);
        assert!((map.sample_bilinear(c[0] + 0.025, c[1] + 0.05) - 0.375).abs() < 1e-12);
    }

    #[test]
    fn cells_outside_the_window_read_the_outside_value() {
        let w = GridWindow::centred([0.0, 0.0], 1.0, 0.1);
        let map = GridMap::filled(w, 0.5);
        assert_eq!(map.get(-1, 3), 0.5);
        assert_eq!(map.at(100.0, 0.0), 0.5);
    }
}
