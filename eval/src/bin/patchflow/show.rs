//! `patchflow show`: a PNG of one sweep'\''s reflection and difference maps with clusters and true boxes.

use std::path::PathBuf;

/// Arguments of `patchflow show`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Dataset folder.
    #[arg(long)]
    pub data: PathBuf,
    /// Sequence name (default: the first one).
    #[arg(long)]
    pub sequence: Option<String>,
    /// Sweep index (must be at least 1: the difference needs the previous sweep).
    #[arg(long, default_value_t = 1)]
    pub scan: usize,
    /// PNG file to write.
    #[arg(long)]
    pub out: PathBuf,
}

/// Runs `patchflow show`.
pub fn run(args: Args) -> anyhow::Result<()> {
    anyhow::bail!("patchflow show is not built yet ({args:?})")
}
