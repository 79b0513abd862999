//! Whether one sweep's files on disk are whole: read with every check of the reader (sizes agree,
//! values finite, labels agree with the object truth), and their SHA-256 against the digests a
//! finished sequence's marker records (`sequence.json`, `sweep_sha256`). `generate` uses it to
//! redo damaged sweeps on resume and to refuse a damaged sequence it would call complete.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::limits::{MAX_JSON_BYTES, read_limited};
use crate::record_files::{read_f32s, read_u16s, read_words};
use crate::sweep::MAX_TIME_IN_SWEEP_SECS;

/// What a `velodyne` file's values may reach: coordinates within the dataset's span (and
/// intensities far below it).
const VELODYNE_LIMIT: (f64, &str) = (crate::MAX_COORDINATE_M, "m");
/// What a `flow` file's values may reach: no road user moves faster.
const FLOW_LIMIT: (f64, &str) = (crate::MAX_OBJECT_SPEED_MPS, "m/s");
/// What a `time` file's values may reach.
const TIME_LIMIT: (f64, &str) = (MAX_TIME_IN_SWEEP_SECS, "s");
use crate::sweep_checks::check_objects;
use sha2::{Digest, Sha256};

use crate::{DatasetError, ObjectTruth, PointLabel, Result};

/// The files of one sweep as read and checked, before poses and stamps are attached.
#[derive(Debug)]
pub(crate) struct SweepFiles {
    pub velodyne: Vec<f32>,
    pub labels: Vec<PointLabel>,
    pub flow: Vec<f32>,
    pub time: Vec<f32>,
    pub rings: Vec<u16>,
    pub objects: Vec<ObjectTruth>,
}

/// The per-sweep files of the layout: folder and extension; `ring` is optional.
pub(crate) const SWEEP_FILE_KINDS: [(&str, &str); 6] = [
    ("velodyne", "bin"),
    ("labels", "label"),
    ("flow", "bin"),
    ("time", "bin"),
    ("ring", "bin"),
    ("objects", "json"),
];

/// Reads sweep `i` of sequence folder `dir` with every check; errors name the file.
pub(crate) fn read_sweep_files(dir: &Path, i: u32) -> Result<SweepFiles> {
    let velodyne = read_f32s(
        &sweep_path(dir, "velodyne", i, "bin"),
        4,
        None,
        VELODYNE_LIMIT,
    )?;
    let n = velodyne.len() / 4;
    let labels_path = sweep_path(dir, "labels", i, "label");
    let labels: Vec<PointLabel> = read_words(&labels_path, 1, Some(n))?
        .into_iter()
        .map(PointLabel)
        .collect();
    let flow = read_f32s(&sweep_path(dir, "flow", i, "bin"), 3, Some(n), FLOW_LIMIT)?;
    let time = read_f32s(&sweep_path(dir, "time", i, "bin"), 1, Some(n), TIME_LIMIT)?;
    let ring_path = sweep_path(dir, "ring", i, "bin");
    let rings = match ring_path.is_file() {
        true => read_u16s(&ring_path, n)?,
        false => Vec::new(),
    };
    let objects_path = sweep_path(dir, "objects", i, "json");
    let objects: Vec<ObjectTruth> =
        serde_json::from_slice(&read_limited(&objects_path, MAX_JSON_BYTES)?)
            .map_err(|e| DatasetError::corrupt(&objects_path, e.to_string()))?;
    check_objects(&objects, &labels, &labels_path)
        .map_err(|reason| DatasetError::corrupt(&objects_path, reason))?;
    Ok(SweepFiles {
        velodyne,
        labels,
        flow,
        time,
        rings,
        objects,
    })
}

/// SHA-256 of each file sweep `i` has (`velodyne` → hex digest, …), as a marker records them.
pub(crate) fn sweep_digests(dir: &Path, i: u32) -> Result<BTreeMap<String, String>> {
    let mut digests = BTreeMap::new();
    for (folder, ext) in SWEEP_FILE_KINDS {
        let path = sweep_path(dir, folder, i, ext);
        if folder == "ring" && !path.is_file() {
            continue;
        }
        let bytes = read_limited(&path, crate::limits::MAX_SWEEP_FILE_BYTES)?;
        digests.insert(folder.to_owned(), sha256_hex(&bytes));
    }
    Ok(digests)
}

