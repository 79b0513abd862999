//! Edited scenario files through the loader (a valid, re-loadable scenario or a `file:line`
//! error), and through a short `generate` whose output must read back.

use std::cell::Cell;

use patchflow_dataset::Dataset;
use patchflow_sim::{GenerateOptions, Scenario, ScenarioSource, Shard, SimError, generate_dataset};
use proptest::prelude::*;
use proptest::sample::select;

use crate::mutate::{apply, edits};
use crate::{cases, report, runner};

/// A small scene that uses every table: the realism rung and its knobs, lidar, ego, an actor
/// with corners and speed changes, structures (a row among them), a road and random traffic.
const SCENE: &str = r#"
sweeps = 2
start_secs = 1.0
ground_reflectivity = 0.2
realism = "urban"

[world]
camber = 0.02
clutter = 1.0
parked_cars_per_100m = 12.0
terrain_relief_m = 0.4

[sensor]
detection_range_m = 140.0
mixed_pixels = 0.5

[pose_error]
position_std_m = 0.3
drift_secs = 30.0

[[roads]]
path_m = [[-50.0, 1.75], [80.0, 1.75]]

[lidar]
channels = 4
azimuth_steps = 32
blocks = 4
rate_hz = 10.0
max_range_m = 80.0
range_noise_std_m = 0.02
dropout_probability = 0.1

[ego]
path_m = [[0.0, 0.0], [30.0, 0.0]]
speed_mps = 3.0

[[actors]]
name = "car"
class = "car"
target = true
path_m = [[10.0, -8.0], [10.0, 20.0], [30.0, 20.0]]
turn_radius_m = 6.0
speed_mps = 6.0
initial_speed_mps = 2.0
speed_changes = [[1.5, 4.0]]

[[actors]]
name = "walker"
class = "pedestrian"
path_m = [[5.0, 4.0], [9.0, 4.0]]
speed_mps = 1.2

[[structures]]
kind = "wall"
centre_m = [25.0, 0.0]
size_m = [0.5, 4.0, 2.0]
repeat_to_m = [25.0, 30.0]
spacing_m = 5.0

[[structures]]
kind = "parked_car"
centre_m = [8.0, -4.0]
yaw_deg = 10.0

[traffic]
random_cars = 1
random_pedestrians = 1
grid_spacing_m = 60.0
extent_m = 60.0
car_speed_mps = [2.0, 6.0]
"#;

/// The scenario files to edit: the scene above and two shipped ones.
fn bases() -> Vec<String> {
    let root = patchflow_tests::workspace_root().join("scenarios");
    let shipped =
        ["tiny.toml", "situation1.toml"].map(|f| std::fs::read_to_string(root.join(f)).unwrap());
    std::iter::once(SCENE.to_owned()).chain(shipped).collect()
}

/// Loads edited text: `Ok` must re-load equal from its resolved text, `Err` must be a scenario
/// error naming the file and a line of it.
fn load(text: &str) -> Result<Scenario, TestCaseError> {
    match Scenario::from_toml(text, "fuzz.toml", "fuzz") {
        Ok(scenario) => {
            let again = Scenario::from_toml(&scenario.to_toml(), "resolved.toml", "x");
            prop_assert_eq!(
                again.as_ref().ok(),
                Some(&scenario),
                "{:?}",
                again.as_ref().err()
            );
            Ok(scenario)
        }
        Err(SimError::Scenario { file, line, reason }) => {
            prop_assert_eq!(file, "fuzz.toml");
            prop_assert!(line >= 1 && line <= text.lines().count() + 1, "line {line}");
            prop_assert!(!reason.is_empty());
            Err(TestCaseError::reject("refused"))
        }
        Err(other) => Err(TestCaseError::fail(format!(
            "not a scenario error: {other}"
        ))),
    }
}

#[test]
fn edited_scenario_files_load_or_are_refused_with_file_and_line() {
    let n = cases(10_000);
    let bases = bases();
    let accepted = Cell::new(0u32);
    let strategy = (select(bases), edits());
    runner(n)
        .run(&strategy, |(base, edits)| {
            let text = String::from_utf8_lossy(&apply(base.as_bytes(), &edits)).into_owned();
            match load(&text) {
                Ok(_) => accepted.set(accepted.get() + 1),
                Err(TestCaseError::Reject(_)) => {}
                Err(fail) => return Err(fail),
            }
            Ok(())
        })
        .unwrap();
    report(
        "scenario loader",
        n,
        &format!(", {} of them valid scenarios", accepted.get()),
    );
}

/// True if the scenario is small enough to generate in a fuzz case.
fn cheap(s: &Scenario) -> bool {
    let rays = u64::from(s.lidar.channels) * u64::from(s.lidar.azimuth_steps);
    let random = s.traffic.random_cars + s.traffic.random_pedestrians;
    let boxes: usize = s.structures.iter().map(|st| st.centres_m().len()).sum();
    rays * u64::from(s.sweeps) <= 20_000 && s.actors.len() + random as usize <= 20 && boxes <= 200
}

#[test]
fn edited_scenarios_generate_data_that_reads_back_or_a_clear_error() {
    let n = cases(10_000) / 5;
    // Every error of a case names the scenario file or the output folder: both hold "fuzz".
    let dir = tempfile::Builder::new().prefix("fuzz").tempdir().unwrap();
    let out = dir.path().join("data");
    let scenario_file = dir.path().join("fuzz.toml");
    let generated = Cell::new(0u32);
    runner(n)
        .run(&edits(), |edits| {
            let text = apply(SCENE.as_bytes(), &edits);
            let scenario = match load(&String::from_utf8_lossy(&text)) {
                Ok(scenario) => scenario,
                Err(TestCaseError::Reject(_)) => return Ok(()),
                Err(fail) => return Err(fail),
            };
            if !cheap(&scenario) {
                return Ok(());
            }
            std::fs::write(&scenario_file, &text).unwrap();
            let options = GenerateOptions {
                out: out.clone(),
                seed: 1,
                shard: Shard::ALL,
                realism: None,
                overwrite: true,
            };
            let source = [ScenarioSource::File(scenario_file.clone())];
            match generate_dataset(&source, &options, &|_| {}) {
                Ok(_) => {
                    generated.set(generated.get() + 1);
                    let dataset =
                        Dataset::open(&out).map_err(|e| TestCaseError::fail(e.to_string()))?;
                    for info in dataset.sequences() {
                        let seq = dataset
                            .sequence(&info.name)
                            .map_err(|e| TestCaseError::fail(e.to_string()))?;
                        for i in 0..seq.len() {
                            seq.read_sweep(i)
                                .map_err(|e| TestCaseError::fail(e.to_string()))?;
                        }
                    }
                }
                Err(e) => {
                    let message = e.to_string();
                    prop_assert!(message.contains("fuzz"), "unclear error: {message}");
                }
            }
            Ok(())
        })
        .unwrap();
    let generated = generated.get();
    report(
        "short generate",
        n,
        &format!(", {generated} of them generated and read back"),
    );
    assert!(
        generated > n / 10,
        "only {generated} of {n} cases generated"
    );
}
