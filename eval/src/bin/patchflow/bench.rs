//! `patchflow bench`: the main job: generate, train, cross-validate, evaluate, report.

use std::path::PathBuf;

/// Arguments of `patchflow bench`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output folder.
    #[arg(long, default_value = "results/bench")]
    pub out: PathBuf,
    /// A smaller run (fewer sweeps, samples and folds) for a quick look.
    #[arg(long)]
    pub quick: bool,
}

/// Runs `patchflow bench`.
pub fn run(args: Args) -> anyhow::Result<()> {
    anyhow::bail!("patchflow bench is not built yet ({args:?})")
}
