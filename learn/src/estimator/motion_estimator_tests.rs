//! Tests of the motion estimator: training, the per-scan step, model files.

use super::*;
use crate::estimator::merge::{HeadingVote, merge_heading, merge_scalar};
use crate::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
use crate::{
    ClusterEstimate, ClusterMotion, Gaussian, MIN_OBJECT_POINTS, MergeRule, SweepFeatures,
};
use patchflow_dataset::{Pose, SequenceWriter, Sweep};

/// A car at `speed_mps` driving at `heading_rad` past a sensor at the origin; `sweeps` sweeps.
fn car_sweeps(heading_rad: f64, speed_mps: f64, sweeps: u32) -> Vec<Sweep> {
    let lidar = SyntheticLidar::with_resolution(24, 900);
    let start = [
        12.0 - 6.0 * heading_rad.cos(),
        3.0 - 6.0 * heading_rad.sin(),
    ];
    let mut scene = SyntheticScene {
        boxes: vec![SceneBox::car(1, start, heading_rad, speed_mps)],
    };
    let mut out = Vec::new();
    for i in 0..sweeps {
        out.push(scene.scan(&lidar, [0.0, 0.0], 0.0, i));
        scene = scene.advanced(0.1);
    }
    out
}

fn write_dataset(root: &std::path::Path, tracks: &[(f64, f64)]) -> Dataset {
    for (k, &(heading, speed)) in tracks.iter().enumerate() {
        let writer = SequenceWriter::open(root, &format!("track{k:02}")).unwrap();
        let sweeps = car_sweeps(heading, speed, 8);
        for s in &sweeps {
            writer.write_sweep(s).unwrap();
        }
        let poses: Vec<Pose> = sweeps.iter().map(|s| s.world_from_sensor).collect();
        let stamps: Vec<f64> = sweeps.iter().map(|s| s.stamp_secs).collect();
        writer
            .finish("synthetic", 0, 10.0, &poses, &stamps, "test")
            .unwrap();
    }
    Dataset::open(root).unwrap()
}

fn small_params() -> EstimatorParams {
    EstimatorParams {
        gp: GpKind::Spgp,
        features: FeatureParams {
            half_extent_m: 20.0,
            ..FeatureParams::default()
        },
        samples: 300,
        pseudo_inputs: 15,
        max_iters: 60,
        ..EstimatorParams::default()
    }
}

fn estimate_for(estimator: &MotionEstimator, heading_rad: f64, speed_mps: f64) -> ClusterEstimate {
    let sweeps = car_sweeps(heading_rad, speed_mps, 4);
    let features =
        SweepFeatures::compute(&sweeps[2], &sweeps[3], estimator.feature_params()).unwrap();
    let biggest = (0..features.clusters().len())
        .max_by_key(|&c| features.clusters().members(c).len())
        .unwrap();
    estimator
        .estimate_cluster(&features, features.clusters().members(biggest))
        .unwrap()
}

#[test]
fn a_trained_estimator_recovers_heading_and_speed_of_a_held_out_car() {
    let dir = tempfile::tempdir().unwrap();
    let tracks: Vec<(f64, f64)> = (0..8)
        .map(|k| (-3.0 + 0.8 * k as f64, 4.0 + (k % 3) as f64 * 2.0))
        .collect();
    let dataset = write_dataset(dir.path(), &tracks);
    let estimator = MotionEstimator::train(&dataset, &small_params()).unwrap();
    let (heading, speed) = (0.2, 6.0);
    let all = estimate_for(&estimator, heading, speed).all.unwrap();
    let heading_error_deg = (all.heading_rad - heading)
        .sin()
        .atan2((all.heading_rad - heading).cos())
        .to_degrees();
    assert!(
        heading_error_deg.abs() < 30.0,
        "heading error {heading_error_deg:.1} deg: {all:?}"
    );
    assert!((all.speed_mps - speed).abs() < 2.5, "speed {all:?}");
}

/// A quickly trained estimator (its accuracy does not matter where it is used).
fn quick_estimator(dir: &std::path::Path) -> MotionEstimator {
    let dataset = write_dataset(dir, &[(0.5, 5.0), (-1.5, 7.0), (2.5, 4.0)]);
    let params = EstimatorParams {
        samples: 100,
        pseudo_inputs: 8,
        max_iters: 15,
        ..small_params()
    };
    MotionEstimator::train(&dataset, &params).unwrap()
}

