//! End to end on a small scene: generate → train SPGP and SPGP-HET → evaluate → report. Checks
//! that every stage hands the next what it needs and that metrics.json has the SPEC §7 shape.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use patchflow_eval::{BaselineParams, evaluate_dataset, write_report};
use patchflow_learn::{
    EstimatorParams, FeatureKind, FeatureParams, GpKind, MotionEstimator, SampleSet,
};

#[test]
fn a_small_scene_goes_through_generate_train_evaluate_and_report() {
    let dir = tempfile::tempdir().unwrap();
    let dataset =
        patchflow_tests::generate_scene(dir.path(), "e2e", patchflow_tests::TRAFFIC_SCENE, 3);

    let features = FeatureParams {
        half_extent_m: 30.0,
        ..FeatureParams::default()
    };
    let set = SampleSet::collect(&dataset, &features, FeatureKind::Patch, 200, 1).unwrap();
    assert!(
        set.samples.len() >= 100,
        "only {} samples",
        set.samples.len()
    );
    let estimators: Vec<MotionEstimator> = [GpKind::Spgp, GpKind::SpgpHet]
        .iter()
        .map(|&gp| {
            let params = EstimatorParams {
                gp,
                features: features.clone(),
                samples: 200,
                pseudo_inputs: 10,
                max_iters: 25,
                seed: 1,
                ..EstimatorParams::default()
            };
            MotionEstimator::fit_samples(&set, &params).unwrap()
        })
        .collect();
    let report =
        evaluate_dataset(&dataset, &estimators, &BaselineParams::default(), &|| {}).unwrap();
    let timing = &report.scenes[0].timing;
    assert!(
        timing
            .iter()
            .all(|t| t.maps_secs > 0.0 && t.estimators.len() == 2)
    );
    assert!(timing.iter().any(|t| t.target_points > 0));
    let out = dir.path().join("report");
    let files = write_report(&report, &out).unwrap();

    let metrics: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&files.metrics_json).unwrap()).unwrap();
    let situation = &metrics["situations"]["e2e"];
    assert_eq!(situation["scans"], 13, "{metrics}");
    let methods = situation["methods"].as_object().unwrap();
    let names: Vec<&str> = methods.keys().map(String::as_str).collect();
    // The eight methods of SPEC §6.
    for name in patchflow_eval::CANONICAL_METHODS.map(|m| m.name()) {
        assert!(names.contains(&name), "{name} missing from {names:?}");
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
    for plot in &files.plots {
        let bytes = std::fs::read(plot).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{}", plot.display());
    }
    assert!(
        std::fs::read_to_string(&files.report_md)
            .unwrap()
            .contains("e2e")
    );
}
