//! Seeded k-means (k-means++ start, Lloyd iterations): inducing points taken from the data
//! (learning-beyond-thesis.md, "Low-dimensional inputs") instead of thousands of free
//! pseudo-input coordinates.

use nalgebra::DMatrix;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Lloyd iterations at most; the centres usually settle well before.
const MAX_ROUNDS: usize = 50;

fn squared_distance(x: &DMatrix<f64>, i: usize, c: &DMatrix<f64>, k: usize) -> f64 {
    x.row(i)
        .iter()
        .zip(c.row(k).iter())
        .map(|(a, b)| (a - b).powi(2))
        .sum()
}

/// `k` centres (k×D) of the rows of `x` (N×D), min(k, N) of them; the same `seed` gives the same
/// centres. An emptied cluster takes the row farthest from its centre.
pub fn kmeans(x: &DMatrix<f64>, k: usize, seed: u64) -> DMatrix<f64> {
    let (n, d) = (x.nrows(), x.ncols());
    let k = k.min(n);
    if k == 0 {
        return DMatrix::zeros(0, d);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // k-means++: each next centre drawn with probability ∝ squared distance to the nearest.
    let mut centres = DMatrix::zeros(k, d);
    centres.set_row(0, &x.row(rng.random_range(0..n)));
    let mut nearest: Vec<f64> = (0..n)
        .map(|i| squared_distance(x, i, &centres, 0))
        .collect();
    for c in 1..k {
        let total: f64 = nearest.iter().sum();
        let pick = if total > 0.0 {
            let mut target = rng.random_range(0.0..total);
            let mut chosen = n - 1;
            for (i, &w) in nearest.iter().enumerate() {
                if target < w {
                    chosen = i;
                    break;
                }
                target -= w;
            }
            chosen
        } else {
            rng.random_range(0..n)
        };
        centres.set_row(c, &x.row(pick));
        for (i, best) in nearest.iter_mut().enumerate() {
            *best = best.min(squared_distance(x, i, &centres, c));
        }
    }
    let mut assign = vec![usize::MAX; n];
    for _ in 0..MAX_ROUNDS {
        let mut changed = false;
        let mut farthest = (0.0, 0);
        for (i, a) in assign.iter_mut().enumerate() {
            let (best, dist) = (0..k)
                .map(|c| (c, squared_distance(x, i, &centres, c)))
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

    #[test]
    fn more_centres_than_rows_gives_one_per_row() {
        let x = DMatrix::from_row_slice(2, 1, &[1.0, 2.0]);
        assert_eq!(kmeans(&x, 5, 0).nrows(), 2);
    }
}
