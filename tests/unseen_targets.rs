//! The default estimator and GP-KF on its readings on targets no training track has (issue 24,
//! "unseen shapes and traffic"): a truck, a van turning across the ego car's path, a cyclist, a
//! car crossing from the left, a truck crossing from the right, a car overtaking at 12 m/s, a van
//! crossing at 10 m/s, a car turning right out of a side street, the car ahead braking hard, an
//! oncoming truck turning across the ego's path, a car crossing from the right, an oncoming
//! cyclist, a van pulling out from the kerb, a van turning out of a side street, an oncoming
//! midibus, an oncoming car while the ego car turns, the van ahead turning into a side street and
//! a cyclist crossing from the right, from the `scenarios/unseen_*.toml` checks that `bench` and
//! `train` never read.
//! At tiny sizes (two training tracks' last sweeps, 400 samples, 20 pseudo-inputs) the model is
//! far from `bench`'s, so the bounds are the errors measured when the test was written plus a
//! margin: they catch a model that breaks on these targets, not one that misses the 25° bar
//! (docs/estimator.md has the figures at `bench --quick`'s sizes).

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use std::path::Path;

use patchflow_dataset::Dataset;
use patchflow_eval::{
    BaselineParams, Method, score_method, stages::evaluate_targets_with_baselines,
};
use patchflow_learn::{EstimatorParams, MotionEstimator};
use patchflow_sim::{GenerateOptions, ScenarioSource, Shard};

/// `(scenario, first kept sweep's time in seconds)`: 20 sweeps from there, where the target is
/// in view and moving.
const UNSEEN: [(&str, f64); 18] = [
    ("unseen_truck", 4.0),
    ("unseen_van_turn", 4.5),
    ("unseen_cyclist", 5.0),
    ("unseen_crossing_left", 4.5),
    ("unseen_truck_crossing", 4.5),
    ("unseen_overtake", 3.0),
    ("unseen_van_crossing", 4.5),
    ("unseen_right_turn", 5.5),
    ("unseen_lead_brakes", 4.0),
    ("unseen_truck_turn", 5.0),
    ("unseen_crossing_right", 5.0),
    ("unseen_oncoming_cyclist", 5.5),
    ("unseen_pull_out", 2.0),
    ("unseen_van_from_side", 5.5),
    ("unseen_bus", 4.0),
    ("unseen_ego_turning", 4.5),
    ("unseen_van_ahead_turns", 4.0),
    ("unseen_cyclist_from_right", 5.5),
];

/// The training tracks of the tiny model (two of the default's nine: traffic from all four
/// directions, crossing traffic) and the start of the 20 sweeps kept of each.
const TRAINING: [(&str, f64); 2] = [("train04", 12.0), ("train08", 11.0)];

