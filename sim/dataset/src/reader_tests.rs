//! Tests of the dataset reader: round trips, and every kind of corrupt or inconsistent file
//! refused with an error naming it.

use super::*;
use crate::{ActorClass, ObjectTruth, PointLabel, SemanticClass, SequenceWriter};
use nalgebra::Vector3;

pub(crate) fn sample_sweep(index: u32) -> Sweep {
    let pose = Pose::new(
        Vector3::new(index as f64, 2.0, 1.73),
        Vector3::new(0.0, 0.0, 0.3),
    );
    Sweep {
        index,
        stamp_secs: index as f64 * 0.1,
        world_from_sensor: pose,
        points_in_sensor: vec![[1.0, 2.0, -1.5], [10.5, -3.25, 0.5]],
        intensities: vec![0.25, 0.75],
        labels: vec![
            PointLabel::new(SemanticClass::Road, 0),
            PointLabel::new(SemanticClass::MovingCar, 3),
        ],
        flow_in_world_mps: vec![[0.0, 0.0, 0.0], [5.0, -1.0, 0.0]],
        time_in_sweep_secs: vec![0.0125, 0.0875],
        rings: vec![63, 2],
        estimated_world_from_sensor: None,
        objects: vec![ObjectTruth {
            id: 3,
            name: "target".into(),
            class: ActorClass::Car,
            target: true,
            moving: true,
            centre_m: [12.0, 0.0, 0.75],
            size_m: [4.5, 1.8, 1.5],
            yaw_rad: -0.2,
            velocity_mps: [5.0, -1.0, 0.0],
            speed_mps: 26f64.sqrt(),
            heading_rad: (-1f64).atan2(5.0),
            yaw_rate_radps: 0.0,
            point_count: 1,
        }],
    }
}

pub(crate) fn write_sequence(root: &Path, sweeps: &[Sweep]) {
    let writer = SequenceWriter::open(root, "seq").unwrap();
    for sweep in sweeps {
        writer.write_sweep(sweep).unwrap();
    }
    let poses: Vec<Pose> = sweeps.iter().map(|s| s.world_from_sensor).collect();
    let stamps: Vec<f64> = sweeps.iter().map(|s| s.stamp_secs).collect();
    writer
        .finish("demo", 7, 10.0, &poses, &stamps, "test")
        .unwrap();
}

#[test]
fn a_written_sequence_reads_back_identically() {
    let dir = tempfile::tempdir().unwrap();
    let sweeps = [sample_sweep(0), sample_sweep(1)];
    write_sequence(dir.path(), &sweeps);
    let dataset = Dataset::open(dir.path()).unwrap();
    assert_eq!(dataset.sequences().len(), 1);
    assert_eq!(dataset.sequences()[0].points, 4);
    let seq = dataset.sequence("seq").unwrap();
    for (i, expected) in sweeps.iter().enumerate() {
        let got = seq.read_sweep(i).unwrap();
        assert_eq!(got.points_in_sensor, expected.points_in_sensor);
        assert_eq!(got.labels, expected.labels);
        assert_eq!(got.flow_in_world_mps, expected.flow_in_world_mps);
        assert_eq!(got.time_in_sweep_secs, expected.time_in_sweep_secs);
        assert_eq!(got.rings, expected.rings);
        assert_eq!(got.objects, expected.objects);
        assert!(
            (got.world_from_sensor.translation.vector
                - expected.world_from_sensor.translation.vector)
                .norm()
                < 1e-9
        );
    }
}

#[test]
fn a_restricted_dataset_lists_only_the_kept_sequences_and_refuses_to_be_empty() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    let dataset = Dataset::open(dir.path()).unwrap();
    let kept = dataset.restricted_to(&|name| name == "seq").unwrap();
    assert_eq!(kept.sequences().len(), 1);
    let err = dataset.restricted_to(&|_| false).unwrap_err().to_string();
    assert!(err.contains("sequences"), "{err}");
}

#[test]
fn a_ring_file_of_the_wrong_length_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    let ring = dir.path().join("sequences/seq/ring/000000.bin");
    std::fs::write(&ring, [0u8; 3]).unwrap();
    let err = open_err(dir.path());
    assert!(err.contains("ring/000000.bin"), "{err}");
}

#[test]
fn a_ring_file_far_too_large_is_refused_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    let ring = dir.path().join("sequences/seq/ring/000000.bin");
    let file = std::fs::File::options().write(true).open(&ring).unwrap();
    file.set_len(1 << 20).unwrap();
    let err = open_err(dir.path());
    assert!(
        err.contains("ring/000000.bin") && err.contains("more than 4 bytes"),
        "{err}"
    );
}

#[test]
fn a_truncated_label_file_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    let labels = dir.path().join("sequences/seq/labels/000000.label");
    std::fs::write(&labels, [0u8; 4]).unwrap();
    let err = Dataset::open(dir.path())
        .unwrap()
        .sequence("seq")
        .unwrap()
        .read_sweep(0)
        .unwrap_err();
    assert!(err.to_string().contains("000000.label"), "{err}");
}

#[test]
fn a_marker_of_another_version_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    let marker = dir.path().join("sequences/seq/sequence.json");
    let text = std::fs::read_to_string(&marker)
        .unwrap()
        .replace("\"version\": 1", "\"version\": 99");
    std::fs::write(&marker, text).unwrap();
    let err = Dataset::open(dir.path()).unwrap_err();
    assert!(
        matches!(err, DatasetError::Version { found: 99, .. }),
        "{err}"
    );
}

