//! A study sharded into two halves and merged writes the same `study.json` bytes as the study
//! run whole (issue #10), on a tiny scene: two rates, each trained and evaluated on its own data.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use patchflow_eval::{StudyFactor, StudyPlan, merge_study, run_study};
use patchflow_learn::GpKind;
use patchflow_sim::{ScenarioSource, Shard};

fn tiny_plan(dir: &std::path::Path) -> StudyPlan {
    let scenario = |name: &str| {
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, patchflow_tests::TRAFFIC_SCENE).unwrap();
        ScenarioSource::File(path)
    };
    let mut points = StudyFactor::Rate.points();
    points.truncate(2); // 5 and 10 Hz: the scene's 14 sweeps become 7 and 14
    StudyPlan {
        factor: StudyFactor::Rate,
        points,
        training: vec![scenario("track")],
        situations: vec![scenario("tiny")],
        gps: vec![GpKind::Spgp],
        samples: 120,
        pseudo_inputs: 6,
        max_iters: 8,
        seed: 5,
    }
}

#[test]
fn a_study_sharded_in_two_and_merged_writes_the_bytes_of_the_whole_study() {
    let dir = tempfile::tempdir().unwrap();
    let plan = tiny_plan(dir.path());
    let whole = dir.path().join("whole");
    let files = run_study(&plan, &whole, Shard::ALL, &|_| {})
        .unwrap()
        .unwrap();

    let sharded = dir.path().join("sharded");
    for index in 0..2 {
        let shard = Shard { index, count: 2 };
        assert!(
            run_study(&plan, &sharded, shard, &|_| {})
                .unwrap()
                .is_none()
        );
    }
    let merged = merge_study(&plan, &sharded).unwrap();

    let a = std::fs::read(&files.study_json).unwrap();
    let b = std::fs::read(&merged.study_json).unwrap();
    assert!(a == b, "study.json differs between whole and sharded runs");
    let study: serde_json::Value = serde_json::from_slice(&a).unwrap();
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
    for plot in &merged.plots {
        let bytes = std::fs::read(plot).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{}", plot.display());
    }
}

#[test]
fn merging_before_every_shard_has_run_names_the_missing_point() {
    let dir = tempfile::tempdir().unwrap();
    let plan = tiny_plan(dir.path());
    let err = merge_study(&plan, &dir.path().join("empty")).unwrap_err();
    assert!(err.to_string().contains("points/000.json"), "{err}");
}
