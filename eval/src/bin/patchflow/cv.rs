//! `patchflow cv`: K-fold cross-validation tables after thesis Tables 4.1 to 4.4.

use std::path::PathBuf;

/// Arguments of `patchflow cv`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Dataset folder.
    #[arg(long)]
    pub data: PathBuf,
    /// Report folder to write.
    #[arg(long)]
    pub out: PathBuf,
    /// Number of folds.
    #[arg(long, default_value_t = 5)]
    pub folds: usize,
}

/// Runs `patchflow cv`.
pub fn run(args: Args) -> anyhow::Result<()> {
    anyhow::bail!("patchflow cv is not built yet ({args:?})")
}
