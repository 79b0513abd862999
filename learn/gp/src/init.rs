//! Seeded starting point of the evidence maximisation (gp.md §5.3, Snelson's demo recipe adapted to
//! high D): pseudo-inputs a random subset of the inputs, the kernel's own start (for the stationary
//! kernels: length-scales from the input spread, s = var(y)), σ² = s/4 and, for SPGP-HET,
//! h = σ²/10 (gp.md §5.2).

use nalgebra::{DMatrix, DVector};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::hyper::Hyper;
use super::kernel::Kernel;
use super::params::GpKind;
use super::train_data::TrainData;
use crate::Result;

/// `m` distinct row indices out of `n`, by a seeded partial Fisher-Yates shuffle.
pub(crate) fn random_subset(n: usize, m: usize, seed: u64) -> Vec<usize> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut idx: Vec<usize> = (0..n).collect();
    let m = m.min(n);
    for i in 0..m {
        let j = rng.random_range(i..n);
        idx.swap(i, j);
    }
    idx.truncate(m);
    idx
}

/// The starting hyperparameters for a fit of `kind` with `m` pseudo-inputs (capped at N), with
/// `kernel` initialised from the inputs' spread and the target variance; `start` gives the
/// pseudo-inputs instead of a seeded random subset.
pub(crate) fn initial_hyper<K: Kernel>(
    data: &TrainData,
    kind: GpKind,
    m: usize,
    seed: u64,
    mut kernel: K,
    start: Option<&DMatrix<f64>>,
) -> Result<Hyper<K>> {
    let (n, dims) = (data.len(), data.dims());
    let mean_y = data.y.mean();
    let var_y = data.y.iter().map(|v| (v - mean_y).powi(2)).sum::<f64>() / n as f64;
    kernel.initialise(&data.xt, var_y)?;
    let noise_variance = kernel.signal_variance() / 4.0;
    let (pseudo_inputs, pseudo_noise) = match kind {
        GpKind::Full => (DMatrix::zeros(0, dims), None),
        GpKind::Spgp | GpKind::SpgpHet => {
            let z = match start {
                Some(z) => z.clone(),
                None => {
                    let rows = random_subset(n, m, seed);
                    DMatrix::from_fn(rows.len(), dims, |i, d| data.xt[(d, rows[i])])
                }
            };
            let h = (kind == GpKind::SpgpHet)
                .then(|| DVector::from_element(z.nrows(), noise_variance / 10.0));
            (z, h)
        }
    };
    Ok(Hyper {
        kernel,
        noise_variance,
        pseudo_inputs,
        pseudo_noise,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_random_subset_is_distinct_seeded_and_capped_at_n() {
        let a = random_subset(50, 10, 7);
        let mut sorted = a.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), 10);
        assert_eq!(a, random_subset(50, 10, 7));
        assert_ne!(a, random_subset(50, 10, 8));
        assert_eq!(random_subset(4, 10, 1).len(), 4);
    }
}
