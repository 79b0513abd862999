//! A user's own scenario through `evaluate` and `show` (issue 15): the report describes the
//! scenario in its own words, shows its scene figures, keeps no thesis placeholders, and
//! `metrics.json` records the model files and their seeds; `show` draws the maps with keys and
//! the scene beside them.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

mod common;

use common::{assert_success, evaluate, generate_tiny, patchflow, train_small};

#[test]
fn evaluate_on_an_own_scenario_writes_its_figures_and_no_thesis_placeholders() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    assert_success(&generate_tiny(&data, 1));
    let model = dir.path().join("spgp.json");
    assert_success(&train_small(&data, &model));
    let out = dir.path().join("report");
    assert_success(&evaluate(&model, &data, &out));
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains("Scenario: test scene: a car crossing in front of a slow ego car."),
        "{md}"
    );
    for placeholder in ["Hess 2008", "layout of thesis", "cf. thesis"] {
        assert!(!md.contains(placeholder), "{placeholder} in {md}");
    }
    // The tables have our columns only (a method without estimates still shows its "–").
    assert!(
        md.contains("| Method | RMSE | ME | scored scans | coverage |\n|---|---|---|---|---|\n")
    );
    for figure in ["tiny_scene.png", "tiny_cloud.png", "summary_rmse.png"] {
        assert!(
            md.contains(&format!("plots/{figure}")),
            "{figure} not linked"
        );
        let bytes = std::fs::read(out.join("plots").join(figure)).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{figure}");
    }
    let metrics: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("metrics.json")).unwrap()).unwrap();
    assert_eq!(metrics["seeds"], serde_json::json!([0]), "{metrics}");
    assert_eq!(metrics["models"][0]["file"], model.to_str().unwrap());
    assert_eq!(metrics["models"][0]["gp"], "spgp");
    assert!(metrics["version"].is_string());
}

#[test]
fn show_draws_the_maps_the_scene_and_the_point_cloud_of_a_sweep_into_a_new_folder() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    assert_success(&generate_tiny(&data, 2));
    let out = dir.path().join("figures").join("sweep.png");
    assert_success(&patchflow(&[
        "show",
        "--data",
        data.to_str().unwrap(),
        "--scan",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]));
    for name in ["sweep.png", "sweep_scene.png", "sweep_cloud.png"] {
        let bytes = std::fs::read(dir.path().join("figures").join(name)).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{name}");
    }
}
