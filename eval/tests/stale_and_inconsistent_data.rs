//! `generate` never mixes another request into a folder (another seed or scenario is refused,
//! `--overwrite` regenerates), two identical runs into one folder both succeed without
//! temporary files left, and readers refuse a dataset whose files disagree instead of silently
//! using less of it (issue 13).

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

mod common;

use std::path::Path;

use common::{
    assert_clean_failure, assert_success, files, generate_file, generate_tiny, patchflow,
    tiny_scenario, train_small,
};

#[test]
fn another_seed_into_a_finished_folder_is_refused_and_overwrite_regenerates_it() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    assert_success(&generate_tiny(&data, 1));
    assert_clean_failure(
        &generate_tiny(&data, 2),
        &["sequences/tiny", "seed 1, not 2", "--overwrite"],
    );
    let overwritten = patchflow(&[
        "generate",
        tiny_scenario().to_str().unwrap(),
        "--out",
        data.to_str().unwrap(),
        "--seed",
        "2",
        "--overwrite",
    ]);
    assert_success(&overwritten);
    let fresh = dir.path().join("fresh");
    assert_success(&generate_tiny(&fresh, 2));
    assert_eq!(files(&data), files(&fresh));
}

#[test]
fn an_edited_scenario_into_a_finished_folder_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("tiny.toml");
    let text = std::fs::read_to_string(tiny_scenario()).unwrap();
    std::fs::write(&scenario, &text).unwrap();
    let data = dir.path().join("data");
    let run = || generate_file(&scenario, &data);
    assert_success(&run());
    std::fs::write(
        &scenario,
        text.replace("speed_mps = 8.0", "speed_mps = 9.0"),
    )
    .unwrap();
    assert_clean_failure(&run(), &["sequences/tiny", "another scenario text"]);
}

#[test]
fn an_edited_mesh_file_into_a_finished_folder_is_refused() {
    // The scenario text stays the same; only the vehicle model it names changes.
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("tiny.toml");
    let text = std::fs::read_to_string(tiny_scenario()).unwrap();
    std::fs::write(
        &scenario,
        text.replace("target = true\n", "target = true\nmesh = \"car.obj\"\n"),
    )
    .unwrap();
    let cube = |x: f32| {
        format!(
            "v 0 0 0\nv {x} 0 0\nv {x} 1 0\nv 0 1 0\nv 0 0 1\nv {x} 0 1\nv {x} 1 1\nv 0 1 1\n\
             f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n"
        )
    };
    std::fs::write(dir.path().join("car.obj"), cube(2.0)).unwrap();
    let data = dir.path().join("data");
    let run = || generate_file(&scenario, &data);
    assert_success(&run());
    assert_success(&run()); // the same request again: skipped, not refused
    std::fs::write(dir.path().join("car.obj"), cube(2.5)).unwrap();
    assert_clean_failure(&run(), &["sequences/tiny", "another scenario text"]);
}

#[test]
fn two_identical_runs_into_one_folder_both_succeed_and_leave_no_temporary_files() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    let (a, b) = std::thread::scope(|s| {
        let a = s.spawn(|| generate_tiny(&data, 3));
        let b = s.spawn(|| generate_tiny(&data, 3));
        (a.join().unwrap(), b.join().unwrap())
    });
    assert_success(&a);
    assert_success(&b);
    let names = files(&data);
    assert!(
        names
            .iter()
            .all(|(p, _)| p.extension().is_none_or(|e| e != "tmp"))
    );
    let fresh = dir.path().join("fresh");
    assert_success(&generate_tiny(&fresh, 3));
    assert_eq!(names, files(&fresh));
}

#[test]
fn temporary_files_of_a_crashed_run_are_removed_by_the_next() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    let velodyne = data.join("sequences/tiny/velodyne");
    std::fs::create_dir_all(&velodyne).unwrap();
    let stale = velodyne.join("000000.bin.4242-0.tmp");
    std::fs::write(&stale, b"half a sweep").unwrap();
    assert_success(&generate_tiny(&data, 0));
    assert!(!stale.exists());
}

/// A finished tiny dataset in `dir/data`.
fn tiny_data(dir: &Path) -> std::path::PathBuf {
    let data = dir.join("data");
    assert_success(&generate_tiny(&data, 0));
    data
}

#[test]
fn a_sequence_listed_in_the_manifest_without_its_marker_stops_training() {
    let dir = tempfile::tempdir().unwrap();
    let data = tiny_data(dir.path());
    std::fs::remove_file(data.join("sequences/tiny/sequence.json")).unwrap();
    let model = dir.path().join("m.json");
    assert_clean_failure(
        &train_small(&data, &model),
        &["sequences/tiny/sequence.json", "manifest.json"],
    );
}

#[test]
fn an_empty_object_file_where_labels_show_actors_stops_training_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let data = tiny_data(dir.path());
    std::fs::write(data.join("sequences/tiny/objects/000001.json"), "[]").unwrap();
    let model = dir.path().join("m.json");
    assert_clean_failure(
        &train_small(&data, &model),
        &["objects/000001.json", "no object has that id"],
    );
}

#[test]
fn a_non_finite_point_is_reported_with_its_file() {
    let dir = tempfile::tempdir().unwrap();
    let data = tiny_data(dir.path());
    let path = data.join("sequences/tiny/velodyne/000002.bin");
    let mut bytes = std::fs::read(&path).unwrap();
    bytes[0..4].copy_from_slice(&f32::INFINITY.to_le_bytes());
    std::fs::write(&path, bytes).unwrap();
    let output = patchflow(&[
        "show",
        "--data",
        data.to_str().unwrap(),
        "--scan",
        "2",
        "--out",
        dir.path().join("s.png").to_str().unwrap(),
    ]);
    assert_clean_failure(&output, &["velodyne/000002.bin", "not a finite number"]);
}

#[test]
fn show_with_a_scan_past_the_end_reports_that_scan() {
    let dir = tempfile::tempdir().unwrap();
    let data = tiny_data(dir.path());
    let output = patchflow(&[
        "show",
        "--data",
        data.to_str().unwrap(),
        "--scan",
        "99",
        "--out",
        dir.path().join("s.png").to_str().unwrap(),
    ]);
    assert_clean_failure(&output, &["--scan 99", "3 sweeps (0 to 2)"]);
}