#[test]
fn patch_rows_go_into_the_gp_input_rows_unchanged_and_in_order() {
    let dir = tempfile::tempdir().unwrap();
    let estimator = quick_estimator(dir.path());
    let sweeps = car_sweeps(0.5, 5.0, 2);
    let features =
        SweepFeatures::compute(&sweeps[0], &sweeps[1], estimator.feature_params()).unwrap();
    let n = features.len().min(150);
    assert!(n > 100, "{n} points: more than one task of rows");
    let axis_of = |i: usize| -> ([f64; 2], f64) {
        let p = &features.points()[i];
        ([p.x_m, p.y_m], 0.3 * i as f64)
    };
    let x = estimator.input_rows(&features, n, axis_of).unwrap();
    let expected: Vec<f64> = (0..n)
        .flat_map(|i| {
            let (xy, axis_rad) = axis_of(i);
            features.patch_at(xy, axis_rad).values
        })
        .collect();
    assert_eq!(x, expected);
}

/// Thesis 3.1 steps 3-4 on one cluster with one `GpModel::predict` call per step, predicted at
/// `positions`: the reference the predictions of many clusters in one batch must reproduce
/// exactly.
fn reference_estimate(
    estimator: &MotionEstimator,
    features: &SweepFeatures,
    positions: &[[f64; 2]],
) -> ClusterEstimate {
    let patches: Vec<_> = positions
        .iter()
        .map(|&xy| features.patch_at(xy, features.bearing_at(xy)))
        .collect();
    // Each regression called on this cluster's rows alone (its projection and noise GP, if any,
    // applied as one call does).
    let flat = |patches: &[crate::Patch]| -> Vec<f64> {
        patches
            .iter()
            .flat_map(|p| p.values.iter().copied())
            .collect()
    };
    let x = flat(&patches);
    let n = [positions.len()];
    let [sin_gp, cos_gp, speed_gp] = estimator.regressors();
    let (sin, cos) = (
        sin_gp.predict_row_groups(&x, &n).unwrap(),
        cos_gp.predict_row_groups(&x, &n).unwrap(),
    );
    let votes: Vec<HeadingVote> = positions
        .iter()
        .enumerate()
        .map(|(k, &xy)| {
            let g = |p: &crate::GpPrediction| Gaussian {
                mean: p.mean[k],
                var: p.var_y[k],
            };
            HeadingVote::from_relative(features.bearing_at(xy), g(&sin), g(&cos))
        })
        .collect();
    let along = |rule| {
        let heading = merge_heading(&votes, rule)?;
        let patches: Vec<_> = positions
            .iter()
            .map(|&xy| features.patch_at(xy, heading.heading_rad))
            .collect();
        let speed = speed_gp.predict_row_groups(&flat(&patches), &n).unwrap();
        let predictions: Vec<Gaussian> = (0..positions.len())
            .map(|k| Gaussian {
                mean: speed.mean[k],
                var: speed.var_y[k],
            })
            .collect();
        merge_scalar(&predictions, rule).map(|s| ClusterMotion {
            heading_rad: heading.heading_rad,
            heading_var: heading.var_rad2,
            speed_mps: s.mean.max(0.0),
            speed_var: s.var,
            heading_votes: heading.votes,
        })
    };
    ClusterEstimate {
        all: along(MergeRule::All),
        best: along(MergeRule::Best),
    }
}

