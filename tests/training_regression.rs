//! Regression test of model training: cross-validated heading and speed RMSE of SPGP-HET on a
//! small fixed scene (fixed scenario, seed and settings) must not get worse than recorded bounds.
//! A change to the simulator, the features or the GPs that makes the learned model worse fails
//! here. The bounds are the values measured when the test was written plus a margin for
//! floating-point differences between machines; tighten them when the model improves.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use patchflow_eval::{CvGp, CvParams, cross_validate};
use patchflow_learn::{EstimatorParams, FeatureKind, MotionEstimator, SampleSet, TrainingSample};

/// Re-recorded at stop 63 (2026-12-06), when cross-validation began to draw the default's own
/// features (its 0.5-0.85 m slice and patches on 0.20 m maps; before, the thesis' slice and
/// 0.10 m maps): measured 20.34° with seed 5. With the thesis' features 27.68° (seeds 6 and 7:
/// 25.26°, 27.85°); before mirror images and jittered speed alignments 9.75°: this scene's cars
/// all pass on one side, which a lopsided training set learned as a prior and the mirror images
/// take away.
const HEADING_RMSE_BOUND_DEG: f64 = 24.0;
/// Measured 0.812 m/s with seed 5 at stop 63 (with the thesis' features 1.040 m/s; before the
/// jittered speed alignments, whose errors the test patches carry too, 0.504 m/s).
const SPEED_RMSE_BOUND_MPS: f64 = 1.00;

#[test]
fn cross_validated_heading_and_speed_errors_stay_within_the_recorded_bounds() {
    // The bounds were recorded on the world of the first release, kept as the ideal rung.
    let scene = format!("realism = \"ideal\"\n{}", patchflow_tests::TRAFFIC_SCENE);
    check_bounds(&scene, HEADING_RMSE_BOUND_DEG, SPEED_RMSE_BOUND_MPS);
}

/// On the default urban rung with the default's features: measured 20.36° with seed 5 (stop 63);
/// with the thesis' 0.5-1.0 m slice and 0.10 m maps 30.21° (2026-12-01), and with the window
/// sills of the first street world (side glass from 0.8 m, inside that slice, so vehicles looked
/// hollow in the maps) 44.48°.
const URBAN_HEADING_RMSE_BOUND_DEG: f64 = 24.0;
/// Measured 0.856 m/s on urban with seed 5 (stop 63; with the thesis' features 0.993 m/s).
const URBAN_SPEED_RMSE_BOUND_MPS: f64 = 1.05;

#[test]
fn cross_validated_errors_on_the_urban_rung_stay_within_their_recorded_bounds() {
    check_bounds(
        patchflow_tests::TRAFFIC_SCENE,
        URBAN_HEADING_RMSE_BOUND_DEG,
        URBAN_SPEED_RMSE_BOUND_MPS,
    );
}

/// Cross-validates SPGP-HET on `scene` (the default's patch features, prior 0.5) and checks both
/// bounds.
fn check_bounds(scene: &str, heading_bound_deg: f64, speed_bound_mps: f64) {
    let dir = tempfile::tempdir().unwrap();
    let dataset = patchflow_tests::generate_scene(dir.path(), "regression", scene, 11);
    let params = CvParams {
        folds: 3,
        samples: 600,
        pseudo_inputs: 20,
        max_iters: 60,
        priors: vec![0.5],
        seed: 5,
        mirror_images: true,
    };
    let features = EstimatorParams::default().features;
    let report = cross_validate(&dataset, &features, &params, &|_, _| {}).unwrap();
    let row = report
        .rows
        .iter()
        .find(|r| r.gp == CvGp::SpgpHet && r.feature == patchflow_eval::CvFeature::Patch)
        .unwrap();
    let speed = row.speed_rmse_mps.unwrap();
    println!(
        "heading RMSE {:.3} deg, speed RMSE {:.4} m/s",
        row.heading_rmse_deg, speed
    );
    assert!(
        row.heading_rmse_deg <= heading_bound_deg,
        "heading RMSE {:.3} deg > bound {heading_bound_deg}",
        row.heading_rmse_deg
    );
    assert!(
        speed <= speed_bound_mps,
        "speed RMSE {speed:.4} m/s > bound {speed_bound_mps}"
    );
}

