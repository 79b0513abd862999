//! The 3 × 3 mass-spreading kernel of the reflection map (thesis 2.1.1: "some mass of the hits
//! and misses was spread to neighboring cells") as two 1-D passes over rows of f32 counts, and
//! the ratio of spread hits to spread hits and misses (thesis Eq. 2.8).

/// The spreading kernel `[side, centre, side]` in f32, like the counts.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Kernel {
    side: f32,
    centre: f32,
}

impl Kernel {
    pub(crate) fn new(spread: f64) -> Self {
        let side = spread as f32;
        Self {
            side,
            centre: 1.0 - 2.0 * side,
        }
    }

    /// `centre · here + side · (a + b)`.
    pub(crate) fn apply(self, here: f32, a: f32, b: f32) -> f32 {
        self.centre * here + self.side * (a + b)
    }
}

/// Rows `k`, `k + 1`, `k + 2` of a buffer of rows of `width` values.
pub(crate) fn neighbour_rows(v: &[f32], k: usize, width: usize) -> [&[f32]; 3] {
    [0, 1, 2].map(|dk| &v[(k + dk) * width..(k + dk + 1) * width])
}

/// Spreads columns `lo ..` of one count row along x into `out` (counts beyond the row are 0).
pub(crate) fn spread_row(kernel: Kernel, row: &[f32], lo: usize, out: &mut [f32]) {
    let at = |x: usize| row.get(x).copied().unwrap_or(0.0);
    let edge = |x: usize| kernel.apply(at(x), x.checked_sub(1).map_or(0.0, at), at(x + 1));
    let width = out.len();
    if width <= 2 {
        for (i, o) in out.iter_mut().enumerate() {
            *o = edge(lo + i);
        }
        return;
    }
    out[0] = edge(lo);
    out[width - 1] = edge(lo + width - 1);
    // The interior as three shifted slices, which the compiler vectorises.
    let (left, here, right) = (
        &row[lo..lo + width - 2],
        &row[lo + 1..lo + width - 1],
        &row[lo + 2..lo + width],
    );
    for (((o, &l), &h), &r) in out[1..width - 1].iter_mut().zip(left).zip(here).zip(right) {
        *o = kernel.apply(h, l, r);
    }
}

/// Spreads the x-spread hits and misses of a row along y (`[below, here, above]` each) and
/// writes hits / (hits + misses) per cell, NaN where no mass arrived (thesis Eq. 2.8).
pub(crate) fn ratios(kernel: Kernel, hits: [&[f32]; 3], misses: [&[f32]; 3], out: &mut [f64]) {
    let [hb, hh, ha] = hits;
    let [mb, mh, ma] = misses;
    let h = hh
        .iter()
        .zip(hb)
        .zip(ha)
        .map(|((&h, &b), &a)| kernel.apply(h, b, a));
    let m = mh
        .iter()
        .zip(mb)
        .zip(ma)
        .map(|((&h, &b), &a)| kernel.apply(h, b, a));
    for ((o, h), m) in out.iter_mut().zip(h).zip(m) {
        let total = f64::from(h) + f64::from(m);
        *o = if total > 1e-9 {
            f64::from(h) / total
        } else {
            f64::NAN
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spreading_a_row_keeps_the_mass_inside_and_shares_it_with_the_neighbours() {
        let kernel = Kernel::new(0.25);
        let row = [0.0, 4.0, 0.0, 0.0, 8.0];
        let mut out = [0.0; 5];
        spread_row(kernel, &row, 0, &mut out);
        assert_eq!(
            out,
            [1.0, 2.0, 1.0, 2.0, 4.0],
            "the edge loses what leaves the row"
        );
        let mut tail = [0.0; 2];
        spread_row(kernel, &row, 3, &mut tail);
        assert_eq!(tail, [2.0, 4.0]);
    }

    #[test]
    fn the_ratio_is_nan_where_no_mass_arrived() {
        let kernel = Kernel::new(0.0);
        let (zero, one) = ([0.0f32], [1.0f32]);
        let mut out = [0.0];
        ratios(kernel, [&zero, &one, &zero], [&zero, &one, &zero], &mut out);
        assert_eq!(out, [0.5]);
        ratios(
            kernel,
            [&zero, &zero, &zero],
            [&zero, &zero, &zero],
            &mut out,
        );
        assert!(out[0].is_nan());
    }
}
