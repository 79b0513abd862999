//! Batch predictions against the matrix path bit for bit, per group and on any number of
//! threads, and bad test rows.

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

/// `predict` on rows `start .. start + n` of the row-major `rows`.
fn matrix_path(model: &GpModel, rows: &[f64], start: usize, n: usize) -> GpPrediction {
    let x = DMatrix::from_row_slice(n, D, &rows[start * D..(start + n) * D]);
    model.predict(&x).expect("predicts")
}

#[test]
fn batch_predictions_have_the_bits_of_the_matrix_path() {
    let (x, y, rows) = toy(150, 300, 3);
    for kind in [GpKind::Spgp, GpKind::SpgpHet, GpKind::Full] {
        let model = fitted(kind, &x, &y);
        for t in [1, 3, 5, 6, 7, 130, 300] {
            let got = model.predict_rows(&rows[..t * D]).expect("predicts rows");
            assert_eq!(got, matrix_path(&model, &rows, 0, t), "{kind:?}, {t} rows");
        }
    }
}

#[test]
fn each_group_gets_the_bits_of_a_call_on_it_alone_on_any_number_of_threads() {
    let (x, y, rows) = toy(150, 300, 4);
    let groups = [3, 1, 140, 6, 5, 2, 130, 13];
    assert_eq!(groups.iter().sum::<usize>(), 300);
    for kind in [GpKind::SpgpHet, GpKind::Full] {
        let model = fitted(kind, &x, &y);
        let in_pool = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool")
                .install(|| model.predict_row_groups(&rows, &groups).expect("predicts"))
        };
        let (one, two) = (in_pool(1), in_pool(2));
        assert_eq!(one, two, "{kind:?}");
        let mut start = 0;
        for n in groups {
            let alone = matrix_path(&model, &rows, start, n);
            let range = start..start + n;
            assert_eq!(&two.mean.as_slice()[range.clone()], alone.mean.as_slice());
            assert_eq!(
                &two.var_latent.as_slice()[range.clone()],
                alone.var_latent.as_slice()
            );
            assert_eq!(&two.var_y.as_slice()[range], alone.var_y.as_slice());
            start += n;
        }
    }
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
    assert!(matches!(
        model.predict_row_groups(&rows, &[1]),
        Err(GpError::InvalidParams(_))
    ));
    let empty = model.predict_rows(&[]).expect("no rows is no predictions");
    assert!(empty.mean.is_empty());
}

#[test]
fn the_mean_alone_has_the_bits_of_the_full_prediction_on_any_number_of_threads() {
    let (x, y, rows) = toy(150, 300, 7);
    for kind in [GpKind::Spgp, GpKind::SpgpHet, GpKind::Full] {
        let model = fitted(kind, &x, &y);
        for t in [0, 1, 5, 6, 129, 300] {
            let rows = &rows[..t * D];
            let in_pool = |threads: usize| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .expect("pool")
                    .install(|| model.predict_mean_rows(rows).expect("predicts"))
            };
            let full = model.predict_rows(rows).expect("predicts rows").mean;
            assert_eq!(in_pool(1), full, "{kind:?}, {t} rows, one thread");
            assert_eq!(in_pool(2), full, "{kind:?}, {t} rows, two threads");
        }
    }
}

#[test]
fn a_value_that_is_not_finite_is_named_before_an_earlier_value_out_of_range() {
    // One pass over all rows reports the first non-finite value even when a value out of range
    // comes earlier, in another block of the parallel path; the mean-only path says the same.
    let (x, y, mut rows) = toy(60, 300, 8);
    let model = fitted(GpKind::Spgp, &x, &y);
    rows[3 * D + 5] = 1e300;
    rows[250 * D + 7] = f64::INFINITY;
    for result in [
        model.predict_rows(&rows).map(|p| p.mean),
        model.predict_mean_rows(&rows),
    ] {
        match result {
            Err(GpError::DegenerateData(msg)) => assert!(
                msg.contains("row 250") && msg.contains("'x7'") && msg.contains("not finite"),
                "{msg}"
            ),
            other => panic!("expected an error, got {other:?}"),
        }
    }
    rows[250 * D + 7] = 0.0;
    for result in [
        model.predict_rows(&rows).map(|p| p.mean),
        model.predict_mean_rows(&rows),
    ] {
        match result {
            Err(GpError::DegenerateData(msg)) => assert!(
                msg.contains("row 3")
                    && msg.contains("'x5'")
                    && msg.contains("standard deviations"),
                "{msg}"
            ),
            other => panic!("expected an error, got {other:?}"),
        }
    }
}
