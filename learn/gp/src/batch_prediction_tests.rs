//! Batch predictions against the matrix path, per-row independence of the batch and the threads,
//! and bad test rows.

use nalgebra::{DMatrix, DVector};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::{GpError, GpKind, GpModel, GpParams, GpPrediction};

/// Inputs per row of the toy problems: enough for several vector tiles of the products.
const D: usize = 23;

/// N noisy samples of a smooth function of D inputs, and T test rows (row-major) off them.
fn toy(n: usize, t: usize, seed: u64) -> (DMatrix<f64>, DVector<f64>, Vec<f64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let x = DMatrix::from_fn(n, D, |_, j| rng.random_range(-1.0..1.0) * (1.0 + j as f64));
    let y = DVector::from_fn(n, |i, _| {
        x.row(i).iter().take(4).sum::<f64>().sin() + 0.05 * rng.random_range(-1.0..1.0)
    });
    let rows = (0..t * D)
        .map(|k| rng.random_range(-1.2..1.2) * (1.0 + (k % D) as f64))
        .collect();
    (x, y, rows)
}

fn fitted(kind: GpKind, x: &DMatrix<f64>, y: &DVector<f64>) -> GpModel {
    GpParams::new(kind)
        .pseudo_inputs(19)
        .max_iters(15)
        .fit(x, y)
        .expect("fits")
}

/// Largest relative difference between two predictions: of the means relative to the larger of
/// the mean and the predictive standard deviation (a mean near zero is a sum of terms that
/// cancel, so its own magnitude is no scale for rounding), of both variances to their values.
fn worst_relative(a: &GpPrediction, b: &GpPrediction) -> f64 {
    let relative = |u: f64, v: f64, scale: f64| (u - v).abs() / u.abs().max(v.abs()).max(scale);
    (0..a.mean.len())
        .flat_map(|i| {
            [
                relative(a.mean[i], b.mean[i], a.var_y[i].sqrt()),
                relative(a.var_latent[i], b.var_latent[i], 1e-300),
                relative(a.var_y[i], b.var_y[i], 1e-300),
            ]
        })
        .fold(0.0, f64::max)
}

#[test]
fn batch_predictions_agree_with_the_matrix_path_to_1e_9_relative() {
    let (x, y, rows) = toy(150, 300, 3);
    for kind in [GpKind::Spgp, GpKind::SpgpHet, GpKind::Full] {
        let model = fitted(kind, &x, &y);
        let want = model
            .predict(&DMatrix::from_row_slice(300, D, &rows))
            .expect("predicts");
        let got = model.predict_rows(&rows).expect("predicts rows");
        let worst = worst_relative(&got, &want);
        assert!(
            worst < 1e-9,
            "{kind:?}: worst relative difference {worst:e}"
        );
    }
}

#[test]
fn a_row_gets_the_same_bits_alone_in_any_batch_and_on_any_number_of_threads() {
    let (x, y, rows) = toy(150, 261, 4);
    let model = fitted(GpKind::SpgpHet, &x, &y);
    let in_pool = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool")
            .install(|| model.predict_rows(&rows).expect("predicts rows"))
    };
    let (one, two) = (in_pool(1), in_pool(2));
    assert_eq!(one, two);
    for r in [0, 7, 128, 260] {
        let alone = model
            .predict_rows(&rows[r * D..(r + 1) * D])
            .expect("predicts one row");
        assert_eq!(alone.mean[0].to_bits(), two.mean[r].to_bits(), "row {r}");
        assert_eq!(alone.var_y[0].to_bits(), two.var_y[r].to_bits(), "row {r}");
    }
    let tail = model.predict_rows(&rows[5 * D..]).expect("predicts");
    assert_eq!(tail.mean.as_slice(), &two.mean.as_slice()[5..]);
    assert_eq!(tail.var_latent.as_slice(), &two.var_latent.as_slice()[5..]);
}

#[test]
fn a_non_finite_value_is_an_error_naming_its_row_and_column() {
    let (x, y, mut rows) = toy(60, 4, 5);
    let model = fitted(GpKind::Spgp, &x, &y);
    rows[2 * D + 3] = f64::NAN;
    match model.predict_rows(&rows) {
        Err(GpError::DegenerateData(msg)) => {
            assert!(msg.contains("row 2") && msg.contains("'x3'"), "{msg}")
        }
        other => panic!("expected an error, got {other:?}"),
    }
}

#[test]
fn values_that_are_not_whole_rows_are_an_error() {
    let (x, y, rows) = toy(60, 2, 6);
    let model = fitted(GpKind::Spgp, &x, &y);
    assert!(matches!(
        model.predict_rows(&rows[..D + 1]),
        Err(GpError::InvalidParams(_))
    ));
    let empty = model.predict_rows(&[]).expect("no rows is no predictions");
    assert!(empty.mean.is_empty());
}
