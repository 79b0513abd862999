//! A folder of another method's predictions in the layout `patchflow flow` writes (SPEC §7):
//! `sequences/<name>/flow/NNNNNN.bin` (float32 vx, vy, vz per point, world frame, m/s; NaN where
//! the method predicts nothing) and optionally `sequences/<name>/moving/NNNNNN.bin` (one uint8
//! per point, 1 for moving). Every read checks the file against the dataset's sweep, so that a
//! wrong folder or a broken file is an error naming it, never a silently wrong score.

use std::path::{Path, PathBuf};

use patchflow_dataset::Dataset;

use crate::error::EvalError;

/// Above this speed a predicted velocity is no road user's (m/s): a unit or frame mistake.
pub const MAX_PREDICTED_SPEED_MPS: f32 = 1.0e3;

/// One prediction folder and the method name it is reported under.
#[derive(Debug, Clone, PartialEq)]
pub struct PredictionFolder {
    /// Method name in the tables (the folder's name unless given as `PATH=NAME`).
    pub name: String,
    /// The folder.
    pub root: PathBuf,
}

impl PredictionFolder {
    /// Parses a command-line argument `PATH` or `PATH=NAME`.
    ///
    /// ```
    /// use patchflow_eval::PredictionFolder;
    /// let f = PredictionFolder::parse("runs/nsfp=NSFP").unwrap();
    /// assert_eq!((f.name.as_str(), f.root.to_str().unwrap()), ("NSFP", "runs/nsfp"));
    /// assert_eq!(PredictionFolder::parse("runs/nn/").unwrap().name, "nn");
    /// ```
    pub fn parse(argument: &str) -> Result<Self, EvalError> {
        let (path, name) = match argument.rsplit_once('=') {
            Some((path, name)) => (path, Some(name.trim().to_owned())),
            None => (argument, None),
        };
        let root = PathBuf::from(path);
        let name = name
            .or_else(|| root.file_name().map(|n| n.to_string_lossy().into_owned()))
            .unwrap_or_default();
        if name.is_empty() || name.len() > 40 || name.chars().any(char::is_control) {
            return Err(EvalError::BadParameter {
                name: "predictions",
                reason: format!("{argument:?}: give the folder as PATH=NAME with a short name"),
            });
        }
        Ok(Self { name, root })
    }

    /// Checks that the folder holds the sequences `names` of `dataset` and nothing else: a
    /// sequence the dataset lacks means the predictions were made on another dataset.
    pub fn check_against(&self, dataset: &Dataset, names: &[String]) -> Result<(), EvalError> {
        let sequences = self.root.join("sequences");
        let entries = std::fs::read_dir(&sequences).map_err(|e| EvalError::BadFile {
            path: sequences.clone(),
            reason: format!("not a prediction folder ({e}): expected sequences/<name>/flow/"),
        })?;
        let mut found = Vec::new();
        for entry in entries {
            let entry = entry.map_err(|e| EvalError::io(&sequences, e))?;
            found.push(entry.file_name().to_string_lossy().into_owned());
        }
        found.sort();
        if let Some(stranger) = found
            .iter()
            .find(|n| !dataset.sequences().iter().any(|s| &s.name == *n))
        {
            return Err(EvalError::BadFile {
                path: sequences.join(stranger),
                reason: format!(
                    "the dataset {} has no sequence {stranger:?}: predictions of another dataset?",
                    dataset.root().display()
                ),
            });
        }
        if let Some(missing) = names.iter().find(|n| !found.contains(n)) {
            return Err(EvalError::BadFile {
                path: sequences.join(missing),
                reason: "missing: every evaluated sequence of the dataset needs predictions".into(),
            });
        }
        Ok(())
    }

    /// The predicted velocities of sweep `index` of `sequence`, which has `points` points.
    pub fn read_flow(
        &self,
        sequence: &str,
        index: usize,
        points: usize,
    ) -> Result<Vec<[f32; 3]>, EvalError> {
        let path = self.file(sequence, "flow", index);
        let bytes = read_sized(&path, points * 12, "12 bytes (3 float32) per point", points)?;
        let flow: Vec<[f32; 3]> = bytes
            .chunks_exact(12)
            .map(|c| {
                let f = |k: usize| f32::from_le_bytes([c[k], c[k + 1], c[k + 2], c[k + 3]]);
                [f(0), f(4), f(8)]
            })
            .collect();
        if let Some(i) = flow.iter().position(|v| v.iter().any(|c| c.is_infinite())) {
            return Err(bad(&path, format!("point {i} has an infinite velocity")));
        }
        let too_fast = |v: &[f32; 3]| v.iter().any(|c| c.abs() > MAX_PREDICTED_SPEED_MPS);
        if let Some(i) = flow.iter().position(too_fast) {
            return Err(bad(
                &path,
                format!(
                    "point {i} moves at {:?} m/s, above {MAX_PREDICTED_SPEED_MPS} m/s: \
                     velocities are m/s in the world frame",
                    flow[i]
                ),
            ));
        }
        if points > 0 && flow.iter().all(|v| v.iter().any(|c| c.is_nan())) {
            return Err(bad(
                &path,
                "holds no prediction (every value NaN): write 0 for points predicted static".into(),
            ));
        }
        Ok(flow)
    }

    /// The moving mask of sweep `index`, when the folder has `moving/` for the sequence.
    pub fn read_moving(
        &self,
        sequence: &str,
        index: usize,
        points: usize,
    ) -> Result<Option<Vec<bool>>, EvalError> {
        if !self
            .root
            .join("sequences")
            .join(sequence)
            .join("moving")
            .is_dir()
        {
            return Ok(None);
        }
        let path = self.file(sequence, "moving", index);
        let bytes = read_sized(&path, points, "one uint8 per point", points)?;
        if let Some(i) = bytes.iter().position(|&b| b > 1) {
            return Err(bad(
                &path,
                format!("point {i} has {}: 0 (static) or 1 (moving)", bytes[i]),
            ));
        }
        Ok(Some(bytes.into_iter().map(|b| b == 1).collect()))
    }

    fn file(&self, sequence: &str, kind: &str, index: usize) -> PathBuf {
        self.root
            .join("sequences")
            .join(sequence)
            .join(kind)
            .join(format!("{index:06}.bin"))
    }
}

/// Reads a file that must hold exactly `expected` bytes.
fn read_sized(
    path: &Path,
    expected: usize,
    layout: &str,
    points: usize,
) -> Result<Vec<u8>, EvalError> {
    let meta = std::fs::metadata(path).map_err(|e| bad(path, format!("cannot be read: {e}")))?;
    if !meta.is_file() {
        return Err(bad(path, "is not a regular file".into()));
    }
    if meta.len() != expected as u64 {
        return Err(bad(
            path,
            format!(
                "has {} bytes where the dataset's sweep of {points} points needs {expected} \
                 ({layout})",
                meta.len()
            ),
        ));
    }
    std::fs::read(path).map_err(|e| EvalError::io(path, e))
}

fn bad(path: &Path, reason: String) -> EvalError {
    EvalError::BadFile {
        path: path.to_owned(),
        reason,
    }
}
