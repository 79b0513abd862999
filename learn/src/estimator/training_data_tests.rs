//! Tests of what the motion estimator trains on: a dataset without moving actors is an error,
//! mirror images double the rows, samples and features drawn with other parameters are refused.

use super::tests::{car_sweeps, small_params, write_dataset};
use super::*;
use patchflow_gp::GpError;

#[test]
fn a_dataset_without_moving_actors_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let dataset = write_dataset(dir.path(), &[(0.0, 0.0)]);
    let err = MotionEstimator::train(&dataset, &small_params()).unwrap_err();
    assert!(
        matches!(
            err,
            LearnError::Gp(GpError::DegenerateData(_) | GpError::InvalidParams(_))
        ),
        "{err}"
    );
}

#[test]
fn mirror_images_double_the_rows_each_gp_is_fitted_to() {
    let dir = tempfile::tempdir().unwrap();
    let dataset = write_dataset(dir.path(), &[(0.4, 5.0)]);
    let params = EstimatorParams {
        max_iters: 5,
        mirror_images: true,
        ..small_params()
    };
    let set = SampleSet::collect(
        &dataset,
        &params.features,
        params.feature,
        params.samples,
        params.seed,
    )
    .unwrap();
    let n = set.samples.len();
    let with = MotionEstimator::fit_samples(&set, &params).unwrap();
    let thesis = EstimatorParams {
        mirror_images: false,
        ..params
    };
    let without = MotionEstimator::fit_samples(&set, &thesis).unwrap();
    assert!(with.gps().iter().all(|gp| gp.fit_report().n == 2 * n));
    assert!(without.gps().iter().all(|gp| gp.fit_report().n == n));
    assert_eq!(with.training().samples, n);
    assert!(with.training().mirror_images && !without.training().mirror_images);
}

#[test]
fn fit_samples_uses_the_first_params_samples_and_refuses_samples_drawn_otherwise() {
    let dir = tempfile::tempdir().unwrap();
    let dataset = write_dataset(dir.path(), &[(0.4, 5.0)]);
    let params = EstimatorParams {
        max_iters: 5,
        ..small_params()
    };
    let set =
        SampleSet::collect(&dataset, &params.features, params.feature, 300, params.seed).unwrap();
    assert!(set.samples.len() > 20, "{} samples", set.samples.len());
    let fewer = EstimatorParams {
        samples: 20,
        mirror_images: false,
        ..params.clone()
    };
    let estimator = MotionEstimator::fit_samples(&set, &fewer).unwrap();
    assert_eq!(estimator.training().samples, 20);
    assert!(estimator.gps().iter().all(|gp| gp.fit_report().n == 20));
    assert_eq!(estimator.feature_params(), &params.features);
    let other_prior = EstimatorParams {
        features: FeatureParams {
            prior: 0.01,
            ..params.features.clone()
        },
        ..fewer.clone()
    };
    let err = MotionEstimator::fit_samples(&set, &other_prior).unwrap_err();
    assert!(err.to_string().contains("feature parameters"), "{err}");
    let other_kind = EstimatorParams {
        feature: FeatureKind::Gabor,
        ..fewer
    };
    assert!(MotionEstimator::fit_samples(&set, &other_kind).is_err());
}

#[test]
fn features_computed_with_other_parameters_than_the_models_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let dataset = write_dataset(dir.path(), &[(0.4, 5.0)]);
    let params = EstimatorParams {
        samples: 40,
        max_iters: 5,
        ..small_params()
    };
    let estimator = MotionEstimator::train(&dataset, &params).unwrap();
    let sweeps = car_sweeps(0.4, 5.0, 4);
    let other = FeatureParams {
        half_extent_m: 15.0,
        ..estimator.feature_params().clone()
    };
    let features = SweepFeatures::compute(&sweeps[2], &sweeps[3], &other).unwrap();
    let err = estimator.estimate_features(&features).unwrap_err();
    assert!(err.to_string().contains("trained with"), "{err}");
    let same = SweepFeatures::compute(&sweeps[2], &sweeps[3], estimator.feature_params()).unwrap();
    estimator.estimate_features(&same).unwrap();
}
