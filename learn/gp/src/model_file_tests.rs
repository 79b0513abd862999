//! Round trips and rejections of GP model files.

use nalgebra::{DMatrix, DVector};

use crate::{GpError, GpKind, GpModel, GpParams, Shape, Stationary};

fn fitted(kind: GpKind) -> GpModel {
    let x = DMatrix::from_fn(30, 2, |i, d| (i as f64 * 0.37 + d as f64).sin() * 3.0);
    let y = DVector::from_fn(30, |i, _| x[(i, 0)].cos() + 0.2 * x[(i, 1)]);
    GpParams::new(kind)
        .pseudo_inputs(6)
        .max_iters(15)
        .fit(&x, &y)
        .expect("fits")
}

#[test]
fn every_kind_round_trips_through_a_file_with_identical_predictions() {
    let dir = tempfile::tempdir().expect("temp dir");
    let test = DMatrix::from_row_slice(3, 2, &[0.1, 0.5, -2.0, 1.0, 2.5, -0.3]);
    for kind in [GpKind::Full, GpKind::Spgp, GpKind::SpgpHet] {
        let model = fitted(kind);
        let path = dir.path().join(format!("{kind}.json"));
        model.save(&path).expect("saves");
        let back = GpModel::load(&path).expect("loads");
        assert_eq!(
            back.predict(&test).expect("predicts"),
            model.predict(&test).expect("predicts")
        );
        let mut want = model.fit_report().clone();
        want.seconds = 0.0; // wall time stays out of model files
        assert_eq!(back.fit_report(), &want);
        let value = model.to_json_value().expect("serialises");
        assert_eq!(value["kind"], kind.name());
        assert!(value.get("lengthscales").is_some() && value.get("input_transform").is_some());
        assert_eq!(value.get("pseudo_noise").is_some(), kind == GpKind::SpgpHet);
    }
}

#[test]
fn another_version_a_foreign_file_and_broken_json_are_model_errors_naming_the_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut value = fitted(GpKind::Spgp).to_json_value().expect("serialises");
    value["version"] = 99.into();
    let cases = [
        ("version.json", value.to_string()),
        (
            "foreign.json",
            r#"{"format": "something-else", "version": 1}"#.to_string(),
        ),
        ("broken.json", "{\"format\": \"patchflow-gp-mo".to_string()),
        (
            "fields.json",
            r#"{"format": "patchflow-gp-model", "version": 1, "kind": "spgp"}"#.to_string(),
        ),
    ];
    for (name, text) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, text).expect("writes");
        let err = GpModel::load(&path).expect_err("must be rejected");
        assert!(matches!(err, GpError::Model { .. }), "{name}: {err}");
        assert!(
            err.to_string().contains(name),
            "{name}: message does not name the file: {err}"
        );
    }
}

#[test]
fn a_tampered_shape_is_rejected_not_panicking() {
    let mut value = fitted(GpKind::SpgpHet).to_json_value().expect("serialises");
    value["pseudo_noise"] = serde_json::json!([0.1]);
    assert!(GpModel::from_json_value(value, std::path::Path::new("m.json")).is_err());
}

#[test]
fn se_ard_models_stay_version_1_and_other_kernels_round_trip_as_version_2() {
    let x = DMatrix::from_fn(30, 3, |i, d| (i as f64 * 0.37 + d as f64).sin() * 3.0);
    let y = DVector::from_fn(30, |i, _| x[(i, 0)].cos() + 0.2 * x[(i, 2)]);
    let se = fitted(GpKind::Spgp).to_json_value().expect("serialises");
    assert_eq!(se["version"], 1);
    assert!(se.get("kernel").is_none());
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("st.json");
    let model = GpParams::new(GpKind::Spgp)
        .pseudo_inputs(5)
        .max_iters(10)
        .kernel(Stationary::space_time(
            2,
            Shape::Matern32,
            Shape::SquaredExponential,
        ))
        .fit(&x, &y)
        .expect("fits");
    model.save(&path).expect("saves");
    let back = GpModel::load(&path).expect("loads");
    assert_eq!(back.kernel(), model.kernel());
    let test = x.rows(0, 4).into_owned();
    assert_eq!(
        back.predict(&test).expect("predicts"),
        model.predict(&test).expect("predicts")
    );
    let mut value = model.to_json_value().expect("serialises");
    assert_eq!(value["version"], 2);
    value["version"] = 1.into(); // a kernel in a version 1 file: an old build would ignore it
    let err = GpModel::from_json_value(value, &path).expect_err("rejected");
    assert!(err.to_string().contains("st.json"), "{err}");
}

