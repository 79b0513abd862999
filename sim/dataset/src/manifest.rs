//! `manifest.json` and the per-sequence completion marker `sequence.json`.
//!
//! A sequence is complete when its marker exists: the writer creates it last, atomically. The
//! manifest is rebuilt from the markers, so shards that wrote into one folder merge by listing it
//! again (`Manifest::scan`), whatever order they finished in.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::atomic_file::write_atomic;
use crate::limits::{MAX_JSON_BYTES, read_limited};
use crate::{DatasetError, Result};

/// Name written into every manifest and marker, so foreign JSON files are recognised as such.
pub const FORMAT_NAME: &str = "patchflow-dataset";
/// Version of the on-disk format this build reads and writes.
pub const FORMAT_VERSION: u32 = 1;

/// What one finished sequence holds; also the content of its `sequence.json` marker.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SequenceInfo {
    /// Always [`FORMAT_NAME`].
    pub format: String,
    /// Format version, [`FORMAT_VERSION`] when written by this build.
    pub version: u32,
    /// Folder name under `sequences/`.
    pub name: String,
    /// Name of the scenario it was generated from.
    pub scenario: String,
    /// SHA-256 of the sequence's `scenario.toml` (the resolved scenario and the seed): what
    /// produced the data. Empty in markers written before it was recorded.
    #[serde(default)]
    pub scenario_sha256: String,
    /// Seed of every random stream of the run.
    pub seed: u64,
    /// Number of sweeps.
    pub sweeps: u32,
    /// Total number of points over all sweeps.
    pub points: u64,
    /// Sweep rate.
    pub rate_hz: f64,
    /// Program and version that wrote it, e.g. `patchflow 0.1.0`.
    pub generator: String,
    /// Per sweep, the SHA-256 of each of its files by folder (`velodyne`, `labels`, `flow`,
    /// `time`, `ring` if present, `objects`), recorded when the sequence was finished; what
    /// `generate` checks before it calls a sequence complete. Only in `sequence.json` (the
    /// manifest leaves it out); absent in markers of older builds.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sweep_sha256: Vec<BTreeMap<String, String>>,
}

/// The dataset's table of contents, `DIR/manifest.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// Always [`FORMAT_NAME`].
    pub format: String,
    /// Format version.
    pub version: u32,
    /// Finished sequences, sorted by name.
    pub sequences: Vec<SequenceInfo>,
}

impl Manifest {
    /// Lists the finished sequences under `root/sequences` from their markers, sorted by name.
    pub fn scan(root: &Path) -> Result<Self> {
        let seq_root = root.join("sequences");
        let mut sequences = Vec::new();
        if seq_root.is_dir() {
            let entries =
                std::fs::read_dir(&seq_root).map_err(|e| DatasetError::io(&seq_root, e))?;
            for entry in entries {
                let entry = entry.map_err(|e| DatasetError::io(&seq_root, e))?;
                let marker = entry.path().join("sequence.json");
                if marker.is_file() {
                    let info = read_marker(&marker)?;
                    if entry.file_name().to_str() != Some(info.name.as_str()) {
                        let reason = format!("names sequence {:?}, not its folder", info.name);
                        return Err(DatasetError::corrupt(&marker, reason));
                    }
                    sequences.push(SequenceInfo {
                        sweep_sha256: Vec::new(),
                        ..info
                    });
                }
            }
        }
        sequences.sort_by(|a, b| a.name.cmp(&b.name));
        Ok(Self {
            format: FORMAT_NAME.to_owned(),
            version: FORMAT_VERSION,
            sequences,
        })
    }

    /// Reads and checks `root/manifest.json`.
    pub fn read(root: &Path) -> Result<Self> {
        let path = root.join("manifest.json");
        let bytes = read_limited(&path, MAX_JSON_BYTES)?;
        let manifest: Self = serde_json::from_slice(&bytes)
            .map_err(|e| DatasetError::corrupt(&path, e.to_string()))?;
        check_format(&path, &manifest.format, manifest.version)?;
        Ok(manifest)
    }

    /// Writes `root/manifest.json` atomically.
    pub fn write(&self, root: &Path) -> Result<()> {
        write_json(&root.join("manifest.json"), self)
    }
}

/// Reads and checks one `sequence.json` marker.
pub(crate) fn read_marker(path: &Path) -> Result<SequenceInfo> {
    let bytes = read_limited(path, MAX_JSON_BYTES)?;
    let info: SequenceInfo =
        serde_json::from_slice(&bytes).map_err(|e| DatasetError::corrupt(path, e.to_string()))?;
    check_format(path, &info.format, info.version)?;
    Ok(info)
}

pub(crate) fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    let mut text = serde_json::to_string_pretty(value).map_err(|e| DatasetError::Invalid {
        path: path.to_owned(),
        reason: e.to_string(),
    })?;
    text.push('\n');
    write_atomic(path, text.as_bytes())
}

fn check_format(path: &Path, format: &str, version: u32) -> Result<()> {
    if format != FORMAT_NAME {
        return Err(DatasetError::corrupt(
            path,
            format!("format is {format:?}, expected {FORMAT_NAME:?}"),
        ));
    }
    if version != FORMAT_VERSION {
        return Err(DatasetError::Version {
            path: path.to_owned(),
            found: version,
            expected: FORMAT_VERSION,
        });
    }
    Ok(())
}
