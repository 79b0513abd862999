//! Shared fixtures of patchflow's cross-crate tests. The tests themselves sit beside this folder,
//! one behaviour per file, declared as `[[test]]` targets in `tests/Cargo.toml`.

/// The workspace root, for tests that read `scenarios/`.
pub fn workspace_root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Writes `scenario_toml` as `<name>.toml` in `dir`, generates it with `seed` into `dir/data`,
/// and opens the dataset.
pub fn generate_scene(
    dir: &std::path::Path,
    name: &str,
    scenario_toml: &str,
    seed: u64,
) -> patchflow_dataset::Dataset {
    let scenario = dir.join(format!("{name}.toml"));
    std::fs::write(&scenario, scenario_toml).expect("writing the scenario file");
    let data = dir.join("data");
    let options = patchflow_sim::GenerateOptions {
        out: data.clone(),
        seed,
        shard: patchflow_sim::Shard::ALL,
        realism: None,
        overwrite: false,
    };
    patchflow_sim::generate_dataset(
        &[patchflow_sim::ScenarioSource::File(scenario)],
        &options,
        &|_| {},
    )
    .expect("generating the scene");
    patchflow_dataset::Dataset::open(&data).expect("opening the generated dataset")
}

/// Cars crossing, oncoming and leaving at three speeds, seen from a slowly moving ego car.
pub const TRAFFIC_SCENE: &str = r#"
description = "three cars around a slow ego car (test scene)"
sweeps = 14

[lidar]
channels = 32
azimuth_steps = 900
blocks = 36

[ego]
path_m = [[0.0, 0.0], [100.0, 0.0]]
speed_mps = 2.0

[[actors]]
name = "crossing"
target = true
path_m = [[14.0, -8.0], [14.0, 60.0]]
speed_mps = 8.0

[[actors]]
name = "oncoming"
path_m = [[40.0, 4.0], [-60.0, 4.0]]
speed_mps = 6.0

[[actors]]
name = "leaving"
path_m = [[8.0, -4.0], [120.0, -4.0]]
speed_mps = 4.0
"#;
