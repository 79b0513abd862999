//! Seeded k-means (k-means++ start, Lloyd iterations): inducing points taken from the data
//! (learning-beyond-thesis.md, "Low-dimensional inputs") instead of thousands of free
//! pseudo-input coordinates.

use nalgebra::DMatrix;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// Lloyd iterations at most; the centres usually settle well before.
const MAX_ROUNDS: usize = 50;

/// Rows per parallel task of the assignment step.
const TASK_ROWS: usize = 256;

/// Squared distance of two rows, summed in column order.
fn squared_distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(a, b)| (a - b).powi(2)).sum()
}

/// k-means++'s draw: an index with probability proportional to its weight (uniform when every
/// weight is zero). `weights` must not be empty.
fn draw_proportional(weights: &[f64], rng: &mut ChaCha8Rng) -> usize {
    let total: f64 = weights.iter().sum();
    if total > 0.0 {
        let mut target = rng.random_range(0.0..total);
        for (i, &w) in weights.iter().enumerate() {
            if target < w {
                return i;
            }
            target -= w;
        }
        weights.len() - 1
    } else {
        rng.random_range(0..weights.len())
    }
}

/// The rows of a matrix, one after the other (the matrix is stored by columns, so a row's
/// values are N apart; copied once, every distance reads contiguous memory).
fn rows_of(x: &DMatrix<f64>) -> Vec<f64> {
    let mut rows = Vec::with_capacity(x.len());
    for i in 0..x.nrows() {
        rows.extend(x.row(i).iter());
    }
    rows
}

