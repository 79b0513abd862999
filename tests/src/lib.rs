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
    };
    patchflow_sim::generate_dataset(
        &[patchflow_sim::ScenarioSource::File(scenario)],
        &options,
        &|_| {},
    )
    .expect("generating the scene");
    patchflow_dataset::Dataset::open(&data).expect("opening the generated dataset")
}