/// Held-out heading and speed RMSE of the whole estimator (its three regressions, with their
/// projections and noise GPs) trained by `params` on the first two thirds of a draw from
/// `dataset` under `params.seed` and tested on the last third: (heading °, speed m/s).
fn held_out_errors(dataset: &patchflow_dataset::Dataset, params: &EstimatorParams) -> (f64, f64) {
    let set = SampleSet::collect(
        dataset,
        &params.features,
        FeatureKind::Patch,
        600,
        params.seed,
    )
    .unwrap();
    let cut = set.samples.len() * 2 / 3;
    let train = SampleSet {
        samples: set.samples[..cut].to_vec(),
        ..set.clone()
    };
    let test = &set.samples[cut..];
    let model = MotionEstimator::fit_samples(&train, params).unwrap();
    let rows = |pick: fn(&TrainingSample) -> &Vec<f64>| -> Vec<f64> {
        test.iter().flat_map(|s| pick(s).iter().copied()).collect()
    };
    let [sin, cos, speed] = model.regressors();
    let heading_rows = rows(|s| &s.heading_features);
    let n = test.len();
    let sin = sin.predict_row_groups(&heading_rows, &[n]).unwrap().mean;
    let cos = cos.predict_row_groups(&heading_rows, &[n]).unwrap().mean;
    let speed = speed
        .predict_row_groups(&rows(|s| &s.speed_features), &[n])
        .unwrap()
        .mean;
    let (mut heading_sq, mut speed_sq) = (0.0, 0.0);
    for (k, s) in test.iter().enumerate() {
        let d = sin[k].atan2(cos[k]) - s.sin_rel.atan2(s.cos_rel);
        let error = d.sin().atan2(d.cos()); // wrapped to (−π, π]
        heading_sq += error.to_degrees().powi(2);
        speed_sq += (speed[k] - s.speed_mps).powi(2);
    }
    let rmse = |sq: f64| (sq / n as f64).sqrt();
    (rmse(heading_sq), rmse(speed_sq))
}

/// The held-out check's sizes, as small as the cross-validation's above.
fn small(params: EstimatorParams) -> EstimatorParams {
    EstimatorParams {
        samples: 400,
        pseudo_inputs: 20,
        max_iters: 60,
        seed: 5,
        ..params
    }
}

/// The seeds the held-out errors are averaged over: one seed's draw of 400 samples swings the
/// default's speed RMSE by 0.4 m/s on `ideal` (1.85-2.27 m/s over seeds 3-8).
const HELD_OUT_SEEDS: [u64; 3] = [5, 6, 7];

fn check_held_out(scene: &str, params: &EstimatorParams, bounds: (f64, f64)) {
    let dir = tempfile::tempdir().unwrap();
    let dataset = patchflow_tests::generate_scene(dir.path(), "regression", scene, 11);
    let (mut heading, mut speed) = (0.0, 0.0);
    let draws = HELD_OUT_SEEDS.len() as f64;
    for seed in HELD_OUT_SEEDS {
        let (h, s) = held_out_errors(
            &dataset,
            &EstimatorParams {
                seed,
                ..params.clone()
            },
        );
        println!("seed {seed}: held-out heading RMSE {h:.3} deg, speed RMSE {s:.4} m/s");
        (heading, speed) = (heading + h / draws, speed + s / draws);
    }
    println!("mean: held-out heading RMSE {heading:.3} deg, speed RMSE {speed:.4} m/s");
    assert!(
        heading <= bounds.0,
        "heading RMSE {heading:.3} deg > bound {}",
        bounds.0
    );
    assert!(
        speed <= bounds.1,
        "speed RMSE {speed:.4} m/s > bound {}",
        bounds.1
    );
}

