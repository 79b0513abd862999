//! Edited dataset files (markers, manifest, poses, times, binary sweeps, labels, object truth)
//! through the reader: every sweep reads, or the error names a file of the dataset.

use std::cell::Cell;
use std::path::{Path, PathBuf};

use patchflow_dataset::{Dataset, LOCK_FILE};
use patchflow_sim::{GenerateOptions, ScenarioSource, Shard, generate_dataset};
use proptest::prelude::*;

use crate::mutate::{apply, edits};
use crate::{cases, report, runner};

/// Two sweeps of a crossing car seen by a small lidar, as a dataset in `root`; returns its
/// files (relative path, bytes), lock files left out.
fn small_dataset(root: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let scenario = root.join("small.toml");
    let text = "sweeps = 2\n[lidar]\nchannels = 8\nazimuth_steps = 60\nblocks = 6\n\
        [ego]\npath_m = [[0.0, 0.0], [40.0, 0.0]]\nspeed_mps = 2.0\n\
        [[actors]]\nname = \"car\"\ntarget = true\npath_m = [[8.0, -6.0], [8.0, 40.0]]\nspeed_mps = 6.0\n";
    std::fs::write(&scenario, text).unwrap();
    let data = root.join("data");
    let options = GenerateOptions {
        out: data.clone(),
        seed: 2,
        shard: Shard::ALL,
        realism: None,
        overwrite: false,
    };
    generate_dataset(&[ScenarioSource::File(scenario)], &options, &|_| {}).unwrap();
    let mut files = Vec::new();
    let mut stack = vec![data.clone()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.file_name().is_some_and(|n| n != LOCK_FILE) {
                let bytes = std::fs::read(&path).unwrap();
                files.push((path.strip_prefix(&data).unwrap().to_owned(), bytes));
            }
        }
    }
    files.sort();
    files
}

/// Opens the dataset and reads every sweep of every sequence.
fn read_all(root: &Path) -> patchflow_dataset::Result<usize> {
    let dataset = Dataset::open(root)?;
    let mut points = 0;
    for info in dataset.sequences() {
        let sequence = dataset.sequence(&info.name)?;
        for i in 0..sequence.len() {
            points += sequence.read_sweep(i)?.len();
        }
    }
    Ok(points)
}

#[test]
fn edited_dataset_files_read_back_or_are_refused_naming_a_file() {
    let n = cases(10_000);
    let dir = tempfile::tempdir().unwrap();
    let files = small_dataset(dir.path());
    let data = dir.path().join("data");
    let root_text = data.display().to_string();
    assert!(read_all(&data).unwrap() > 100);
    let refused = Cell::new(0u32);
    let strategy = (0..files.len(), edits());
    runner(n)
        .run(&strategy, |(k, edits)| {
            let (relative, original) = &files[k];
            let path = data.join(relative);
            std::fs::write(&path, apply(original, &edits)).unwrap();
            let result = read_all(&data);
            std::fs::write(&path, original).unwrap();
            if let Err(e) = result {
                refused.set(refused.get() + 1);
                let message = e.to_string();
                prop_assert!(
                    message.contains(&root_text),
                    "names no file of the dataset: {message}"
                );
            }
            Ok(())
        })
        .unwrap();
    report(
        "dataset reader",
        n,
        &format!(", {} of them refused", refused.get()),
    );
}
