//! End-to-end fits on toy data (thesis Figure 3.5-style) and degenerate inputs.

use nalgebra::{DMatrix, DVector};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use crate::{GpError, GpKind, GpParams};

/// y = sin(x) on [0, 10] with noise sd `low` below x = 5 and `high` above.
fn toy(n: usize, low: f64, high: f64, seed: u64) -> (DMatrix<f64>, DVector<f64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let unit = Normal::new(0.0, 1.0).expect("valid normal");
    let x: DMatrix<f64> = DMatrix::from_fn(n, 1, |_, _| rng.random_range(0.0..10.0));
    let y = DVector::from_fn(n, |i, _| {
        let sd = if x[(i, 0)] < 5.0 { low } else { high };
        x[(i, 0)].sin() + sd * unit.sample(&mut rng)
    });
    (x, y)
}

fn grid(a: f64, b: f64, n: usize) -> DMatrix<f64> {
    DMatrix::from_fn(n, 1, |i, _| a + (b - a) * i as f64 / (n - 1) as f64)
}

#[test]
fn spgp_recovers_a_sine_from_noisy_samples() {
    let (x, y) = toy(80, 0.05, 0.05, 1);
    let model = GpParams::new(GpKind::Spgp)
        .pseudo_inputs(10)
        .max_iters(100)
        .fit(&x, &y)
        .expect("fits");
    let t = grid(0.5, 9.5, 50);
    let p = model.predict(&t).expect("predicts");
    let rmse = (p.mean - t.column(0).map(f64::sin)).norm() / 50f64.sqrt();
    assert!(rmse < 0.08, "rmse {rmse}");
    assert!(model.fit_report().evals > 1 && model.fit_report().nlml.is_finite());
}

#[test]
fn the_full_gp_recovers_a_sine_from_noisy_samples() {
    let (x, y) = toy(60, 0.05, 0.05, 2);
    let model = GpParams::new(GpKind::Full)
        .max_iters(100)
        .fit(&x, &y)
        .expect("fits");
    let t = grid(0.5, 9.5, 50);
    let p = model.predict(&t).expect("predicts");
    let rmse = (p.mean - t.column(0).map(f64::sin)).norm() / 50f64.sqrt();
    assert!(rmse < 0.08, "rmse {rmse}");
    assert!(
        (model.noise_variance() - 0.0025).abs() < 0.003,
        "σ² {}",
        model.noise_variance()
    );
}

#[test]
fn spgp_het_predicts_more_variance_where_the_training_noise_is_larger() {
    let (x, y) = toy(200, 0.05, 0.5, 3);
    let model = GpParams::new(GpKind::SpgpHet)
        .pseudo_inputs(12)
        .max_iters(150)
        .fit(&x, &y)
        .expect("fits");
    let quiet = model
        .predict(&grid(0.5, 4.5, 20))
        .expect("predicts")
        .var_y
        .mean();
    let noisy = model
        .predict(&grid(5.5, 9.5, 20))
        .expect("predicts")
        .var_y
        .mean();
    assert!(
        noisy > 3.0 * quiet,
        "noisy side {noisy} vs quiet side {quiet}"
    );
}

#[test]
fn fitting_twice_gives_the_identical_model() {
    let (x, y) = toy(300, 0.1, 0.1, 4); // two row blocks, so the parallel reduction is exercised
    let params = GpParams::new(GpKind::SpgpHet)
        .pseudo_inputs(6)
        .max_iters(20);
    let a = params.fit(&x, &y).expect("fits");
    let b = params.fit(&x, &y).expect("fits");
    assert_eq!(a.hyper, b.hyper);
    assert_eq!(a.posterior, b.posterior);
}

/// A degenerate fit must not panic; if it succeeds, its predictions must be finite.
fn fits_or_errors(kind: GpKind, x: &DMatrix<f64>, y: &DVector<f64>, m: usize) {
    match GpParams::new(kind).pseudo_inputs(m).max_iters(30).fit(x, y) {
        Ok(model) => {
            let p = model.predict(&x.rows(0, 2).into_owned()).expect("predicts");
            assert!(
                p.mean.iter().chain(p.var_y.iter()).all(|v| v.is_finite()),
                "{kind}: non-finite prediction"
            );
        }
        Err(e) => assert!(
            matches!(e, GpError::DegenerateData(_) | GpError::Numerical(_)),
            "{kind}: {e}"
        ),
    }
}