/// Bounds of the default estimator's held-out errors (heading °, speed m/s), the mean over
/// [`HELD_OUT_SEEDS`], on `ideal` and `urban` with its per-vehicle fleet (400 training and 200
/// test samples, 20 pseudo-inputs, 60 iterations). Measured 2026-12-06 on stop 60's maps (each
/// sweep's beams traced once, a beam's cells those of its whole line): 70.41°/2.046 m/s on
/// `ideal`, 48.14°/1.730 m/s on `urban` (stop 59's maps: 70.42°/2.016 and 51.48°/1.900). Until
/// stop 59 the bounds held seed 5 alone, measured 2026-12-04 with the default's patches on maps
/// of 0.20 m cells (`WIDE_PATCH_CELL_M`): 70.24°/2.036 m/s on `ideal`, 48.15°/2.022 m/s on
/// `urban` (on stop 60's maps 67.31°/2.267 and 42.27°/1.993); with the thesis' 0.10 m patches
/// (stop 41's default) 74.64°/1.774 and 67.72°/1.738; with the previous 0.5-1.0 m slice
/// 48.61°/1.209 and 78.75°/1.624 (55.59°/1.136 without the fleet); with a 0.35-0.85 m slice
/// 29.56°/1.150 and 79.07°/1.733. This small one-sided scene's per-sample heading swings by tens
/// of degrees with the slice while the thesis preset's stays at 10-25°, so these bounds catch a
/// broken model, not a worse one; on the situations' targets the lower top and the wider patches
/// gain on every seed (docs/estimator.md). Which part of the default makes it so fragile here is
/// not measured (the most-likely noise GP's refit on 400 samples is one suspect). Held-out
/// samples are drawn ones only, no mirror images.
const DEFAULT_HELD_OUT_IDEAL: (f64, f64) = (76.0, 2.21);
const DEFAULT_HELD_OUT_URBAN: (f64, f64) = (54.0, 1.95);
/// The thesis preset's (its 0.5-1.0 m slice), the mean over [`HELD_OUT_SEEDS`] on stop 60's
/// maps: 16.27°/0.952 m/s on `ideal`, 19.79°/1.259 m/s on `urban` (stop 59's maps: 15.55°/0.980
/// and 20.47°/1.252; seed 5 alone, until stop 59: 16.24°/1.008 and 25.07°/1.231, 21.11°/0.418
/// m/s on `urban` without the fleet).
const THESIS_HELD_OUT_IDEAL: (f64, f64) = (18.5, 1.10);
const THESIS_HELD_OUT_URBAN: (f64, f64) = (23.0, 1.41);

/// The `urban` scene of the held-out bounds: the traffic scene on the default rung, the fleet's
/// drawn bodies on (issue 24 item 4, docs/realism.md).
fn urban_scene() -> String {
    patchflow_tests::TRAFFIC_SCENE.to_owned()
}

#[test]
fn the_default_estimator_stays_within_its_held_out_bounds_on_both_rungs() {
    let ideal = format!("realism = \"ideal\"\n{}", patchflow_tests::TRAFFIC_SCENE);
    let params = small(EstimatorParams::default());
    check_held_out(&ideal, &params, DEFAULT_HELD_OUT_IDEAL);
    check_held_out(&urban_scene(), &params, DEFAULT_HELD_OUT_URBAN);
}

#[test]
fn the_thesis_preset_stays_within_its_held_out_bounds_on_both_rungs() {
    let ideal = format!("realism = \"ideal\"\n{}", patchflow_tests::TRAFFIC_SCENE);
    let params = small(EstimatorParams::thesis());
    check_held_out(&ideal, &params, THESIS_HELD_OUT_IDEAL);
    check_held_out(&urban_scene(), &params, THESIS_HELD_OUT_URBAN);
}