/// Per-target bounds (heading RMSE °, speed RMSE m/s), in [`UNSEEN`]'s order: re-measured
/// 2026-12-04 (seed 7, `urban` with the per-vehicle fleet) once parked cars kept their length off
/// crossing corridors (docs/realism.md): 7.12°/0.503, 9.30°/1.491, 46.28°/1.095 and
/// 22.56°/1.819 m/s (coverage 0.47, 1.00, 0.95, 1.00), plus 15° and 0.5 m/s. Before, a parked
/// car stood across the cyclist's path at the crossing and shared its cluster: 68.63°/0.705 m/s
/// at coverage 0.79 (the speed now includes the scans it hid). With the thesis' 0.10 m patches
/// the car from the left read backwards (47.18°). The two checks of stop 44, a truck crossing
/// from the right and a car overtaking at 12 m/s: 36.71°/1.053 (coverage 0.95; 41.88°/1.059 at
/// 1.00 before a hypothesis that has just come into view went without an estimate, stop 45) and
/// 10.79°/4.536 m/s (coverage 1.00), plus the same margins. The cyclist, the crossing truck and
/// the overtaking car's speed are outside the 25° and 1.5 m/s bar, as at `bench`'s sizes
/// (docs/estimator.md). The three checks of stop 51, a van crossing from the left at 10 m/s, a car
/// turning right out of a side street and the car ahead braking hard: 27.49°/3.529, 65.51°/0.527
/// and 9.59°/2.747 m/s (coverage 0.95, 0.84, 1.00), plus the same margins. The five checks of
/// stop 53, an oncoming truck turning across the ego's path, a car crossing from the right in the
/// near lane, an oncoming cyclist, a van pulling out from the kerb and a van turning out of the
/// side street on the left: 9.09°/2.493, 58.46°/0.901, 28.06°/1.886, 59.01°/3.967 and
/// 34.85°/1.369 m/s (coverage 1.00, 0.68, 0.95, 1.00, 0.89), plus the same margins. The four
/// checks of stop 57, an oncoming midibus, an oncoming car while the ego turns right, the van
/// ahead turning left into a side street and a cyclist crossing from the right: 4.68°/0.493,
/// 4.17°/0.509, 73.42°/2.001 and 76.40°/1.544 m/s (coverage 1.00, 1.00, 1.00, 0.68), plus the
/// same margins.
const BOUNDS: [(f64, f64); 18] = [
    (22.5, 1.01),
    (24.5, 1.99),
    (61.5, 1.60),
    (37.5, 2.32),
    (51.7, 1.55),
    (25.8, 5.04),
    (42.5, 4.03),
    (80.6, 1.03),
    (24.6, 3.25),
    (24.1, 2.99),
    (73.5, 1.40),
    (43.1, 2.39),
    (74.0, 4.47),
    (49.9, 1.87),
    (19.7, 0.99),
    (19.2, 1.01),
    (88.4, 2.50),
    (91.4, 2.04),
];

/// GP-KF's bounds on the same model (the learned tracker, no moving decision, as in the per-target
/// tables), in [`UNSEEN`]'s order: measured 2026-12-05 (stop 51, an unsettled track reporting its
/// likeliest mode only where the mixture knows the heading within the 25° bar) at 7.12°/0.468,
/// 8.36°/0.964, 21.07°/1.203, 7.78°/1.194, 4.62°/0.911, 4.75°/2.644, 15.29°/1.971, 22.16°/0.804 and
/// 3.98°/2.517 m/s (coverage 0.47, 0.95, 0.89, 0.95, 0.74, 0.95, 0.89, 0.47, 0.95), plus 15° and
/// 0.5 m/s. Reporting from a track's first GP reading (stop 50): 7.12°/0.468, 8.15°/0.994,
/// 21.07°/1.203, 7.60°/1.181, 4.62°/0.911 and 5.88°/2.780 for the first six; reporting settled
/// tracks only (stop 49): 6.46°/0.455, 8.55°/0.928, 16.29°/1.124, 8.00°/1.216, 3.21°/0.945 and
/// 3.76°/2.492; on centroids alone (stop 44) the crossing truck read 1.46°/2.795 m/s: it comes out
/// from behind a parked car, its centroid at half its speed. Stop 52's rule (a track reports only
/// once a learned reading has agreed with it) leaves these nine values as they were (re-measured).
/// Stop 53's (a track reports only where it states its speed within 0.75 m/s) reads them at
/// 6.46°/0.455, 8.55°/0.928, 18.01°/1.087, 8.00°/1.216, 3.21°/0.945, 3.76°/2.492, 8.29°/1.823,
/// 21.93°/0.678 and 1.47°/2.387 m/s, the bounds kept; its five checks at 2.31°/1.442,
/// 16.15°/1.352, 4.33°/1.044, 53.25°/2.432 and 5.74°/1.234 m/s (coverage 0.89, 0.21, 0.89, 0.79,
/// 0.74), plus the same margins. At `bench`'s sizes GP-KF reads the first nine within the 25° and
/// 1.5 m/s bar on the worlds of `--seed 7`, 8 and 9 with each of the three models
/// (docs/estimator.md, "Stop 53"). Stop 57's four checks: 3.46°/0.368, 2.93°/0.549, 9.77°/1.325
/// and 9.12°/0.377 m/s (coverage 0.89, 0.89, 0.89, 0.42), plus the same margins. Stop 58's box
/// (a moving object in view measured by the centre of a box aligned with its heading) and fading
/// error (the GP's persistent error forgotten as the object's motion changes) read the eighteen
/// at 6.48°/0.464, 5.29°/1.019, 19.70°/0.998, 8.13°/1.249, 2.58°/0.528, 3.39°/2.897,
/// 10.21°/2.235, 25.94°/0.627, 2.18°/2.297, 3.04°/1.603, 5.76°/0.859, 7.70°/1.314, 59.31°/2.864,
/// 4.27°/1.198, 3.50°/0.390, 2.88°/0.455, 5.43°/1.479 and 13.11°/0.415 m/s, the bounds kept (at
/// these sizes the van pulling out comes within 0.07 m/s of its bound).
const GP_KF_BOUNDS: [(f64, f64); 18] = [
    (22.1, 0.97),
    (23.4, 1.47),
    (36.1, 1.70),
    (22.8, 1.70),
    (19.6, 1.41),
    (19.8, 3.15),
    (30.3, 2.48),
    (37.2, 1.31),
    (19.0, 3.02),
    (17.3, 1.94),
    (31.2, 1.85),
    (19.3, 1.54),
    (68.3, 2.93),
    (20.7, 1.73),
    (18.5, 0.87),
    (17.9, 1.05),
    (24.8, 1.83),
    (24.1, 0.88),
];

