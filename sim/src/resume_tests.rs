//! Resume and "already complete" trust only what reads back: a truncated or emptied sweep left
//! by an interrupted run is written again, and a finished sequence whose files changed since is
//! refused with the damaged file named (issue 26).

#![allow(clippy::unwrap_used)]

use std::path::{Path, PathBuf};

use crate::{GenerateOptions, ScenarioSource, Shard, generate_dataset};

const TINY: &str = "sweeps = 2\n[lidar]\nchannels = 8\nazimuth_steps = 60\nblocks = 6\n\
    [ego]\npath_m = [[0.0, 0.0], [40.0, 0.0]]\nspeed_mps = 2.0\n\
    [[actors]]\nname = \"car\"\ntarget = true\npath_m = [[8.0, -6.0], [8.0, 40.0]]\nspeed_mps = 6.0\n";

fn generate(out: &Path) -> crate::Result<()> {
    let options = GenerateOptions {
        out: out.to_owned(),
        seed: 4,
        shard: Shard::ALL,
        realism: None,
        overwrite: false,
    };
    let source = ScenarioSource::Embedded("tiny", TINY);
    generate_dataset(&[source], &options, &|_| {}).map(|_| ())
}

fn sequence(out: &Path) -> PathBuf {
    out.join("sequences/tiny")
}

#[test]
fn a_resumed_run_writes_a_truncated_or_emptied_sweep_again() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("D");
    generate(&out).unwrap();
    let seq = sequence(&out);
    let velodyne = seq.join("velodyne/000001.bin");
    let labels = seq.join("labels/000000.label");
    let (whole_velodyne, whole_labels) = (
        std::fs::read(&velodyne).unwrap(),
        std::fs::read(&labels).unwrap(),
    );
    // An interrupted run: no marker yet, one sweep cut short and one label file emptied.
    std::fs::remove_file(seq.join("sequence.json")).unwrap();
    std::fs::write(&velodyne, &whole_velodyne[..whole_velodyne.len() / 2]).unwrap();
    std::fs::write(&labels, b"").unwrap();
    generate(&out).unwrap();
    assert_eq!(std::fs::read(&velodyne).unwrap(), whole_velodyne);
    assert_eq!(std::fs::read(&labels).unwrap(), whole_labels);
    patchflow_dataset::Dataset::open(&out).unwrap();
}

#[test]
fn a_finished_sequence_with_a_changed_file_is_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("D");
    generate(&out).unwrap();
    let labels = sequence(&out).join("labels/000001.label");
    // Same size, every label zeroed: only the recorded digest can tell.
    let zeros = vec![0u8; std::fs::metadata(&labels).unwrap().len() as usize];
    std::fs::write(&labels, zeros).unwrap();
    let err = generate(&out).unwrap_err().to_string();
    assert!(
        err.contains("labels/000001.label") && err.contains("damaged"),
        "{err}"
    );
}

#[test]
fn a_finished_sequence_with_a_nan_injected_is_not_called_complete() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("D");
    generate(&out).unwrap();
    let flow = sequence(&out).join("flow/000000.bin");
    let mut bytes = std::fs::read(&flow).unwrap();
    bytes[..4].copy_from_slice(&f32::NAN.to_le_bytes());
    std::fs::write(&flow, bytes).unwrap();
    let err = generate(&out).unwrap_err().to_string();
    assert!(err.contains("flow/000000.bin"), "{err}");
}

#[test]
fn the_marker_records_a_digest_of_every_sweep_file_and_the_manifest_does_not() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("D");
    generate(&out).unwrap();
    let marker = std::fs::read_to_string(sequence(&out).join("sequence.json")).unwrap();
    let info: patchflow_dataset::SequenceInfo = serde_json::from_str(&marker).unwrap();
    assert_eq!(info.sweep_sha256.len(), 2);
    let velodyne = std::fs::read(sequence(&out).join("velodyne/000000.bin")).unwrap();
    assert_eq!(
        info.sweep_sha256[0]["velodyne"],
        patchflow_dataset::sha256_hex(&velodyne)
    );
    let manifest = std::fs::read_to_string(out.join("manifest.json")).unwrap();
    assert!(!manifest.contains("sweep_sha256"));
}