#[test]
fn duplicate_inputs_constant_targets_and_constant_columns_give_sane_models() {
    let (x, y) = toy(20, 0.1, 0.1, 5);
    let doubled = DMatrix::from_fn(40, 1, |i, _| x[(i % 20, 0)]);
    let doubled_y = DVector::from_fn(40, |i, _| y[i % 20]);
    let constant_y = DVector::from_element(20, 3.0);
    let with_constant_col = DMatrix::from_fn(20, 2, |i, d| if d == 0 { x[(i, 0)] } else { 7.0 });
    for kind in [GpKind::Full, GpKind::Spgp, GpKind::SpgpHet] {
        fits_or_errors(kind, &doubled, &doubled_y, 10);
        fits_or_errors(kind, &x, &constant_y, 5);
        fits_or_errors(kind, &with_constant_col, &y, 5);
    }
}

#[test]
fn more_pseudo_inputs_than_samples_are_capped_at_n() {
    let (x, y) = toy(7, 0.1, 0.1, 6);
    let model = GpParams::new(GpKind::Spgp)
        .pseudo_inputs(100)
        .max_iters(20)
        .fit(&x, &y)
        .expect("fits");
    assert_eq!(model.fit_report().m, 7);
}

#[test]
fn non_finite_inputs_or_too_few_samples_are_errors() {
    let (mut x, y) = toy(10, 0.1, 0.1, 7);
    x[(3, 0)] = f64::NAN;
    let err = GpParams::new(GpKind::Spgp)
        .fit(&x, &y)
        .expect_err("NaN input");
    assert!(matches!(err, GpError::DegenerateData(_)), "{err}");
    let one = DMatrix::from_element(1, 1, 0.5);
    assert!(
        GpParams::new(GpKind::Full)
            .fit(&one, &DVector::from_element(1, 1.0))
            .is_err()
    );
}

#[test]
fn held_pseudo_inputs_stay_at_their_seeded_subset_and_leave_the_vector() {
    let (x, y) = toy(60, 0.1, 0.1, 8);
    let params = GpParams::new(GpKind::SpgpHet)
        .pseudo_inputs(6)
        .max_iters(20);
    let moving = params.clone().fit(&x, &y).expect("fits");
    let held = params
        .clone()
        .optimise_pseudo_inputs(false)
        .fit(&x, &y)
        .expect("fits");
    // The same seed draws the same starting subset; only the moving fit changes it.
    let start = crate::GpObjective::new(&params.check().expect("valid"), &x, &y).expect("sets up");
    let z0 = start.start.pseudo_inputs.clone();
    assert_eq!(held.pseudo_inputs(), &z0);
    assert_ne!(moving.pseudo_inputs(), &z0);
    let fixed = crate::GpObjective::new(
        &params.optimise_pseudo_inputs(false).check().expect("valid"),
        &x,
        &y,
    )
    .expect("sets up");
    assert_eq!(start.dims() - fixed.dims(), 6);
}

#[test]
fn values_too_large_to_standardise_are_an_error_naming_the_column() {
    let (mut x, mut y) = toy(20, 0.1, 0.1, 9);
    x[(4, 0)] = 1e300;
    let err = GpParams::new(GpKind::Spgp)
        .pseudo_inputs(4)
        .fit(&x, &y)
        .expect_err("overflowing input");
    assert!(
        matches!(err, GpError::DegenerateData(_)) && err.to_string().contains("'x0'"),
        "{err}"
    );
    x[(4, 0)] = 1.0;
    y[2] = -1e300;
    let err = GpParams::new(GpKind::Full)
        .fit(&x, &y)
        .expect_err("overflowing target");
    assert!(err.to_string().contains("'y'"), "{err}");
}
