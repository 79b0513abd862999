//! The arguments the report commands (`cv`, `evaluate`, `occupancy`, `score`) share: the dataset
//! they read and the report folder they write, declared once and flattened into each; a command
//! whose dataset needs more words names it with `mut_arg` (see `evaluate.rs`).

use std::path::PathBuf;

use anyhow::Context;
use patchflow_learn::{MOVING_FILE_NAME, MotionEstimator, MovingClassifier};

use crate::output_guard::{Input, OutputKind, check_output};

/// `--data DIR --out REPORT_DIR`.
#[derive(Debug, clap::Args)]
pub struct DataAndReport {
    /// Dataset folder.
    #[arg(long)]
    pub data: PathBuf,
    /// Report folder to write.
    #[arg(long)]
    pub out: PathBuf,
}

impl DataAndReport {
    /// Refuses a report folder that would overwrite the dataset or any of `more_inputs`.
    pub fn check_output(&self, more_inputs: &[Input<'_>]) -> anyhow::Result<()> {
        let mut inputs = vec![Input::new("--data", &self.data)];
        inputs.extend_from_slice(more_inputs);
        check_output(&self.out, OutputKind::Folder, &inputs)
    }
}

/// The trained models given with `--model`, and the moving classifier `patchflow train` writes
/// beside the first of them, if it is there.
pub fn load_models(
    paths: &[PathBuf],
) -> anyhow::Result<(Vec<MotionEstimator>, Option<MovingClassifier>)> {
    let estimators = paths
        .iter()
        .map(|path| {
            MotionEstimator::load(path).with_context(|| format!("loading model {}", path.display()))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let moving = match paths.first().map(|m| m.with_file_name(MOVING_FILE_NAME)) {
        Some(path) if path.exists() => Some(
            MovingClassifier::load(&path).with_context(|| format!("loading {}", path.display()))?,
        ),
        _ => None,
    };
    Ok((estimators, moving))
}
