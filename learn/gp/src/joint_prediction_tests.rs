//! Joint predictions against each model's own call, bit for bit, and their fallbacks.

use nalgebra::{DMatrix, DVector};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::{GpError, GpKind, GpModel, GpParams, Predicted, Readout};

const D: usize = 17;

/// Inputs, two targets on them, and T test rows (row-major).
fn toy(n: usize, t: usize, seed: u64) -> (DMatrix<f64>, [DVector<f64>; 2], Vec<f64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let x = DMatrix::from_fn(n, D, |_, j| rng.random_range(-1.0..1.0) * (1.0 + j as f64));
    let y0 = DVector::from_fn(n, |i, _| x[(i, 0)].sin() + 0.3 * x[(i, 3)]);
    let y1 = DVector::from_fn(n, |i, _| (x[(i, 1)] * 0.5).cos() - 0.1 * x[(i, 2)]);
    let rows = (0..t * D)
        .map(|k| rng.random_range(-1.2..1.2) * (1.0 + (k % D) as f64))
        .collect();
    (x, [y0, y1], rows)
}

fn fitted(kind: GpKind, m: usize, x: &DMatrix<f64>, y: &DVector<f64>) -> GpModel {
    GpParams::new(kind)
        .pseudo_inputs(m)
        .max_iters(12)
        .fit(x, y)
        .expect("fits")
}

#[test]
fn every_model_gets_the_bits_of_its_own_call_on_any_number_of_threads() {
    let (x, [y0, y1], rows) = toy(140, 300, 21);
    let models = [
        fitted(GpKind::SpgpHet, 19, &x, &y0),
        fitted(GpKind::Spgp, 7, &x, &y1),
        fitted(GpKind::SpgpHet, 11, &x, &y1),
    ];
    let readouts = [Readout::Full, Readout::Mean, Readout::Full];
    let jobs: Vec<(&GpModel, Readout)> = models.iter().zip(readouts).collect();
    let groups = [3, 1, 140, 6, 5, 2, 130, 13];
    for threads in [1, 2] {
        let got = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool")
            .install(|| GpModel::predict_jointly(&jobs, &rows, &groups).expect("predicts"));
        assert_eq!(got.len(), 3);
        for ((model, readout), got) in jobs.iter().zip(&got) {
            let alone = model.predict_row_groups(&rows, &groups).expect("alone");
            match (readout, got) {
                (Readout::Full, Predicted::Full(p)) => assert_eq!(p, &alone),
                (Readout::Mean, Predicted::Mean(mean)) => assert_eq!(mean, &alone.mean),
                other => panic!("readout and result disagree: {other:?}"),
            }
            assert_eq!(got.mean(), &alone.mean);
        }
    }
}

#[test]
fn models_on_other_inputs_or_full_gps_fall_back_to_their_own_calls() {
    let (x, [y0, y1], rows) = toy(120, 40, 22);
    let shifted = x.map(|v| v + 1.0); // another input transform
    let models = [
        fitted(GpKind::Spgp, 9, &x, &y0),
        fitted(GpKind::Spgp, 9, &shifted, &y1),
        fitted(GpKind::Full, 0, &x, &y1),
    ];
    let jobs: Vec<(&GpModel, Readout)> = models.iter().map(|m| (m, Readout::Full)).collect();
    let got = GpModel::predict_jointly(&jobs, &rows, &[40]).expect("predicts");
    for (model, got) in models.iter().zip(&got) {
        assert_eq!(
            got,
            &Predicted::Full(model.predict_rows(&rows).expect("alone"))
        );
    }
}

#[test]
fn a_bad_row_or_group_is_the_error_each_model_gives() {
    let (x, [y0, y1], mut rows) = toy(80, 200, 23);
    let models = [
        fitted(GpKind::Spgp, 9, &x, &y0),
        fitted(GpKind::Spgp, 9, &x, &y1),
    ];
    let jobs: Vec<(&GpModel, Readout)> = models.iter().map(|m| (m, Readout::Mean)).collect();
    assert!(matches!(
        GpModel::predict_jointly(&jobs, &rows, &[199]),
        Err(GpError::InvalidParams(_))
    ));
    rows[150 * D + 4] = f64::NAN;
    match GpModel::predict_jointly(&jobs, &rows, &[200]) {
        Err(GpError::DegenerateData(msg)) => {
            assert!(msg.contains("row 150") && msg.contains("'x4'"), "{msg}")
        }
        other => panic!("expected an error, got {other:?}"),
    }
    let none: &[(&GpModel, Readout)] = &[];
    assert!(
        GpModel::predict_jointly(none, &rows, &[200])
            .unwrap()
            .is_empty()
    );
}
