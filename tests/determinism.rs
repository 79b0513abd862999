//! Generating the same scenario with the same seed gives byte-identical files; another seed
//! changes the noise; an interrupted run resumes to the same bytes.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use std::path::{Path, PathBuf};

use patchflow_sim::{GenerateOptions, ScenarioSource, Shard, generate_dataset};

fn tiny() -> ScenarioSource {
    ScenarioSource::File(
        patchflow_tests::workspace_root()
            .join("scenarios")
            .join("tiny.toml"),
    )
}

fn generate(out: &Path, seed: u64) {
    let options = GenerateOptions {
        out: out.to_owned(),
        seed,
        shard: Shard::ALL,
        realism: None,
        overwrite: false,
    };
    generate_dataset(&[tiny()], &options, &|_| {}).unwrap();
}

fn files(root: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![root.to_owned()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                out.push((
                    path.strip_prefix(root).unwrap().to_owned(),
                    std::fs::read(&path).unwrap(),
                ));
            }
        }
    }
    out.sort();
    out
}

#[test]
fn the_same_seed_gives_byte_identical_datasets() {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    generate(a.path(), 7);
    generate(b.path(), 7);
    let (fa, fb) = (files(a.path()), files(b.path()));
    assert!(fa.len() > 15);
    assert_eq!(fa, fb);
}

#[test]
fn another_seed_changes_the_points() {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    generate(a.path(), 7);
    generate(b.path(), 8);
    let velodyne = Path::new("sequences/tiny/velodyne/000000.bin");
    assert_ne!(
        std::fs::read(a.path().join(velodyne)).unwrap(),
        std::fs::read(b.path().join(velodyne)).unwrap()
    );
}

#[test]
fn a_resumed_run_writes_the_same_bytes() {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    generate(a.path(), 3);
    generate(b.path(), 3);
    // Simulate a crash after sweep 1: drop the marker and sweep 2's object file (written last).
    let seq = b.path().join("sequences/tiny");
    std::fs::remove_file(seq.join("sequence.json")).unwrap();
    std::fs::remove_file(seq.join("objects/000002.json")).unwrap();
    std::fs::write(seq.join("velodyne/000002.bin"), b"half").unwrap();
    generate(b.path(), 3);
    assert_eq!(files(a.path()), files(b.path()));
}