/// Checks sweep `i` against `recorded` digests: the first file whose SHA-256 differs (or that
/// is missing) is a [`DatasetError::Corrupt`] naming it.
pub(crate) fn check_sweep_digests(
    dir: &Path,
    i: u32,
    recorded: &BTreeMap<String, String>,
) -> Result<()> {
    for (folder, ext) in SWEEP_FILE_KINDS {
        let path: PathBuf = sweep_path(dir, folder, i, ext);
        let Some(wanted) = recorded.get(folder) else {
            continue;
        };
        let bytes = read_limited(&path, crate::limits::MAX_SWEEP_FILE_BYTES)?;
        if sha256_hex(&bytes) != *wanted {
            return Err(DatasetError::corrupt(
                &path,
                format!(
                    "its SHA-256 differs from the one sequence.json recorded when it was written ({}…): the file was changed or damaged since; regenerate the sequence (generate --overwrite)",
                    wanted.get(..12).unwrap_or("")
                ),
            ));
        }
    }
    Ok(())
}

/// SHA-256 of `bytes` as 64 lower-case hex digits (what `sha256sum` prints).
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// `dir/folder/NNNNNN.ext`.
pub(crate) fn sweep_path(dir: &Path, folder: &str, index: u32, ext: &str) -> PathBuf {
    dir.join(folder).join(format!("{index:06}.{ext}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::reader::tests::{sample_sweep, write_sequence};

    /// The error reading sweep 0 of `root`'s sequence `seq`, or opening it.
    fn read_err(root: &Path) -> String {
        let opened = crate::Dataset::open(root).and_then(|d| d.sequence("seq"));
        match opened.and_then(|s| s.read_sweep(0)) {
            Ok(_) => panic!("the sweep was read"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn finite_but_absurd_point_values_are_refused_naming_the_file_and_the_bound() {
        // (file, value index, value): a flow of 3e38 m/s, a coordinate of 1e30 m, a time of 1e9 s.
        for (file, k, value, unit) in [
            ("flow", 0, 3e38f32, "m/s"),
            ("flow", 4, -2000.0, "m/s"),
            ("velodyne", 1, 1e30, "m"),
            ("time", 0, 1e9, "s"),
        ] {
            let dir = tempfile::tempdir().unwrap();
            write_sequence(dir.path(), &[sample_sweep(0), sample_sweep(1)]);
            let path = dir.path().join(format!("sequences/seq/{file}/000000.bin"));
            let mut bytes = std::fs::read(&path).unwrap();
            bytes[4 * k..4 * k + 4].copy_from_slice(&value.to_le_bytes());
            std::fs::write(&path, bytes).unwrap();
            let err = read_err(dir.path());
            assert!(
                err.contains(&format!("{file}/000000.bin")) && err.contains(unit),
                "{file}: {err}"
            );
        }
    }

    #[test]
    fn times_beyond_the_bound_or_out_of_order_are_refused_naming_the_line() {
        for (line, text) in [(2, "1e300"), (2, "-0.5"), (1, "4e9")] {
            let dir = tempfile::tempdir().unwrap();
            write_sequence(dir.path(), &[sample_sweep(0), sample_sweep(1)]);
            let path = dir.path().join("sequences/seq/times.txt");
            let old = std::fs::read_to_string(&path).unwrap();
            let mut lines: Vec<&str> = old.lines().collect();
            lines[line - 1] = text;
            std::fs::write(&path, lines.join("\n") + "\n").unwrap();
            let err = read_err(dir.path());
            assert!(
                err.contains("times.txt") && err.contains(&format!("line {line}")),
                "{text}: {err}"
            );
        }
    }

    #[test]
    fn the_scenario_hash_is_what_sha256sum_prints() {
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }
}
