//! End to end on a small scene, through the same library driver as `patchflow bench`: generate →
//! sample → train SPGP and SPGP-HET → cross-validate → evaluate → report. Checks that every stage
//! hands the next what it needs, that metrics.json has the SPEC §7 shape, and that the whole-scene
//! evaluation scores every method (zero flow included) on every point and every moving actor.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use patchflow_eval::{BenchPlan, CvParams, run_bench};
use patchflow_learn::GpKind;
use patchflow_sim::ScenarioSource;

#[test]
fn a_small_bench_goes_through_generate_train_cv_evaluate_and_report() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = |name: &str| {
        let path = dir.path().join(format!("{name}.toml"));
        std::fs::write(&path, patchflow_tests::TRAFFIC_SCENE).unwrap();
        ScenarioSource::File(path)
    };
    let plan = BenchPlan {
        training: vec![scenario("track")],
        situations: vec![scenario("e2e")],
        occupancy: Vec::new(),
        occupancy_params: Default::default(),
        ahead_params: Default::default(),
        gps: vec![GpKind::Spgp, GpKind::SpgpHet],
        estimator: Default::default(),
        thesis_preset: true,
        samples: 200,
        pseudo_inputs: 10,
        max_iters: 25,
        cv: CvParams {
            folds: 2,
            samples: 120,
            pseudo_inputs: 6,
            max_iters: 8,
            seed: 1,
            ..CvParams::default()
        },
        seed: 3,
        seeds: 2,
        training_sweep_share: 1.0,
        keep_data: false,
        quick: true,
        realism_situations: Vec::new(),
        realism_rungs: Vec::new(),
    };
    let out = dir.path().join("bench");
    let stages = std::sync::Mutex::new(Vec::new());
    let outcome = run_bench(&plan, &out, &|t| {
        stages.lock().unwrap().push(t.stage.clone())
    })
    .unwrap();
    // The six stages of one seed (training fits every seed), the moving classifier (issue 27),
    // the second seed's targets, the figures, and the realism study (the situations at every
    // rung, issue #10).
    assert_eq!(stages.lock().unwrap().len(), 10);
    assert!(
        !out.join("data").exists(),
        "the datasets are deleted once used without keep_data"
    );
    let files = &outcome.files;
    for file in [
        "cv.json",
        "cv.md",
        "models/spgp.json",
        "models/spgp-het.json",
        "models/spgp-seed4.json",
        "models/spgp-het-seed4.json",
        "realism/study.json",
        "realism/plots/study_realism_heading.png",
    ] {
        assert!(out.join(file).exists(), "{file} missing");
    }

    let metrics: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&files.metrics_json).unwrap()).unwrap();
    // What produced the numbers, and their spread over the two training seeds.
    assert_eq!(metrics["seeds"], serde_json::json!([3, 4]));
    assert_eq!(metrics["model_files"].as_array().unwrap().len(), 4);
    let spread = &metrics["seed_spread"]["situations"]["e2e"]["SPGP-HET-ALL"];
    let values = spread["heading_rmse_deg"]["values"].as_array().unwrap();
    assert_eq!(values.len(), 2);
    assert!(spread["heading_rmse_deg"]["std"].as_f64().unwrap() >= 0.0);
    let situation = &metrics["situations"]["e2e"];
    // The first seed's spread entry is the main table's figure.
    assert_eq!(
        values[0],
        situation["methods"]["SPGP-HET-ALL"]["heading_rmse_deg"]
    );
    assert_eq!(situation["scans"], 13, "{metrics}");
    let methods = situation["methods"].as_object().unwrap();
    // The eight methods of SPEC §6 with their per-target scores.
    for name in patchflow_eval::CANONICAL_METHODS.map(|m| m.name()) {
        let m = &methods[name];
        for key in [
            "heading_rmse_deg",
            "heading_me_deg",
            "speed_rmse_mps",
            "speed_me_mps",
            "coverage",
            "epe_mps",
        ] {
            assert!(m.get(key).is_some(), "{name} lacks {key}");
        }
    }
    // The target is in view all along, so the GP methods estimate at (nearly) every scan.
    let coverage = methods["SPGP-HET-ALL"]["coverage"].as_f64().unwrap();
    assert!(coverage >= 0.8, "coverage {coverage}");
    assert!(
        methods["SPGP-HET-ALL"]["heading_rmse_deg"]
            .as_f64()
            .unwrap()
            .is_finite()
    );
    // Scene flow of every method, zero flow included, on the same points.
    let zero = &methods["ZERO-FLOW"]["scene_flow"];
    assert_eq!(zero["normalised_dynamic_epe"], 1.0);
    let points = zero["points"].as_u64().unwrap();
    assert!(points > 1000);
    // The thesis preset's row is scored on the target alone (its models do not run on the
    // whole scene), beside the default's.
    let thesis = &methods["SPGP-HET-ALL (thesis)"];
    assert!(thesis["heading_rmse_deg"].as_f64().unwrap().is_finite());
    assert!(thesis.get("scene_flow").is_none());
    for (name, m) in methods {
        if name == "SPGP-HET-ALL (thesis)" {
            continue;
        }
        let flow = &m["scene_flow"];
        assert_eq!(flow["points"].as_u64(), Some(points), "{name}");
        assert!(flow["epe3d_m"].as_f64().unwrap().is_finite(), "{name}");
    }
    assert!(methods["SPGP-HET-POINT"].get("coverage").is_none());
    // The three cars of the scene are scored as moving objects, not only the target.
    let object_scans = situation["objects"]["KF-AUTO"]["object_scans"]
        .as_u64()
        .unwrap();
    assert!(object_scans > 13, "{object_scans} object scans");
    assert!(metrics["objects"]["by_class"]["car"].is_object());
    // Plots (the scene figures too), perception and the report.
    for figure in ["e2e_scene.png", "e2e_cloud.png", "summary_rmse.png"] {
        assert!(out.join("plots").join(figure).exists(), "{figure}");
        assert!(md_links(&files.report_md, figure), "{figure} not linked");
    }
    for plot in &files.plots {
        let bytes = std::fs::read(plot).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{}", plot.display());
    }
    assert_eq!(files.plots.len(), 5);
    let all = outcome.perception.last().unwrap();
    assert_eq!(
        (all.name.as_str(), all.scans, all.estimators),
        ("all", 13, 2)
    );
    let md = std::fs::read_to_string(&files.report_md).unwrap();
    for needle in [
        "## e2e (13 scans)",
        "### Scene flow",
        "## Perception per scan",
        "## Spread over training seeds",
        "## Realism study",
        "## Synthetic to real",
    ] {
        assert!(md.contains(needle), "{needle}");
    }
}

fn md_links(report_md: &std::path::Path, figure: &str) -> bool {
    std::fs::read_to_string(report_md)
        .unwrap()
        .contains(&format!("(plots/{figure})"))
}