/// `name.toml` from `scenarios/` with 20 sweeps from `start_secs`, written into `dir`.
fn shortened(dir: &Path, name: &str, start_secs: f64) -> ScenarioSource {
    let file = patchflow_tests::workspace_root()
        .join("scenarios")
        .join(format!("{name}.toml"));
    let text = std::fs::read_to_string(&file).unwrap();
    let mut out = String::new();
    for line in text.lines() {
        if line.starts_with("sweeps =") {
            out.push_str(&format!("sweeps = 20\nstart_secs = {start_secs:?}\n"));
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, out).unwrap();
    ScenarioSource::File(path)
}

fn generate(dir: &Path, scenes: &[(&str, f64)]) -> Dataset {
    std::fs::create_dir_all(dir).unwrap();
    let sources: Vec<ScenarioSource> = scenes
        .iter()
        .map(|&(name, start)| shortened(dir, name, start))
        .collect();
    let options = GenerateOptions {
        out: dir.join("data"),
        seed: 7,
        shard: Shard::ALL,
        realism: None,
        overwrite: false,
    };
    patchflow_sim::generate_dataset(&sources, &options, &|_| {}).unwrap();
    Dataset::open(&dir.join("data")).unwrap()
}

#[test]
fn unseen_errors_stay_within_their_recorded_bounds() {
    let dir = tempfile::tempdir().unwrap();
    let train = generate(&dir.path().join("train"), &TRAINING);
    let unseen = generate(&dir.path().join("unseen"), &UNSEEN);
    let params = EstimatorParams {
        samples: 400,
        pseudo_inputs: 20,
        max_iters: 60,
        seed: 7,
        ..EstimatorParams::default()
    };
    let model = MotionEstimator::train(&train, &params).unwrap();
    // The per-target protocol with the baselines and the learned trackers (no moving decision).
    let report =
        evaluate_targets_with_baselines(&unseen, &[model], &BaselineParams::default(), None)
            .unwrap();
    let mut failures = Vec::new();
    for (method, bounds) in [(Method::SpgpHetAll, BOUNDS), (Method::GpKf, GP_KF_BOUNDS)] {
        for ((name, _), bound) in UNSEEN.iter().zip(bounds) {
            let situation = report.situations.iter().find(|s| s.name == *name).unwrap();
            let estimates = situation.methods.get(&method).unwrap();
            let m = score_method(&situation.truth, estimates).unwrap();
            let heading = m.heading_rmse_deg.unwrap_or(f64::INFINITY);
            let speed = m.speed_rmse_mps.unwrap_or(f64::INFINITY);
            println!(
                "{name} {method}: heading RMSE {heading:.2} deg, speed RMSE {speed:.3} m/s, coverage {:.2}",
                m.coverage
            );
            if heading > bound.0 || speed > bound.1 {
                failures.push(format!(
                    "{name} {method}: {heading:.2} deg / {speed:.3} m/s > {bound:?}"
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}
