//! `patchflow check` as a user runs it (issue 24's unseen targets): a scenario of one's own read
//! by a trained model on several world draws. Its readings are `evaluate`'s per-target figures
//! for the same world, a rerun writes the same bytes, the worlds' data go unless kept, and bad
//! input is refused naming what is wrong.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

mod common;

use std::path::{Path, PathBuf};

use common::{
    assert_clean_failure, assert_success, evaluate, generate_seeded, generate_tiny, patchflow,
    train_small,
};

/// `scenarios/tiny.toml` with 8 sweeps (GP-KF needs a few scans to report), written into `dir`.
fn eight_sweep_check(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(common::tiny_scenario())
        .unwrap()
        .replace("sweeps = 3", "sweeps = 8");
    let path = dir.join("crossing_check.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// A small SPGP model trained on the tiny scene (world 1).
fn model(dir: &Path) -> PathBuf {
    let data = dir.join("train");
    assert_success(&generate_tiny(&data, 1));
    let model = dir.join("spgp.json");
    assert_success(&train_small(&data, &model));
    model
}

fn check(scenario: &Path, model: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec![
        "check",
        scenario.to_str().unwrap(),
        "--model",
        model.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    patchflow(&args)
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn check_reads_each_world_as_evaluate_does_and_a_rerun_writes_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = eight_sweep_check(dir.path());
    let model = model(dir.path());
    let out = dir.path().join("checks");
    assert_success(&check(&scenario, &model, &out, &["--worlds", "3-4"]));
    let report = json(&out.join("checks.json"));
    // One check × two worlds × one model × four methods.
    let readings = report["readings"].as_array().unwrap();
    assert_eq!(readings.len(), 8, "{report}");
    assert_eq!(report["worlds"], serde_json::json!([3, 4]));
    assert!(!out.join("data").exists(), "the worlds' data were kept");
    // World 3's readings are what `evaluate` reports on the same world.
    let data = dir.path().join("world3");
    assert_success(&generate_seeded(&scenario, &data, 3));
    let evaluated = dir.path().join("evaluated");
    assert_success(&evaluate(&model, &data, &evaluated));
    let metrics = json(&evaluated.join("metrics.json"));
    // GP-KF reading an SPGP model is named after it in the check's tally.
    let methods = [
        ("SPGP-ALL", "SPGP-ALL"),
        ("GP-KF (SPGP-ALL)", "GP-KF"),
        ("KF-AUTO", "KF-AUTO"),
    ];
    for (method, in_evaluate) in methods {
        let reading = readings
            .iter()
            .find(|r| r["world"] == 3 && r["method"] == method)
            .unwrap();
        let scores = &metrics["situations"]["crossing_check"]["methods"][in_evaluate];
        for key in ["heading_rmse_deg", "speed_rmse_mps", "coverage"] {
            assert_eq!(
                reading[key], scores[key],
                "{method} {key}: {reading} {scores}"
            );
        }
    }
    let again = dir.path().join("again");
    assert_success(&check(&scenario, &model, &again, &["--worlds", "3-4"]));
    for file in ["checks.json", "checks.csv", "checks.md"] {
        let (a, b) = (out.join(file), again.join(file));
        assert_eq!(
            std::fs::read(a).unwrap(),
            std::fs::read(b).unwrap(),
            "{file}"
        );
    }
}

#[test]
fn keep_data_keeps_each_worlds_dataset() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = eight_sweep_check(dir.path());
    let model = model(dir.path());
    let out = dir.path().join("checks");
    assert_success(&check(
        &scenario,
        &model,
        &out,
        &["--worlds", "5", "--keep-data"],
    ));
    assert!(out.join("data/world-5/manifest.json").exists());
    let md = std::fs::read_to_string(out.join("checks.md")).unwrap();
    assert!(md.contains("| crossing_check | "), "{md}");
}

#[test]
fn a_scenario_without_a_target_is_refused_naming_its_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(common::tiny_scenario())
        .unwrap()
        .replace("target = true", "target = false");
    let scenario = dir.path().join("no_target.toml");
    std::fs::write(&scenario, text).unwrap();
    let model = dir.path().join("model.json");
    std::fs::write(&model, "{}").unwrap();
    let out = dir.path().join("checks");
    let output = check(&scenario, &model, &out, &["--worlds", "7"]);
    assert_clean_failure(&output, &["no_target.toml", "target"]);
}

#[test]
fn malformed_worlds_and_a_broken_model_file_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = common::tiny_scenario();
    let broken = dir.path().join("broken.json");
    std::fs::write(&broken, "{\"gp\": ").unwrap();
    let out = dir.path().join("checks");
    assert_clean_failure(
        &check(&scenario, &broken, &out, &["--worlds", "9-7"]),
        &["--worlds", "9-7"],
    );
    assert_clean_failure(&check(&scenario, &broken, &out, &[]), &["broken.json"]);
    assert!(!out.join("checks.json").exists());
}
