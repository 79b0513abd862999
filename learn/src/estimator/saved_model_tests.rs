//! Tests of the motion estimator's model files: a saved model loads and predicts identically,
//! with or without PLS projections and noise GPs, and another version is refused by name.

use super::tests::{estimate_for, quick_estimator, small_params, write_dataset};
use super::*;

/// The quick estimator, saved as `model.json` in `dir`.
fn saved_quick_estimator(dir: &std::path::Path) -> (MotionEstimator, std::path::PathBuf) {
    let estimator = quick_estimator(dir);
    let path = dir.join("model.json");
    estimator.save(&path).unwrap();
    (estimator, path)
}

#[test]
fn a_saved_model_loads_and_predicts_identically() {
    let dir = tempfile::tempdir().unwrap();
    let (estimator, path) = saved_quick_estimator(dir.path());
    let loaded = MotionEstimator::load(&path).unwrap();
    assert_eq!(loaded.feature_params(), estimator.feature_params());
    assert_eq!(
        estimate_for(&loaded, 0.5, 5.0),
        estimate_for(&estimator, 0.5, 5.0)
    );
}

#[test]
fn a_saved_model_with_pls_projections_and_noise_gps_loads_and_predicts_identically() {
    let dir = tempfile::tempdir().unwrap();
    let dataset = write_dataset(dir.path(), &[(0.5, 5.0), (-1.5, 7.0), (2.5, 4.0)]);
    let params = EstimatorParams {
        samples: 100,
        pseudo_inputs: 8,
        max_iters: 15,
        projection_dims: 4,
        most_likely_noise: true,
        ..small_params()
    };
    let estimator = MotionEstimator::train(&dataset, &params).unwrap();
    assert!(
        estimator
            .regressors()
            .iter()
            .all(|r| { r.projection.as_ref().is_some_and(|p| p.dims == 4) && r.noise.is_some() })
    );
    let path = dir.path().join("model.json");
    estimator.save(&path).unwrap();
    let loaded = MotionEstimator::load(&path).unwrap();
    assert_eq!(
        estimate_for(&loaded, 0.5, 5.0),
        estimate_for(&estimator, 0.5, 5.0)
    );
}

#[test]
fn a_model_file_of_another_version_is_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("old.json");
    std::fs::write(
        &path,
        r#"{"format": "patchflow-motion-model", "version": 0}"#,
    )
    .unwrap();
    let err = MotionEstimator::load(&path).unwrap_err().to_string();
    assert!(
        err.contains("old.json") && err.contains("version 0"),
        "{err}"
    );
}

#[test]
fn a_model_file_without_a_patch_cell_reads_its_patches_from_the_maps_themselves() {
    let dir = tempfile::tempdir().unwrap();
    let (_, path) = saved_quick_estimator(dir.path());
    // A file written before the patches had maps of their own.
    let mut json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    let features = json["features"].as_object_mut().unwrap();
    assert!(features.remove("patch_cell_m").is_some());
    features.insert("cell_m".into(), serde_json::json!(0.2));
    std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
    let loaded = MotionEstimator::load(&path).unwrap();
    assert_eq!(loaded.feature_params().patch_cell_m, 0.2);
    assert!(!loaded.feature_params().has_patch_maps());
}