#[test]
fn two_identical_fits_write_byte_identical_files() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (a, b) = (dir.path().join("a.json"), dir.path().join("b.json"));
    fitted(GpKind::SpgpHet).save(&a).expect("saves");
    fitted(GpKind::SpgpHet).save(&b).expect("saves");
    let bytes = std::fs::read(&a).expect("reads");
    assert_eq!(bytes, std::fs::read(&b).expect("reads"));
    assert!(!String::from_utf8_lossy(&bytes).contains("seconds"));
}

/// `value` with its sparse posterior's var_matrix changed by `edit`.
fn with_var_matrix(kind: GpKind, edit: impl Fn(&mut Vec<Vec<f64>>)) -> serde_json::Value {
    let mut value = fitted(kind).to_json_value().expect("serialises");
    let mut w: Vec<Vec<f64>> =
        serde_json::from_value(value["posterior"]["var_matrix"].clone()).expect("matrix");
    edit(&mut w);
    value["posterior"]["var_matrix"] = serde_json::json!(w);
    value
}

#[test]
fn a_var_matrix_that_is_not_symmetric_or_not_a_fits_is_refused_naming_the_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    type Edit = fn(&mut Vec<Vec<f64>>);
    let cases: [(&str, Edit); 4] = [
        ("asymmetric", |w| w[0][1] += 1.0),
        ("negated", |w| {
            w.iter_mut().flatten().for_each(|v| *v = -*v);
        }),
        ("tenfold", |w| {
            w.iter_mut().flatten().for_each(|v| *v *= 10.0);
        }),
        ("spiked", |w| w[2][2] += 1e6),
    ];
    for kind in [GpKind::Spgp, GpKind::SpgpHet] {
        for (name, edit) in cases {
            let path = dir.path().join(format!("{name}-{kind}.json"));
            let value = with_var_matrix(kind, edit);
            std::fs::write(&path, value.to_string()).expect("writes");
            let err = GpModel::load(&path).expect_err(name).to_string();
            assert!(
                err.contains(&format!("{name}-{kind}.json")) && err.contains("var_matrix"),
                "{name}: {err}"
            );
        }
        // Untouched, it loads.
        let path = dir.path().join(format!("fitted-{kind}.json"));
        std::fs::write(&path, with_var_matrix(kind, |_| {}).to_string()).expect("writes");
        GpModel::load(&path).expect("a fitted model loads");
    }
}

#[test]
fn predictions_at_the_extremes_of_the_finite_numbers_have_a_positive_variance_or_are_refused() {
    for kind in [GpKind::Full, GpKind::Spgp, GpKind::SpgpHet] {
        let model = fitted(kind);
        for v in [
            1e308,
            -1e308,
            f64::MAX,
            f64::MIN,
            1e200,
            -3e154,
            1e50,
            -1e90,
            1e6,
        ] {
            let x = DMatrix::from_row_slice(2, 2, &[v, 0.0, 0.5, v]);
            match model.predict(&x) {
                Ok(p) => {
                    for i in 0..2 {
                        assert!(
                            p.mean[i].is_finite()
                                && p.var_latent[i] > 0.0
                                && p.var_y[i] > p.var_latent[i]
                                && p.var_y[i].is_finite(),
                            "{kind} at {v:e}: mean {} var {} var_y {}",
                            p.mean[i],
                            p.var_latent[i],
                            p.var_y[i]
                        );
                    }
                }
                Err(err) => assert!(
                    v.abs() > 1e100 && err.to_string().contains("column"),
                    "{kind} at {v:e}: {err}"
                ),
            }
        }
    }
}

#[test]
fn a_sparse_model_with_more_pseudo_inputs_than_the_bound_is_refused_before_its_check() {
    let mut value = fitted(GpKind::Spgp).to_json_value().expect("serialises");
    let row = value["pseudo_inputs"][0].clone();
    value["pseudo_inputs"] = serde_json::json!(vec![row; crate::params::MAX_PSEUDO_INPUTS + 1]);
    let err = GpModel::from_json_value(value, std::path::Path::new("wide.json"))
        .expect_err("refused")
        .to_string();
    assert!(err.contains("wide.json") && err.contains("2000"), "{err}");
}
