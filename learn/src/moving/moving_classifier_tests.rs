//! Tests of the moving classifier: decisions on a scene with a moving and a parked car, the file.

use super::*;
use crate::moving::{MOVING_FILE_NAME, cluster_is_moving};
use crate::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};

/// Features of a scene with one car at `speed_mps` and one parked car, the observed change over
/// 0.5 s, and the current sweep.
fn scene(speed_mps: f64, at: [f64; 2]) -> (SweepFeatures, ChangeEvidence, Sweep) {
    let scene = SyntheticScene {
        boxes: vec![
            SceneBox::car(1, at, 0.3, speed_mps),
            SceneBox::car(2, [-at[0], -at[1]], 1.2, 0.0),
        ],
    };
    let lidar = SyntheticLidar::with_resolution(32, 720);
    let valid = FeatureParams::default().check().unwrap();
    let past = scene.advanced(-0.4).scan(&lidar, [0.0, 0.0], 0.0, 0);
    let prev = scene.scan(&lidar, [0.0, 0.0], 0.0, 4);
    let curr = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 5);
    let slice = |s: &Sweep| HeightSlice::cut(s, &valid).unwrap();
    let f = SweepFeatures::from_slices(&slice(&prev), &slice(&curr), &valid).unwrap();
    let change = ChangeEvidence::build(&slice(&past), &slice(&curr), &valid);
    (f, change, curr)
}

fn training_rows() -> Vec<MovingRow> {
    let mut rows = Vec::new();
    for (k, speed) in [0.0, 4.0, 8.0, 12.0].iter().enumerate() {
        for r in [10.0, 15.0, 20.0] {
            let (f, change, sweep) = scene(*speed, [r, 2.0 + k as f64]);
            for c in f.object_hypotheses() {
                rows.push(MovingRow::of(&f, &change, &sweep, c));
            }
        }
    }
    rows
}

fn trained() -> MovingClassifier {
    MovingClassifier::fit(training_rows(), &MovingParams::default()).unwrap()
}

/// `classifier` saved as `moving.json` in a fresh folder, its JSON then changed by `edit`.
fn saved_and_edited(
    classifier: &MovingClassifier,
    edit: impl FnOnce(&mut serde_json::Value),
) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(MOVING_FILE_NAME);
    classifier.save(&path).unwrap();
    let mut value: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    edit(&mut value);
    std::fs::write(&path, serde_json::to_vec(&value).unwrap()).unwrap();
    (dir, path)
}

#[test]
fn a_moving_car_is_decided_moving_and_a_parked_car_static() {
    let classifier = trained();
    let (f, change, sweep) = scene(10.0, [13.0, 4.0]);
    let decisions = classifier.cluster_decisions(&f, &change).unwrap();
    let hypotheses = f.object_hypotheses();
    assert_eq!(hypotheses.len(), 2);
    for c in hypotheses {
        assert_eq!(
            decisions[c],
            Some(cluster_is_moving(&f, &sweep, c)),
            "cluster {c}"
        );
    }
}

#[test]
fn along_their_tracks_a_moving_car_stays_moving_and_a_parked_car_static() {
    let classifier = trained();
    let cars = SyntheticScene {
        boxes: vec![
            SceneBox::car(1, [13.0, 4.0], 0.3, 10.0),
            SceneBox::car(2, [-13.0, -4.0], 1.2, 0.0),
        ],
    };
    let lidar = SyntheticLidar::with_resolution(32, 720);
    let valid = FeatureParams::default().check().unwrap();
    let slice = |t: f64, index: u32| {
        HeightSlice::cut(
            &cars.advanced(t).scan(&lidar, [0.0, 0.0], 0.0, index),
            &valid,
        )
        .unwrap()
    };
    let mut belief = MovingBelief::default();
    for k in 5..12u32 {
        let t = 0.1 * f64::from(k);
        let now = cars.advanced(t).scan(&lidar, [0.0, 0.0], 0.0, k);
        let current = HeightSlice::cut(&now, &valid).unwrap();
        let f = SweepFeatures::from_slices(&slice(t - 0.1, k - 1), &current, &valid).unwrap();
        let change = ChangeEvidence::build(&slice(t - 0.5, k - 5), &current, &valid);
        let decisions = classifier
            .tracked_decisions(&mut belief, &f, &change, t)
            .unwrap();
        for c in f.object_hypotheses() {
            assert_eq!(
                decisions[c],
                Some(cluster_is_moving(&f, &now, c)),
                "scan {k}, cluster {c}"
            );
        }
    }
}

