//! The two presets as `train`, `features` and `cv` take them: the thesis' protocol exactly beside
//! the default (issue 24); `features` writes the very samples each preset's `train` draws, and `cv`
//! cross-validates that training set.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

mod common;

use common::{assert_success, generate_file, patchflow, tiny_scenario, train_small_with};

#[test]
fn thesis_training_writes_a_model_without_mirror_images_or_speed_alignment_errors() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    assert_success(&generate_file(&tiny_scenario(), &data));
    let model_of = |name: &str, extra: &[&str]| {
        let model = dir.path().join(name);
        assert_success(&train_small_with(&data, &model, extra));
        let text = std::fs::read_to_string(&model).unwrap();
        serde_json::from_str::<serde_json::Value>(&text).unwrap()
    };
    let thesis = model_of("thesis.json", &["--preset", "thesis"]);
    assert_eq!(thesis["training"]["mirror_images"], false);
    assert_eq!(thesis["training"]["zero_mean"], true);
    assert_eq!(thesis["training"]["most_likely_noise"], false);
    assert_eq!(thesis["features"]["speed_jitter_deg"], 0.0);
    let default = model_of("default.json", &[]);
    assert_eq!(default["training"]["mirror_images"], true);
    assert_eq!(default["training"]["most_likely_noise"], true);
    assert_eq!(default["features"]["speed_jitter_deg"], 25.0);
}

#[test]
fn features_writes_the_features_each_preset_trains_on() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    assert_success(&generate_file(&tiny_scenario(), &data));
    let dataset = patchflow_dataset::Dataset::open(&data).unwrap();
    for (preset, params) in [
        ("default", patchflow_learn::EstimatorParams::default()),
        ("thesis", patchflow_learn::EstimatorParams::thesis()),
    ] {
        let csv = dir.path().join(format!("{preset}.csv"));
        let written = patchflow(&[
            "features",
            "--data",
            data.to_str().unwrap(),
            "--out",
            csv.to_str().unwrap(),
            "--samples",
            "20",
            "--seed",
            "3",
            "--align",
            "heading",
            "--preset",
            preset,
        ]);
        assert_success(&written);
        let expected = patchflow_learn::SampleSet::collect(
            &dataset,
            &params.features,
            patchflow_learn::FeatureKind::Patch,
            20,
            3,
        )
        .unwrap()
        .to_csv(patchflow_learn::Alignment::Heading);
        assert_eq!(std::fs::read_to_string(&csv).unwrap(), expected, "{preset}");
    }
    let read = |name: &str| std::fs::read_to_string(dir.path().join(name)).unwrap();
    assert_ne!(read("default.csv"), read("thesis.csv"));
}

#[test]
fn cv_cross_validates_the_training_set_of_the_preset() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    assert_success(&generate_file(&tiny_scenario(), &data));
    let cv_json = |preset: &str| {
        let out = dir.path().join(preset);
        assert_success(&patchflow(&[
            "cv",
            "--data",
            data.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--folds",
            "2",
            "--preset",
            preset,
        ]));
        std::fs::read(out.join("cv.json")).unwrap()
    };
    // The default's: its features, its mirror images, the command's folds.
    let dataset = patchflow_dataset::Dataset::open(&data).unwrap();
    let params = patchflow_eval::CvParams {
        folds: 2,
        mirror_images: true,
        ..patchflow_eval::CvParams::default()
    };
    let features = patchflow_learn::EstimatorParams::default().features;
    let report = patchflow_eval::cross_validate(&dataset, &features, &params, &|_, _| {}).unwrap();
    let expected = dir.path().join("expected");
    patchflow_eval::write_cv_report(&report, &expected).unwrap();
    let default = cv_json("default");
    assert_eq!(default, std::fs::read(expected.join("cv.json")).unwrap());
    assert_ne!(default, cv_json("thesis"));
}
