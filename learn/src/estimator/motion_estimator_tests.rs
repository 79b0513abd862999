//! Tests of the motion estimator: training and the per-scan step, and the fixtures (a car
//! driving past, a small dataset, small parameters) the other estimator tests share.

use super::*;
use crate::estimator::merge::{HeadingVote, merge_heading, merge_scalar};
use crate::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
use crate::{
    ClusterEstimate, ClusterMotion, Gaussian, MIN_OBJECT_POINTS, MergeRule, SweepFeatures,
};
use patchflow_dataset::{Pose, SequenceWriter, Sweep};

/// A car at `speed_mps` driving at `heading_rad` past a sensor at the origin; `sweeps` sweeps.
pub(super) fn car_sweeps(heading_rad: f64, speed_mps: f64, sweeps: u32) -> Vec<Sweep> {
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

pub(super) fn write_dataset(root: &std::path::Path, tracks: &[(f64, f64)]) -> Dataset {
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

pub(super) fn small_params() -> EstimatorParams {
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

pub(super) fn estimate_for(
    estimator: &MotionEstimator,
    heading_rad: f64,
    speed_mps: f64,
) -> ClusterEstimate {
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

/// Trains with `params` on eight tracks and checks a held-out car (heading 0.2 rad, 6 m/s) is
/// read within 30° and 2.5 m/s; returns the estimator.
fn assert_recovers_a_held_out_car(params: &EstimatorParams) -> MotionEstimator {
    let dir = tempfile::tempdir().unwrap();
    let tracks: Vec<(f64, f64)> = (0..8)
        .map(|k| (-3.0 + 0.8 * k as f64, 4.0 + (k % 3) as f64 * 2.0))
        .collect();
    let dataset = write_dataset(dir.path(), &tracks);
    let estimator = MotionEstimator::train(&dataset, params).unwrap();
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
    estimator
}

#[test]
fn a_trained_estimator_recovers_heading_and_speed_of_a_held_out_car() {
    assert_recovers_a_held_out_car(&small_params());
}

#[test]
fn an_estimator_on_patch_maps_of_their_own_recovers_heading_and_speed_of_a_held_out_car() {
    let mut params = small_params();
    params.features.patch_cell_m = crate::WIDE_PATCH_CELL_M;
    let estimator = assert_recovers_a_held_out_car(&params);
    assert_eq!(estimator.feature_params().patch_cell_m, 0.2);
}

/// A quickly trained estimator (its accuracy does not matter where it is used).
pub(super) fn quick_estimator(dir: &std::path::Path) -> MotionEstimator {
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
        let points = features.positions_xy(members);
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

#[test]
fn a_car_that_has_just_come_into_view_gets_no_estimate() {
    let dir = tempfile::tempdir().unwrap();
    let estimator = quick_estimator(dir.path());
    let wall = SceneBox::wall([-10.0, 0.0], 0.0, [0.4, 20.0, 2.5]);
    let lidar = SyntheticLidar::with_resolution(64, 1800);
    let seen = SyntheticScene {
        boxes: vec![SceneBox::car(1, [6.0, 2.5], 0.3, 6.0), wall.clone()],
    };
    // In the previous sweep a wall 2 m ahead hid the car (a truck that has since driven off);
    // then the same car seen in both sweeps.
    let hidden = SyntheticScene {
        boxes: vec![
            SceneBox::car(1, [6.0, 2.5], 0.3, 6.0),
            wall.clone(),
            SceneBox::wall([2.0, 1.5], 0.0, [0.4, 14.0, 2.5]),
        ],
    };
    let current = seen.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
    for (previous, expect_estimate) in [(&hidden, false), (&seen, true)] {
        let scan = estimator
            .estimate_scan(&previous.scan(&lidar, [0.0, 0.0], 0.0, 0), &current)
            .unwrap();
        let car = (0..scan.features.clusters().len())
            .find(|&c| {
                let first = scan.features.clusters().members(c)[0];
                scan.features.points()[first].x_m > 0.0
            })
            .unwrap();
        let members = scan.features.clusters().members(car);
        let alone = estimator.estimate_cluster(&scan.features, members).unwrap();
        assert_eq!(alone.all.is_some(), expect_estimate, "alone");
        assert_eq!(
            scan.motion.clusters[car].is_some(),
            expect_estimate,
            "in the scan"
        );
    }
}
