//! The realism ladder across crates: on the default `urban` rung the tiny scene is written with
//! ring files and the ego's own pose estimate, its road is not a plane, `generate --realism`
//! replaces a file's rung, and every rung is byte-identical for the same seed.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use std::path::Path;

use patchflow_dataset::Dataset;
use patchflow_sim::{GenerateOptions, Realism, ScenarioSource, Shard, generate_dataset};

fn tiny_text() -> String {
    std::fs::read_to_string(patchflow_tests::workspace_root().join("scenarios/tiny.toml")).unwrap()
}

fn generate(dir: &Path, text: &str, rung: Option<Realism>) -> Dataset {
    let file = dir.join("tiny.toml");
    std::fs::write(&file, text).unwrap();
    let options = GenerateOptions {
        out: dir.join("data"),
        seed: 3,
        shard: Shard::ALL,
        realism: rung,
        overwrite: false,
    };
    generate_dataset(&[ScenarioSource::File(file)], &options, &|_| {}).unwrap();
    Dataset::open(&dir.join("data")).unwrap()
}

/// Standard deviation of the world z of the road points of sweep `index`.
fn road_height_std(dataset: &Dataset, index: usize) -> f64 {
    let sweep = dataset.sequence("tiny").unwrap().read_sweep(index).unwrap();
    let zs: Vec<f64> = (0..sweep.len())
        .filter(|&i| sweep.labels[i].semantic() == 40)
        .map(|i| sweep.point_in_world(i).z)
        .collect();
    assert!(zs.len() > 1000, "{} road points", zs.len());
    let mean = zs.iter().sum::<f64>() / zs.len() as f64;
    (zs.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / zs.len() as f64).sqrt()
}

#[test]
fn the_urban_tiny_scene_has_rings_a_drifting_pose_estimate_and_a_road_that_is_not_a_plane() {
    let (urban_dir, ideal_dir) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let urban = generate(urban_dir.path(), &tiny_text(), None);
    let sequence = urban.sequence("tiny").unwrap();
    let sweep = sequence.read_sweep(1).unwrap();
    assert_eq!(sweep.rings.len(), sweep.len());
    assert!(sweep.rings.iter().all(|&r| r < 32), "tiny has 32 channels");
    assert!(sweep.rings.contains(&0) && sweep.rings.contains(&31));
    // The estimate drifts off the truth, by centimetres to a metre (0.3 m std per axis).
    for (truth, estimate) in sequence.poses().iter().zip(sequence.estimated_poses()) {
        let off = (truth.translation.vector - estimate.translation.vector).norm();
        assert!((0.001..2.0).contains(&off), "estimate off by {off} m");
    }
    // Camber, grade and roughness: the road's height spread is well above the ideal plane's
    // (which is range noise alone).
    let ideal = generate(ideal_dir.path(), &tiny_text(), Some(Realism::Ideal));
    let (urban_std, ideal_std) = (road_height_std(&urban, 1), road_height_std(&ideal, 1));
    assert!(
        urban_std > 0.015 && urban_std > 3.0 * ideal_std,
        "urban {urban_std} m, ideal {ideal_std} m"
    );
    assert!(
        ideal
            .sequence("tiny")
            .unwrap()
            .read_sweep(1)
            .unwrap()
            .rings
            .len()
            > 1000
    );
}

#[test]
fn generate_with_a_rung_writes_what_the_file_naming_that_rung_writes() {
    let (option_dir, file_dir) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    generate(option_dir.path(), &tiny_text(), Some(Realism::Harsh));
    generate(
        file_dir.path(),
        &format!("realism = \"harsh\"\n{}", tiny_text()),
        None,
    );
    for file in [
        "velodyne/000002.bin",
        "labels/000002.label",
        "ring/000002.bin",
    ] {
        let read = |dir: &Path| std::fs::read(dir.join("data/sequences/tiny").join(file)).unwrap();
        assert_eq!(read(option_dir.path()), read(file_dir.path()), "{file}");
    }
    let read =
        |dir: &Path| std::fs::read(dir.join("data/sequences/tiny/poses_estimated.txt")).unwrap();
    assert_eq!(read(option_dir.path()), read(file_dir.path()));
}

#[test]
fn the_same_seed_and_rung_give_identical_bytes_on_the_harsh_rung() {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    generate(a.path(), &tiny_text(), Some(Realism::Harsh));
    generate(b.path(), &tiny_text(), Some(Realism::Harsh));
    for file in [
        "velodyne/000000.bin",
        "flow/000000.bin",
        "ring/000000.bin",
        "poses_estimated.txt",
    ] {
        let read = |dir: &Path| std::fs::read(dir.join("data/sequences/tiny").join(file)).unwrap();
        assert_eq!(read(a.path()), read(b.path()), "{file}");
    }
}

#[test]
fn the_same_scenario_on_another_rung_is_refused_without_overwrite_and_regenerated_with_it() {
    let dir = tempfile::tempdir().unwrap();
    let text = "sweeps = 1\n[lidar]\nchannels = 8\nazimuth_steps = 90\nblocks = 9\n[ego]\npath_m = [[0.0, 0.0], [40.0, 0.0]]\nspeed_mps = 2.0\n";
    let file = dir.path().join("rungs.toml");
    std::fs::write(&file, text).unwrap();
    let run = |rung: Option<Realism>, overwrite: bool| {
        let options = GenerateOptions {
            out: dir.path().join("data"),
            seed: 3,
            shard: Shard::ALL,
            realism: rung,
            overwrite,
        };
        generate_dataset(&[ScenarioSource::File(file.clone())], &options, &|_| {})
    };
    run(None, false).unwrap();
    // The resolved scenario (whose SHA-256 the marker records) names its rung.
    let stored = dir.path().join("data/sequences/rungs/scenario.toml");
    assert!(
        std::fs::read_to_string(&stored)
            .unwrap()
            .contains("realism = \"urban\"")
    );
    let err = run(Some(Realism::Ideal), false).unwrap_err().to_string();
    assert!(
        err.contains("refusing") && err.contains("--overwrite") && err.contains("rungs"),
        "{err}"
    );
    run(Some(Realism::Urban), false).unwrap();
    run(Some(Realism::Ideal), true).unwrap();
    assert!(
        std::fs::read_to_string(&stored)
            .unwrap()
            .contains("realism = \"ideal\"")
    );
}
