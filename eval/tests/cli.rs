//! The `patchflow` command as users and scripts call it (SPEC §7): bad input gives a message
//! naming the file (and line, for scenario files) and a non-zero exit, never a panic; `gp fit`
//! and `gp predict` work on a CSV.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use std::path::Path;
use std::process::{Command, Output};

fn patchflow(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_patchflow"))
        .args(args)
        .output()
        .unwrap()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

fn assert_clean_failure(output: &Output, must_mention: &[&str]) {
    let err = stderr(output);
    assert_eq!(
        output.status.code(),
        Some(1),
        "exit status {:?}, stderr: {err}",
        output.status
    );
    assert!(!err.contains("panicked"), "panic: {err}");
    for text in must_mention {
        assert!(err.contains(text), "stderr lacks {text:?}: {err}");
    }
}

#[test]
fn a_broken_scenario_file_is_rejected_with_its_name_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("broken.toml");
    std::fs::write(
        &scenario,
        "sweeps = 3\n\n[ego]\npath_m = [[0.0, 0.0]]\nspeed_mps = 5.0\n",
    )
    .unwrap();
    let out = dir.path().join("data");
    let output = patchflow(&[
        "generate",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_clean_failure(&output, &["broken.toml:4"]);
}

#[test]
fn an_unknown_scenario_field_is_rejected_with_its_name_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("typo.toml");
    std::fs::write(&scenario, "sweeps = 3\nsweep_rate = 10\n").unwrap();
    let output = patchflow(&[
        "generate",
        scenario.to_str().unwrap(),
        "--out",
        dir.path().join("d").to_str().unwrap(),
    ]);
    assert_clean_failure(&output, &["typo.toml:2"]);
}

#[test]
fn occupancy_on_a_dataset_of_an_older_build_names_the_missing_sensor_file() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    let generated = patchflow(&[
        "generate",
        "dgpom_tjunction",
        "--out",
        data.to_str().unwrap(),
    ]);
    assert!(generated.status.success(), "{}", stderr(&generated));
    std::fs::remove_file(data.join("sequences/dgpom_tjunction/sensor.json")).unwrap();
    let output = patchflow(&[
        "occupancy",
        "--data",
        data.to_str().unwrap(),
        "--out",
        dir.path().join("report").to_str().unwrap(),
    ]);
    assert_clean_failure(&output, &["sensor.json", "regenerate"]);
}

#[test]
fn a_corrupt_model_file_is_named_in_the_error() {
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("model.json");
    std::fs::write(
        &model,
        "{\"format\": \"patchflow-motion-model\", \"version\": 1, \"gp\": ",
    )
    .unwrap();
    let output = patchflow(&[
        "evaluate",
        "--model",
        model.to_str().unwrap(),
        "--data",
        dir.path().join("data").to_str().unwrap(),
        "--out",
        dir.path().join("r").to_str().unwrap(),
    ]);
    assert_clean_failure(&output, &["model.json"]);
}

#[test]
fn training_on_a_folder_without_a_dataset_names_the_folder() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("nothing-here");
    let output = patchflow(&[
        "train",
        "--data",
        missing.to_str().unwrap(),
        "--out",
        dir.path().join("m.json").to_str().unwrap(),
    ]);
    assert_clean_failure(&output, &["nothing-here"]);
}

fn write_csv(path: &Path) {
    let mut text = String::from("x0,x1,y\n");
    for i in 0..60 {
        let (a, b) = (i as f64 / 10.0, (i % 7) as f64 / 7.0);
        text.push_str(&format!("{a},{b},{}\n", a.sin() + 0.1 * b));
    }
    std::fs::write(path, text).unwrap();
}

#[test]
fn gp_fit_then_predict_works_on_a_csv() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("train.csv");
    write_csv(&csv);
    let model = dir.path().join("gp.json");
    let fit = patchflow(&[
        "gp",
        "fit",
        "--csv",
        csv.to_str().unwrap(),
        "--out",
        model.to_str().unwrap(),
        "--kind",
        "spgp-het",
        "--pseudo",
        "8",
        "--iters",
        "40",
    ]);
    assert!(fit.status.success(), "{}", stderr(&fit));
    let stdout = String::from_utf8_lossy(&fit.stdout);
    let summary: serde_json::Value = serde_json::from_str(stdout.lines().last().unwrap()).unwrap();
    for key in ["kind", "n", "d", "m", "evals", "seconds", "nlml"] {
        assert!(summary.get(key).is_some(), "{key} missing from {summary}");
    }
    assert_eq!(
        (
            summary["n"].as_u64(),
            summary["d"].as_u64(),
            summary["m"].as_u64()
        ),
        (Some(60), Some(2), Some(8))
    );

    let predictions = dir.path().join("pred.csv");
    let predict = patchflow(&[
        "gp",
        "predict",
        "--model",
        model.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
        "--out",
        predictions.to_str().unwrap(),
    ]);
    assert!(predict.status.success(), "{}", stderr(&predict));
    let text = std::fs::read_to_string(&predictions).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("mean,var,var_y"));
    assert_eq!(lines.count(), 60);
}

