//! `patchflow evaluate`: every method on the five situations; metrics, tables and plots.

use std::path::PathBuf;

/// Arguments of `patchflow evaluate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Trained model file (from `patchflow train`).
    #[arg(long)]
    pub model: PathBuf,
    /// Dataset folder holding the situations.
    #[arg(long)]
    pub data: PathBuf,
    /// Report folder to write.
    #[arg(long)]
    pub out: PathBuf,
}

/// Runs `patchflow evaluate`.
pub fn run(args: Args) -> anyhow::Result<()> {
    anyhow::bail!("patchflow evaluate is not built yet ({args:?})")
}
