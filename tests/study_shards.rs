//! A study sharded into two halves and merged writes the same `study.json` bytes as the study
//! run whole (issue #10), on a tiny scene: two rates, each trained and evaluated on its own data;
//! and two patch-map cell sizes, each sampled, trained and evaluated on its own features of the
//! same sweeps.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use patchflow_eval::{StudyFactor, StudyPlan, merge_study, run_study};
use patchflow_learn::GpKind;
use patchflow_sim::{ScenarioSource, Shard};

fn tiny_plan(dir: &std::path::Path, factor: StudyFactor) -> StudyPlan {
    let scenario = |name: &str| {
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, patchflow_tests::TRAFFIC_SCENE).unwrap();
        ScenarioSource::File(path)
    };
    let points = match factor {
        // 5 and 10 Hz: the scene's 14 sweeps become 7 and 14.
        StudyFactor::Rate => StudyFactor::Rate.points()[..2].to_vec(),
        // 0.10 and 0.20 m cells: the default and the coarse one, on the same sweeps.
        _ => factor.points()[1..].to_vec(),
    };
    StudyPlan {
        factor,
        points,
        training: vec![scenario("track")],
        training_sweep_share: 1.0,
        situations: vec![scenario("tiny")],
        gps: vec![GpKind::Spgp],
        samples: 120,
        pseudo_inputs: 6,
        max_iters: 8,
        seed: 5,
    }
}

/// Runs `plan` whole and in two shards merged afterwards; asserts equal `study.json` bytes and
/// PNG plots, and returns the study.
fn whole_equals_sharded(plan: &StudyPlan, dir: &std::path::Path) -> serde_json::Value {
    let whole = dir.join("whole");
    let files = run_study(plan, &whole, Shard::ALL, &|_| {})
        .unwrap()
        .unwrap();

    let sharded = dir.join("sharded");
    for index in 0..2 {
        let shard = Shard { index, count: 2 };
        assert!(run_study(plan, &sharded, shard, &|_| {}).unwrap().is_none());
    }
    let merged = merge_study(plan, &sharded).unwrap();

    let a = std::fs::read(&files.study_json).unwrap();
    let b = std::fs::read(&merged.study_json).unwrap();
    assert!(a == b, "study.json differs between whole and sharded runs");
    for plot in &merged.plots {
        let bytes = std::fs::read(plot).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{}", plot.display());
    }
    serde_json::from_slice(&a).unwrap()
}

#[test]
fn a_rate_study_sharded_in_two_and_merged_writes_the_bytes_of_the_whole_study() {
    let dir = tempfile::tempdir().unwrap();
    let plan = tiny_plan(dir.path(), StudyFactor::Rate);
    let study = whole_equals_sharded(&plan, dir.path());
    let points = study["points"].as_array().unwrap();
    assert_eq!(points.len(), 2);
    assert_eq!(points[0]["label"], "5 Hz");
    // Each rate's own data: half the scans at half the rate.
    let scans = |p: &serde_json::Value| p["pooled"]["KF"]["scans"].as_u64().unwrap();
    assert!(scans(&points[0]) < scans(&points[1]), "{study}");
    assert!(
        points[1]["pooled"]["SPGP-ALL"]["coverage"]
            .as_f64()
            .unwrap()
            > 0.0
    );
    // ZERO-FLOW is scored in the scene flow, where it moves nothing.
    let zero = &points[1]["scene_flow"]["ZERO-FLOW"];
    assert!(zero["points"].as_u64().unwrap() > 0, "{study}");
    assert!(zero["epe_fg_dynamic_m"].as_f64().unwrap() > 0.0, "{study}");
}

#[test]
fn a_cell_study_sharded_in_two_and_merged_writes_the_bytes_of_the_whole_study() {
    let dir = tempfile::tempdir().unwrap();
    let plan = tiny_plan(dir.path(), StudyFactor::Cell);
    let study = whole_equals_sharded(&plan, dir.path());
    let points = study["points"].as_array().unwrap();
    assert_eq!(points.len(), 2);
    assert_eq!(points[1]["label"], "0.20 m");
    assert_eq!(points[1]["train"], "0.2m");
    // One set of sweeps for both points (the cell is a feature parameter, not a sensor one) ...
    let data: Vec<_> = std::fs::read_dir(dir.path().join("whole/data"))
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(data, ["default"]);
    // ... but each point's own features: the GP estimates differ.
    let heading = |p: &serde_json::Value| p["pooled"]["SPGP-ALL"]["heading_rmse_deg"].clone();
    assert_ne!(heading(&points[0]), heading(&points[1]), "{study}");
}

#[test]
fn merging_before_every_shard_has_run_names_the_missing_point() {
    let dir = tempfile::tempdir().unwrap();
    let plan = tiny_plan(dir.path(), StudyFactor::Rate);
    let err = merge_study(&plan, &dir.path().join("empty")).unwrap_err();
    assert!(err.to_string().contains("points/000.json"), "{err}");
}

#[test]
fn merging_points_run_with_another_plan_is_refused_naming_the_difference() {
    let dir = tempfile::tempdir().unwrap();
    let mut plan = tiny_plan(dir.path(), StudyFactor::Rate);
    plan.points.truncate(1);
    let out = dir.path().join("quick");
    run_study(&plan, &out, Shard { index: 0, count: 2 }, &|_| {}).unwrap();
    // The merge's own flags say more samples than the shard ran with (a quick study merged
    // without `--quick`): refused, naming the file and both values.
    let mut other = plan.clone();
    other.samples += 1;
    let err = merge_study(&other, &out).unwrap_err().to_string();
    assert!(err.contains("points/000.json"), "{err}");
    assert!(
        err.contains("samples: points have 120, this plan 121"),
        "{err}"
    );
    // Merged with the plan it ran with, it is accepted.
    merge_study(&plan, &out).unwrap();
}
