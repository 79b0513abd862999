//! Edited estimator model files through the loader: a model that loads must estimate a
//! cluster (a value or an error, no panic); a refused one names the file.

use std::cell::Cell;

use patchflow_learn::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
use patchflow_learn::{
    EstimatorParams, FeatureKind, FeatureParams, GpKind, MotionEstimator, SweepFeatures,
};
use proptest::prelude::*;

use crate::mutate::{apply, edits};
use crate::{cases, report, runner};

/// A small trained model (Gabor features: 16 inputs, few pseudo-inputs, so the file is small)
/// and the features of a sweep pair with a moving car to estimate on.
fn model_and_features(root: &std::path::Path) -> (Vec<u8>, SweepFeatures, Vec<usize>) {
    let dataset =
        patchflow_tests::generate_scene(root, "traffic", patchflow_tests::TRAFFIC_SCENE, 3);
    let params = EstimatorParams {
        gp: GpKind::SpgpHet,
        feature: FeatureKind::Gabor,
        samples: 40,
        pseudo_inputs: 4,
        max_iters: 10,
        ..EstimatorParams::default()
    };
    let estimator = MotionEstimator::train(&dataset, &params).unwrap();
    let path = root.join("model.json");
    estimator.save(&path).unwrap();
    let lidar = SyntheticLidar::with_resolution(16, 600);
    let scene = SyntheticScene {
        boxes: vec![SceneBox::car(1, [10.0, 2.0], 0.5, 6.0)],
    };
    let prev = scene.scan(&lidar, [0.0, 0.0], 0.0, 0);
    let curr = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
    let features = SweepFeatures::compute(&prev, &curr, &FeatureParams::default()).unwrap();
    let biggest = (0..features.clusters().len())
        .max_by_key(|&c| features.clusters().members(c).len())
        .unwrap();
    let members = features.clusters().members(biggest).to_vec();
    (std::fs::read(&path).unwrap(), features, members)
}

#[test]
fn edited_model_files_load_and_estimate_or_are_refused_naming_the_file() {
    let n = cases(10_000);
    let dir = tempfile::tempdir().unwrap();
    let (original, features, members) = model_and_features(dir.path());
    let path = dir.path().join("edited-model.json");
    let loaded = Cell::new(0u32);
    runner(n)
        .run(&edits(), |edits| {
            std::fs::write(&path, apply(&original, &edits)).unwrap();
            match MotionEstimator::load(&path) {
                Ok(estimator) => {
                    loaded.set(loaded.get() + 1);
                    // A value or an error, never a panic.
                    let _ = estimator.estimate_cluster(&features, &members);
                }
                Err(e) => {
                    let message = e.to_string();
                    prop_assert!(
                        message.contains("edited-model.json"),
                        "names no file: {message}"
                    );
                }
            }
            Ok(())
        })
        .unwrap();
    report(
        "model loader",
        n,
        &format!(", {} of them loaded", loaded.get()),
    );
}