#[test]
fn batched_predictions_equal_one_gp_call_per_cluster_and_step_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let estimator = quick_estimator(dir.path());
    // A close car (hundreds of points: several blocks of GP rows), a far one, and a long wall.
    let scene = SyntheticScene {
        boxes: vec![
            SceneBox::car(1, [6.0, 2.5], 0.3, 6.0),
            SceneBox::car(2, [14.0, -6.0], 2.0, 4.0),
            SceneBox::wall([0.0, -12.0], 0.0, [30.0, 0.4, 2.5]),
        ],
    };
    let lidar = SyntheticLidar::with_resolution(64, 1800);
    let previous = scene.scan(&lidar, [0.0, 0.0], 0.0, 0);
    let current = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
    let scan = estimator.estimate_scan(&previous, &current).unwrap();
    let features = &scan.features;
    assert_eq!(features.clusters().len(), 3);
    let biggest = (0..3)
        .map(|c| features.clusters().members(c).len())
        .max()
        .unwrap();
    assert!(biggest > 300, "{biggest} points");
    for c in 0..3 {
        let members = features.clusters().members(c);
        let wall = features.points()[members[0]].y_m < -10.0;
        // Every point, as for the thesis' hand-labelled target (several blocks for the close car).
        let points: Vec<[f64; 2]> = members
            .iter()
            .map(|&i| [features.points()[i].x_m, features.points()[i].y_m])
            .collect();
        let whole = estimator.estimate_cluster(features, members).unwrap();
        assert_eq!(whole, reference_estimate(&estimator, features, &points));
        // One sample per occupied cell in the whole-scan step; walls are no hypotheses.
        match scan.motion.clusters[c] {
            None => assert!(wall, "cluster {c} was left out"),
            Some(estimate) => {
                assert!(!wall, "the wall was estimated");
                assert!(estimate.all.is_some());
                let cells = features.cell_samples(members);
                assert!(cells.len() < members.len());
                assert_eq!(
                    estimate,
                    reference_estimate(&estimator, features, &cells.positions)
                );
            }
        }
    }
    assert_eq!(scan.motion.timing.clusters, 2);
}

#[test]
fn every_point_of_an_estimated_cluster_gets_its_own_heading_and_speed() {
    let dir = tempfile::tempdir().unwrap();
    let estimator = quick_estimator(dir.path());
    let sweeps = car_sweeps(0.4, 6.0, 2);
    let scan = estimator.estimate_scan(&sweeps[0], &sweeps[1]).unwrap();
    let members = scan.features.clusters().members(0);
    assert!(members.len() > 10);
    let cells = scan.features.cell_samples(members);
    for (&i, &cell) in members.iter().zip(&cells.sample_of_member) {
        let point = scan.motion.points[i].unwrap();
        let first_of_cell = cells
            .sample_of_member
            .iter()
            .position(|&c| c == cell)
            .unwrap();
        assert_eq!(Some(point), scan.motion.points[members[first_of_cell]]);
        assert!(
            point.heading_var > 0.0 && point.speed_var > 0.0,
            "{point:?}"
        );
        assert!(point.speed_mps >= 0.0);
        let [vx, vy] = point.velocity_xy_mps();
        assert!((vx.hypot(vy) - point.speed_mps).abs() < 1e-9);
    }
}

#[test]
fn a_saved_model_loads_and_predicts_identically() {
    let dir = tempfile::tempdir().unwrap();
    let estimator = quick_estimator(dir.path());
    let path = dir.path().join("model.json");
    estimator.save(&path).unwrap();
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
fn a_dataset_without_moving_actors_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let dataset = write_dataset(dir.path(), &[(0.0, 0.0)]);
    let err = MotionEstimator::train(&dataset, &small_params()).unwrap_err();
    assert!(
        matches!(
            err,
            LearnError::DegenerateData(_) | LearnError::InvalidParams(_)
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

#[test]
fn a_cluster_of_fewer_than_the_minimum_points_gets_no_estimate() {
    let dir = tempfile::tempdir().unwrap();
    let estimator = quick_estimator(dir.path());
    let scene = SyntheticScene {
        boxes: vec![SceneBox::car(1, [6.0, 2.5], 0.3, 6.0)],
    };
    let lidar = SyntheticLidar::with_resolution(64, 1800);
    let previous = scene.scan(&lidar, [0.0, 0.0], 0.0, 0);
    let current = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
    let features = estimator
        .estimate_scan(&previous, &current)
        .unwrap()
        .features;
    let car = features.clusters().members(0);
    assert!(car.len() > MIN_OBJECT_POINTS, "{} points", car.len());
    let few = estimator
        .estimate_cluster(&features, &car[..MIN_OBJECT_POINTS - 1])
        .unwrap();
    assert_eq!(few, ClusterEstimate::default());
    let enough = estimator
        .estimate_cluster(&features, &car[..MIN_OBJECT_POINTS])
        .unwrap();
    assert!(enough.all.is_some() && enough.best.is_some());
}