#[test]
fn an_unfinished_sequence_is_not_listed() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    let writer = SequenceWriter::open(dir.path(), "half").unwrap();
    writer.write_sweep(&sample_sweep(0)).unwrap();
    let dataset = Dataset::open(dir.path()).unwrap();
    let names: Vec<_> = dataset
        .sequences()
        .iter()
        .map(|s| s.name.as_str())
        .collect();
    assert_eq!(names, ["seq"]);
    assert!(writer.has_sweep(0) && !writer.has_sweep(1));
}

pub(crate) fn open_err(root: &Path) -> String {
    match Dataset::open(root) {
        Ok(d) => match d.sequence("seq").and_then(|s| s.read_sweep(0)) {
            Ok(_) => panic!("the dataset opened and read"),
            Err(e) => e.to_string(),
        },
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_sequence_listed_in_the_manifest_without_its_marker_is_an_error_naming_the_marker() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    let writer = SequenceWriter::open(dir.path(), "other").unwrap();
    writer.write_sweep(&sample_sweep(0)).unwrap();
    writer
        .finish(
            "demo",
            7,
            10.0,
            &[sample_sweep(0).world_from_sensor],
            &[0.0],
            "test",
        )
        .unwrap();
    Manifest::scan(dir.path())
        .unwrap()
        .write(dir.path())
        .unwrap();
    std::fs::remove_file(dir.path().join("sequences/other/sequence.json")).unwrap();
    let err = Dataset::open(dir.path()).unwrap_err().to_string();
    assert!(
        err.contains("other/sequence.json") && err.contains("manifest.json"),
        "{err}"
    );
}

#[test]
fn an_empty_object_file_where_labels_show_an_actor_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    std::fs::write(dir.path().join("sequences/seq/objects/000000.json"), "[]").unwrap();
    let err = open_err(dir.path());
    assert!(
        err.contains("000000.json") && err.contains("instance 3"),
        "{err}"
    );
}

#[test]
fn moving_labels_naming_an_instance_with_no_object_are_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let mut sweep = sample_sweep(0);
    sweep.labels[1] = PointLabel::new(SemanticClass::MovingCar, 9);
    sweep.objects[0].point_count = 0;
    write_sequence(dir.path(), &[sweep]);
    let err = open_err(dir.path());
    assert!(err.contains("instance 9"), "{err}");
}

#[test]
fn a_non_finite_point_is_an_error_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    let path = dir.path().join("sequences/seq/velodyne/000000.bin");
    let mut bytes = std::fs::read(&path).unwrap();
    bytes[4..8].copy_from_slice(&f32::NAN.to_le_bytes());
    std::fs::write(&path, bytes).unwrap();
    let err = open_err(dir.path());
    assert!(
        err.contains("velodyne/000000.bin") && err.contains("finite"),
        "{err}"
    );
}

#[test]
fn the_writer_refuses_a_non_finite_point_naming_the_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let mut sweep = sample_sweep(0);
    sweep.points_in_sensor[1][2] = f32::INFINITY;
    let writer = SequenceWriter::open(dir.path(), "seq").unwrap();
    let err = writer.write_sweep(&sweep).unwrap_err().to_string();
    assert!(
        err.contains("000000.json") && err.contains("point 1"),
        "{err}"
    );
}

#[test]
fn a_marker_whose_point_count_disagrees_with_the_files_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    let marker = dir.path().join("sequences/seq/sequence.json");
    let text = std::fs::read_to_string(&marker)
        .unwrap()
        .replace("\"points\": 2", "\"points\": 3");
    std::fs::write(&marker, text).unwrap();
    let err = open_err(dir.path());
    assert!(
        err.contains("sequence.json") && err.contains("hold 2"),
        "{err}"
    );
}

#[test]
fn a_velodyne_file_larger_than_a_sweep_can_be_is_refused_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    let path = dir.path().join("sequences/seq/velodyne/000000.bin");
    let file = std::fs::File::options().write(true).open(&path).unwrap();
    let points = crate::MAX_POINTS_PER_SWEEP as u64 + 1;
    file.set_len(16 * points).unwrap();
    let marker = dir.path().join("sequences/seq/sequence.json");
    let text = std::fs::read_to_string(&marker)
        .unwrap()
        .replace("\"points\": 2", &format!("\"points\": {points}"));
    std::fs::write(&marker, text).unwrap();
    let err = open_err(dir.path());
    assert!(err.contains("velodyne/000000.bin"), "{err}");
}

#[test]
fn an_infinite_time_stamp_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    std::fs::write(dir.path().join("sequences/seq/times.txt"), "inf\n").unwrap();
    let err = open_err(dir.path());
    assert!(err.contains("times.txt") && err.contains("finite"), "{err}");
}

#[test]
fn a_missing_sweep_is_reported_by_the_index_asked_for() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0)]);
    let err = Dataset::open(dir.path())
        .unwrap()
        .sequence("seq")
        .unwrap()
        .read_sweep(99)
        .unwrap_err()
        .to_string();
    assert!(err.contains("sweep 99") && err.contains("0 to 0"), "{err}");
}

#[test]
fn a_pose_translated_astronomically_far_is_refused_naming_the_line() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[sample_sweep(0), sample_sweep(1)]);
    let poses = dir.path().join("sequences/seq/poses.txt");
    let text = std::fs::read_to_string(&poses).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let mut values: Vec<String> = lines[1].split_whitespace().map(String::from).collect();
    values[3] = "1e300".into();
    lines[1] = values.join(" ");
    std::fs::write(&poses, lines.join("\n") + "\n").unwrap();
    let err = open_err(dir.path());
    assert!(err.contains("poses.txt") && err.contains("line 2"), "{err}");
}
