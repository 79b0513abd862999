//! Whether one sweep's files on disk are whole: read with every check of the reader (sizes agree,
//! values finite, labels agree with the object truth), and their SHA-256 against the digests a
//! finished sequence's marker records (`sequence.json`, `sweep_sha256`). `generate` uses it to
//! redo damaged sweeps on resume and to refuse a damaged sequence it would call complete.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::limits::{MAX_JSON_BYTES, read_limited};
use crate::record_files::{read_f32s, read_u16s, read_words};
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
    let velodyne = read_f32s(&sweep_path(dir, "velodyne", i, "bin"), 4, None)?;
    let n = velodyne.len() / 4;
    let labels_path = sweep_path(dir, "labels", i, "label");
    let labels: Vec<PointLabel> = read_words(&labels_path, 1, Some(n))?
        .into_iter()
        .map(PointLabel)
        .collect();
    let flow = read_f32s(&sweep_path(dir, "flow", i, "bin"), 3, Some(n))?;
    let time = read_f32s(&sweep_path(dir, "time", i, "bin"), 1, Some(n))?;
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

    #[test]
    fn the_scenario_hash_is_what_sha256sum_prints() {
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }
}
