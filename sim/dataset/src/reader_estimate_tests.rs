//! Tests of the estimated-pose file a sequence may carry beside its true poses
//! (`poses_estimated.txt`): read when there, the truth when not, refused naming the file when
//! broken.

use super::tests::{open_err, sample_sweep, write_sequence};
use super::*;
use crate::SequenceWriter;
use nalgebra::Vector3;

#[test]
fn without_an_estimate_file_the_estimated_poses_are_the_truth() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0), sample_sweep(1)]);
    let seq = Dataset::open(dir.path()).unwrap().sequence("seq").unwrap();
    assert_eq!(seq.estimated_poses(), seq.poses());
    let sweep = seq.read_sweep(1).unwrap();
    assert_eq!(sweep.estimated_world_from_sensor, None);
    assert_eq!(sweep.estimated_pose(), sweep.world_from_sensor);
}

/// Writes two sweeps with an estimate file 0.3 m and 0.01 rad off the truth; returns the estimate.
fn write_sequence_with_estimate(root: &Path) -> Vec<Pose> {
    let sweeps = [sample_sweep(0), sample_sweep(1)];
    let writer = SequenceWriter::open(root, "seq").unwrap();
    for sweep in &sweeps {
        writer.write_sweep(sweep).unwrap();
    }
    let truth: Vec<Pose> = sweeps.iter().map(|s| s.world_from_sensor).collect();
    let estimate: Vec<Pose> = truth
        .iter()
        .map(|p| {
            Pose::new(
                p.translation.vector + Vector3::new(0.3, -0.2, 0.0),
                Vector3::new(0.0, 0.0, 0.31),
            )
        })
        .collect();
    writer.write_estimated_poses(&estimate).unwrap();
    let stamps: Vec<f64> = sweeps.iter().map(|s| s.stamp_secs).collect();
    writer
        .finish("demo", 7, 10.0, &truth, &stamps, "test")
        .unwrap();
    estimate
}

#[test]
fn an_estimate_file_is_read_beside_the_truth() {
    let dir = tempfile::tempdir().unwrap();
    let estimate = write_sequence_with_estimate(dir.path());
    let seq = Dataset::open(dir.path()).unwrap().sequence("seq").unwrap();
    let sweep = seq.read_sweep(1).unwrap();
    let got = sweep.estimated_pose().translation.vector;
    assert!((got - estimate[1].translation.vector).norm() < 1e-9);
    assert!(
        (sweep.world_from_sensor.translation.vector - Vector3::new(1.0, 2.0, 1.73)).norm() < 1e-9
    );
}

#[test]
fn an_estimate_file_with_a_non_finite_value_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence_with_estimate(dir.path());
    let path = dir.path().join("sequences/seq/poses_estimated.txt");
    let text = std::fs::read_to_string(&path).unwrap();
    let first = text.lines().next().unwrap();
    let broken: Vec<&str> = first
        .split_whitespace()
        .enumerate()
        .map(|(i, v)| if i == 3 { "NaN" } else { v })
        .collect();
    std::fs::write(&path, text.replacen(first, &broken.join(" "), 1)).unwrap();
    let err = open_err(dir.path());
    assert!(
        err.contains("poses_estimated.txt") && err.contains("line 1"),
        "{err}"
    );
}

#[test]
fn an_estimate_file_with_a_line_missing_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence_with_estimate(dir.path());
    let path = dir.path().join("sequences/seq/poses_estimated.txt");
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, text.lines().next().unwrap()).unwrap();
    let err = open_err(dir.path());
    assert!(
        err.contains("poses_estimated.txt") && err.contains("2 sweeps"),
        "{err}"
    );
}
