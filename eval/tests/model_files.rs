//! Estimator model files: identical `train` runs write identical bytes (no wall-clock time in
//! them), the GP kind written in a file cannot be edited to relabel one method as another, and a
//! feature setting that would need gigabytes of maps is refused with the estimate (issue 13).

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

mod common;

use std::path::Path;

use common::{assert_clean_failure, assert_success, evaluate, generate_tiny, train_small};

/// Loads `model`, applies `edit` to its JSON and writes it as `edited.json` beside it.
fn edited(model: &Path, edit: impl Fn(&mut serde_json::Value)) -> std::path::PathBuf {
    let mut value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(model).unwrap()).unwrap();
    edit(&mut value);
    let path = model.with_file_name("edited.json");
    std::fs::write(&path, serde_json::to_string(&value).unwrap()).unwrap();
    path
}

#[test]
fn training_twice_writes_byte_identical_models_that_edits_cannot_relabel_or_inflate() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    assert_success(&generate_tiny(&data, 0));
    let (a, b) = (dir.path().join("a.json"), dir.path().join("b.json"));
    assert_success(&train_small(&data, &a));
    assert_success(&train_small(&data, &b));
    assert!(
        std::fs::read(&a).unwrap() == std::fs::read(&b).unwrap(),
        "the two model files differ"
    );

    // One test, so the dataset and model are made once: relabelling an SPGP model as SPGP-HET.
    let relabelled = edited(&a, |v| v["gp"] = "spgp-het".into());
    assert_clean_failure(
        &evaluate(&relabelled, &data, &dir.path().join("r1")),
        &["edited.json", "gp spgp-het", "GP is spgp"],
    );

    // A cell size under the old cap that asked for 6 GB of maps.
    let fine = edited(&a, |v| v["features"]["cell_m"] = 0.011.into());
    assert_clean_failure(
        &evaluate(&fine, &data, &dir.path().join("r2")),
        &["edited.json", "7273 × 7273 cells", "GB per sweep pair"],
    );
}