#[test]
fn a_gp_model_given_to_evaluate_is_refused_as_not_an_estimator() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("train.csv");
    write_csv(&csv);
    let model = dir.path().join("gp.json");
    assert!(
        patchflow(&[
            "gp",
            "fit",
            "--csv",
            csv.to_str().unwrap(),
            "--out",
            model.to_str().unwrap(),
            "--pseudo",
            "5",
            "--iters",
            "10"
        ])
        .status
        .success()
    );
    let output = patchflow(&[
        "evaluate",
        "--model",
        model.to_str().unwrap(),
        "--data",
        dir.path().join("data").to_str().unwrap(),
        "--out",
        dir.path().join("r").to_str().unwrap(),
    ]);
    assert_clean_failure(&output, &["gp.json", "not a patchflow motion model"]);
}

#[test]
fn no_command_writes_over_its_input() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("D");
    std::fs::create_dir_all(data.join("sequences")).unwrap();
    std::fs::write(data.join("manifest.json"), "{\"mine\": 1}").unwrap();
    let (d, manifest) = (data.to_str().unwrap(), data.join("manifest.json"));
    let m = manifest.to_str().unwrap();
    let model = dir.path().join("model.json");
    std::fs::write(&model, "{}").unwrap();
    let mo = model.to_str().unwrap();
    for args in [
        vec!["train", "--data", d, "--out", m],
        vec!["features", "--data", d, "--out", m],
        vec!["flow", "--data", d, "--model", mo, "--out", d],
        vec!["evaluate", "--data", d, "--model", mo, "--out", d],
        vec!["cv", "--data", d, "--out", d],
        vec!["occupancy", "--data", d, "--out", d],
        vec!["show", "--data", d, "--out", &format!("{d}/x.png")],
        vec!["gp", "predict", "--model", mo, "--csv", m, "--out", mo],
    ] {
        let output = patchflow(&args);
        assert_clean_failure(&output, &["--out", "the input"]);
    }
    assert_eq!(std::fs::read_to_string(&manifest).unwrap(), "{\"mine\": 1}");
    assert_eq!(std::fs::read_to_string(&model).unwrap(), "{}");
}

#[test]
fn an_out_that_is_an_existing_file_is_named_in_words() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("report");
    std::fs::write(&file, "x").unwrap();
    let output = patchflow(&[
        "cv",
        "--data",
        dir.path().join("data").to_str().unwrap(),
        "--out",
        file.to_str().unwrap(),
    ]);
    assert_clean_failure(&output, &["is an existing file, not a folder"]);
}

/// Exit 2 (clap's usage error), no panic, the refused value and every valid value named.
fn assert_refused_listing(output: &Output, refused: &str, valid: &[&str]) {
    let err = stderr(output);
    assert_eq!(output.status.code(), Some(2), "stderr: {err}");
    assert!(!err.contains("panicked"), "panic: {err}");
    assert!(err.contains("invalid value"), "{err}");
    assert!(err.contains(&format!("'{refused}'")), "{err}");
    assert!(err.contains("possible values"), "{err}");
    for value in valid {
        assert!(err.contains(value), "stderr lacks {value:?}: {err}");
    }
}

#[test]
fn a_misspelt_gp_kind_is_refused_with_the_valid_kinds() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("model.json");
    let output = patchflow(&[
        "train",
        "--data",
        dir.path().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--gp",
        "spgp-hte",
    ]);
    assert_refused_listing(&output, "spgp-hte", &["spgp", "spgp-het", "full"]);
    assert!(!out.exists());
}

#[test]
fn a_misspelt_feature_is_refused_with_the_valid_features() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("f.csv");
    let output = patchflow(&[
        "features",
        "--data",
        dir.path().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--feature",
        "gabour",
    ]);
    assert_refused_listing(&output, "gabour", &["patch", "gabor"]);
}

#[test]
fn a_misspelt_gp_fit_kind_is_refused_with_the_valid_kinds() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("train.csv");
    write_csv(&csv);
    let out = dir.path().join("gp.json");
    let output = patchflow(&[
        "gp",
        "fit",
        "--csv",
        csv.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--kind",
        "sparse",
    ]);
    assert_refused_listing(&output, "sparse", &["spgp", "spgp-het", "full"]);
}

#[test]
fn an_unknown_study_is_refused_with_the_known_studies() {
    let output = patchflow(&["study", "colour"]);
    assert_refused_listing(
        &output,
        "colour",
        &["realism", "rate", "channels", "cell", "cell-rate"],
    );
}

#[test]
fn the_help_opens_with_patchflows_own_description() {
    let output = patchflow(&["--help"]);
    assert!(output.status.success());
    let help = String::from_utf8_lossy(&output.stdout);
    let first = help.lines().next().unwrap_or_default();
    assert!(first.contains("lidar"), "first line: {first}");
    assert!(!first.contains("ICP and Kalman"), "first line: {first}");
}