#[test]
fn the_decision_threshold_lies_between_even_odds_and_certainty() {
    let t = trained().threshold();
    assert!((0.5..1.0).contains(&t), "threshold {t}");
}

#[test]
fn a_saved_classifier_loads_back_with_the_same_probabilities_and_threshold() {
    let classifier = trained();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(MOVING_FILE_NAME);
    classifier.save(&path).unwrap();
    let loaded = MovingClassifier::load(&path).unwrap();
    let (f, change, _) = scene(6.0, [12.0, 3.0]);
    let a = classifier.cluster_probabilities(&f, &change).unwrap();
    let b = loaded.cluster_probabilities(&f, &change).unwrap();
    assert_eq!(a, b);
    assert_eq!(classifier.threshold(), loaded.threshold());
}

#[test]
fn a_file_of_another_format_or_version_is_refused_with_its_path() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(MOVING_FILE_NAME);
    std::fs::write(&path, r#"{"format":"other","version":2}"#).unwrap();
    let err = MovingClassifier::load(&path).unwrap_err().to_string();
    assert!(
        err.contains("moving.json") && err.contains("other"),
        "{err}"
    );
    let classifier = trained();
    classifier.save(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, text.replace("\"version\":3", "\"version\":1")).unwrap();
    let err = MovingClassifier::load(&path).unwrap_err().to_string();
    assert!(
        err.contains("version 1") && err.contains("retrain"),
        "{err}"
    );
}

#[test]
fn the_bag_reads_the_mean_of_its_draws_probabilities() {
    let params = MovingParams {
        max_rows: 16,
        ..MovingParams::default()
    };
    let bag = MovingClassifier::fit(training_rows(), &params).unwrap();
    assert_eq!(bag.training_rows().len(), 3);
    let (f, change, _) = scene(6.0, [12.0, 3.0]);
    let mut mean = vec![0.0; f.clusters().len()];
    for k in 0..3 {
        let one = MovingParams {
            draws: 1,
            seed: params.seed + k,
            ..params
        };
        let draw = MovingClassifier::fit(training_rows(), &one).unwrap();
        for (m, p) in mean
            .iter_mut()
            .zip(draw.cluster_probabilities(&f, &change).unwrap())
        {
            *m += p.unwrap_or(0.0) / 3.0;
        }
    }
    let probabilities = bag.cluster_probabilities(&f, &change).unwrap();
    for c in f.object_hypotheses() {
        let p = probabilities[c].unwrap();
        assert!(
            (p - mean[c]).abs() < 1e-12,
            "cluster {c}: {p} against {}",
            mean[c]
        );
    }
}

#[test]
fn a_version_2_file_reads_as_a_bag_of_one() {
    let one = MovingClassifier::fit(
        training_rows(),
        &MovingParams {
            draws: 1,
            ..MovingParams::default()
        },
    )
    .unwrap();
    // Version 2 kept the one GP's fields beside the threshold.
    let (_dir, path) = saved_and_edited(&one, |value| {
        let draw = value["draws"][0].clone();
        let file = value.as_object_mut().unwrap();
        file.remove("draws");
        for key in ["rows", "moving_rows", "squashing", "gp"] {
            file.insert(key.into(), draw[key].clone());
        }
        file.insert("version".into(), serde_json::json!(2));
    });
    let loaded = MovingClassifier::load(&path).unwrap();
    let (f, change, _) = scene(6.0, [12.0, 3.0]);
    assert_eq!(
        loaded.cluster_probabilities(&f, &change).unwrap(),
        one.cluster_probabilities(&f, &change).unwrap()
    );
    assert_eq!(loaded.threshold(), one.threshold());
}

#[test]
fn a_file_with_an_empty_bag_is_refused() {
    let (_dir, path) = saved_and_edited(&trained(), |value| {
        value["draws"] = serde_json::json!([]);
    });
    let err = MovingClassifier::load(&path).unwrap_err().to_string();
    assert!(
        err.contains("moving.json") && err.contains("draws"),
        "{err}"
    );
}

#[test]
fn a_threshold_outside_its_range_is_refused() {
    let (_dir, path) = saved_and_edited(&trained(), |value| {
        value["threshold"] = serde_json::json!(1.5);
    });
    let err = MovingClassifier::load(&path).unwrap_err().to_string();
    assert!(err.contains("threshold"), "{err}");
}

#[test]
fn one_class_only_is_an_error() {
    let row = MovingRow {
        inputs: [0.0; MOVING_INPUTS],
        moving: false,
        moving_points: 0,
        static_points: 10,
    };
    assert!(MovingClassifier::fit(vec![row; 10], &MovingParams::default()).is_err());
}
