//! The closed-form leave-one-out moments against brute force: condition on N − 1 samples with the
//! same hyperparameters and predict the one left out.

use nalgebra::{DMatrix, DVector};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::*;
use crate::sparse_posterior::SparsePosterior;
use crate::stationary::Stationary;

fn problem(kind: GpKind, seed: u64) -> (TrainData, Hyper<Stationary>) {
    let (n, m) = (23, 6);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let x: DMatrix<f64> = DMatrix::from_fn(n, 2, |_, _| rng.random_range(-2.0..2.0));
    let y = DVector::from_fn(n, |i, _| {
        (1.5 * x[(i, 0)]).sin() - 0.5 * x[(i, 1)] + rng.random_range(-0.3..0.3)
    });
    let h = Hyper {
        kernel: Stationary::se(&[0.9, 1.6], 1.2),
        noise_variance: 0.07,
        pseudo_inputs: match kind {
            GpKind::Full => DMatrix::zeros(0, 2),
            _ => DMatrix::from_fn(m, 2, |_, _| rng.random_range(-2.0..2.0)),
        },
        pseudo_noise: (kind == GpKind::SpgpHet)
            .then(|| DVector::from_fn(m, |_, _| rng.random_range(0.01..0.3))),
    };
    (TrainData::new(&x, &y), h)
}

/// Mean and latent variance at x_i of the model conditioned on every sample but i.
fn refit_without(
    data: &TrainData,
    kind: GpKind,
    h: &Hyper<Stationary>,
    jitter: f64,
    i: usize,
) -> (f64, f64) {
    let x = data.x_rows();
    let keep: Vec<usize> = (0..data.len()).filter(|&j| j != i).collect();
    let rest = TrainData::new(&x.select_rows(&keep), &data.y.select_rows(&keep));
    let at = x.rows(i, 1).into_owned();
    let (mean, var) = match kind {
        GpKind::Full => {
            let (p, _) = FullPosterior::new(&rest, h, jitter).expect("factors");
            p.predict(h, &at).expect("predicts")
        }
        _ => SparsePosterior::new(&rest, h, jitter)
            .expect("factors")
            .0
            .predict(h, &at),
    };
    (mean[0], var[0])
}

#[test]
fn loo_moments_equal_brute_force_leave_one_out_refits() {
    for (kind, jitter) in [
        (GpKind::Full, 0.0),
        (GpKind::Spgp, 1e-8),
        (GpKind::SpgpHet, 1e-8),
    ] {
        let (data, h) = problem(kind, 3);
        let loo = loo_moments(&data, kind, &h, jitter).expect("factors");
        for i in 0..data.len() {
            let (mean, var) = refit_without(&data, kind, &h, jitter, i);
            // Absolute tolerance 1e-8 on moments of order one.
            assert!(
                (loo.mean[i] - mean).abs() < 1e-8,
                "{kind} mean {i}: {} vs {mean}",
                loo.mean[i]
            );
            let got = loo.var_latent[i];
            assert!((got - var).abs() < 1e-8, "{kind} var {i}: {got} vs {var}");
            assert!(
                (loo.var_y[i] - var - h.noise_variance).abs() < 1e-8,
                "{kind} var_y {i}"
            );
        }
    }
}

#[test]
fn sparse_loo_moments_are_the_same_across_row_blocks() {
    let (small, h) = problem(GpKind::Spgp, 5);
    // Repeat the samples past one row block: the first copy's moments must not depend on blocking
    // beyond rounding, since each block is computed from the same global factorisation.
    let x = small.x_rows();
    let reps = 300 / small.len() + 1;
    let big_x = DMatrix::from_fn(reps * small.len(), 2, |i, d| x[(i % small.len(), d)]);
    let big_y = DVector::from_fn(reps * small.len(), |i, _| small.y[i % small.len()]);
    let big = TrainData::new(&big_x, &big_y);
    let loo = loo_moments(&big, GpKind::Spgp, &h, 1e-8).expect("factors");
    for r in 1..reps {
        for i in 0..small.len() {
            let j = r * small.len() + i;
            assert!(
                (loo.mean[j] - loo.mean[i]).abs() < 1e-9,
                "copy {r}, sample {i}"
            );
            assert!(
                (loo.var_y[j] - loo.var_y[i]).abs() < 1e-9,
                "copy {r}, sample {i}"
            );
        }
    }
}