/// `k` centres (k×D) of the rows of `x` (N×D), min(k, N) of them; the same `seed` gives the same
/// centres. An emptied cluster takes the row farthest from its centre.
pub fn kmeans(x: &DMatrix<f64>, k: usize, seed: u64) -> DMatrix<f64> {
    let (n, d) = (x.nrows(), x.ncols());
    let k = k.min(n);
    if k == 0 {
        return DMatrix::zeros(0, d);
    }
    if d == 0 {
        return DMatrix::zeros(k, 0);
    }
    let rows = rows_of(x);
    let row = |i: usize| &rows[i * d..(i + 1) * d];
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // k-means++: each next centre drawn with probability ∝ squared distance to the nearest.
    let mut centres = vec![0.0; k * d];
    centres[..d].copy_from_slice(row(rng.random_range(0..n)));
    let mut nearest: Vec<f64> = (0..n)
        .map(|i| squared_distance(row(i), &centres[..d]))
        .collect();
    for c in 1..k {
        let pick = draw_proportional(&nearest, &mut rng);
        centres[c * d..(c + 1) * d].copy_from_slice(row(pick));
        let centre = &centres[c * d..(c + 1) * d];
        for (i, best) in nearest.iter_mut().enumerate() {
            *best = best.min(squared_distance(row(i), centre));
        }
    }
    let mut assign = vec![usize::MAX; n];
    for _ in 0..MAX_ROUNDS {
        // Each row's nearest centre (the first of equals), in parallel tasks; whether any row
        // moved, and the first row farthest from its centre, as one pass in row order gives.
        let (mut changed, farthest) = assign
            .par_chunks_mut(TASK_ROWS)
            .enumerate()
            .map(|(task, part)| {
                let mut changed = false;
                let mut farthest = (0.0, 0);
                for (r, a) in part.iter_mut().enumerate() {
                    let i = task * TASK_ROWS + r;
                    let (best, dist) = (0..k)
                        .map(|c| (c, squared_distance(row(i), &centres[c * d..(c + 1) * d])))
                        .fold(
                            (0, f64::INFINITY),
                            |acc, v| if v.1 < acc.1 { v } else { acc },
                        );
                    if *a != best {
                        *a = best;
                        changed = true;
                    }
                    if dist > farthest.0 {
                        farthest = (dist, i);
                    }
                }
                (changed, farthest)
            })
            .collect::<Vec<_>>()
            .into_iter()
            .fold((false, (0.0, 0)), |(changed, far), (c, f)| {
                (changed || c, if f.0 > far.0 { f } else { far })
            });
        let mut sums = vec![0.0; k * d];
        let mut counts = vec![0usize; k];
        for (i, &a) in assign.iter().enumerate() {
            for (s, v) in sums[a * d..(a + 1) * d].iter_mut().zip(row(i)) {
                *s += v;
            }
            counts[a] += 1;
        }
        for (c, &count) in counts.iter().enumerate() {
            let centre = &mut centres[c * d..(c + 1) * d];
            if count == 0 {
                centre.copy_from_slice(row(farthest.1));
                changed = true;
            } else {
                for (m, s) in centre.iter_mut().zip(&sums[c * d..(c + 1) * d]) {
                    *m = s / count as f64;
                }
            }
        }
        if !changed {
            break;
        }
    }
    DMatrix::from_row_slice(k, d, &centres)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn blobs(seed: u64) -> DMatrix<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let at = [[0.0, 0.0], [5.0, 5.0], [-5.0, 5.0]];
        DMatrix::from_fn(150, 2, |i, j| at[i % 3][j] + rng.random_range(-0.5..0.5))
    }

    #[test]
    fn the_same_seed_gives_the_same_centres() {
        let x = blobs(1);
        assert_eq!(kmeans(&x, 3, 9), kmeans(&x, 3, 9));
    }

    #[test]
    fn three_separated_blobs_get_one_centre_each_within_a_quarter_unit() {
        let c = kmeans(&blobs(2), 3, 4);
        for at in [[0.0, 0.0], [5.0, 5.0], [-5.0, 5.0]] {
            let near = (0..3)
                .map(|k| ((c[(k, 0)] - at[0]).powi(2) + (c[(k, 1)] - at[1]).powi(2)).sqrt())
                .fold(f64::INFINITY, f64::min);
            assert!(near < 0.25, "no centre near {at:?}: {near}");
        }
    }

    /// The plain loop over the matrix's rows this file had before its rows were copied out and
    /// assigned in parallel: the reference the fast one must equal bit for bit.
    fn kmeans_reference(x: &DMatrix<f64>, k: usize, seed: u64) -> DMatrix<f64> {
        let dist = |x: &DMatrix<f64>, i: usize, c: &DMatrix<f64>, k: usize| -> f64 {
            x.row(i)
                .iter()
                .zip(c.row(k).iter())
                .map(|(a, b)| (a - b).powi(2))
                .sum()
        };
        let (n, d) = (x.nrows(), x.ncols());
        let k = k.min(n);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut centres = DMatrix::zeros(k, d);
        centres.set_row(0, &x.row(rng.random_range(0..n)));
        let mut nearest: Vec<f64> = (0..n).map(|i| dist(x, i, &centres, 0)).collect();
        for c in 1..k {
            let pick = draw_proportional(&nearest, &mut rng);
            centres.set_row(c, &x.row(pick));
            for (i, best) in nearest.iter_mut().enumerate() {
                *best = best.min(dist(x, i, &centres, c));
            }
        }
        let mut assign = vec![usize::MAX; n];
        for _ in 0..MAX_ROUNDS {
            let mut changed = false;
            let mut farthest = (0.0, 0);
            for (i, a) in assign.iter_mut().enumerate() {
                let (best, d2) = (0..k).map(|c| (c, dist(x, i, &centres, c))).fold(
                    (0, f64::INFINITY),
                    |acc, v| if v.1 < acc.1 { v } else { acc },
                );
                if *a != best {
                    *a = best;
                    changed = true;
                }
                if d2 > farthest.0 {
                    farthest = (d2, i);
                }
            }
            let mut sums = DMatrix::zeros(k, d);
            let mut counts = vec![0usize; k];
            for (i, &a) in assign.iter().enumerate() {
                let row = sums.row(a) + x.row(i);
                sums.set_row(a, &row);
                counts[a] += 1;
            }
            for (c, &count) in counts.iter().enumerate() {
                if count == 0 {
                    centres.set_row(c, &x.row(farthest.1));
                    changed = true;
                } else {
                    let mean = sums.row(c) / count as f64;
                    centres.set_row(c, &mean);
                }
            }
            if !changed {
                break;
            }
        }
        centres
    }

    #[test]
    fn the_centres_equal_the_plain_row_loop_bit_for_bit() {
        // More rows than one parallel task, many columns, repeated rows (ties and empty
        // clusters), as the standardised patches of a training set.
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let x = DMatrix::from_fn(700, 37, |i, j| {
            if i % 7 == 3 {
                1.0
            } else {
                rng.random_range(-2.0..2.0) * (1.0 + (j % 5) as f64)
            }
        });
        for (k, seed) in [(40, 3), (5, 8), (1, 0), (150, 2)] {
            let (fast, plain) = (kmeans(&x, k, seed), kmeans_reference(&x, k, seed));
            assert_eq!(fast.shape(), plain.shape());
            let same = fast
                .iter()
                .zip(plain.iter())
                .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "k = {k}, seed {seed}: the centres differ");
        }
    }

    #[test]
    fn more_centres_than_rows_gives_one_per_row() {
        let x = DMatrix::from_row_slice(2, 1, &[1.0, 2.0]);
        assert_eq!(kmeans(&x, 5, 0).nrows(), 2);
    }
}
