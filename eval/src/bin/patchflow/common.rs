//! The arguments the report commands (`cv`, `evaluate`, `occupancy`, `score`) share: the dataset
//! they read and the report folder they write, declared once and flattened into each; a command
//! whose dataset needs more words names it with `mut_arg` (see `evaluate.rs`).

use std::path::PathBuf;

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
