//! `patchflow train`: train the motion estimator on a dataset.

use std::path::PathBuf;

/// Arguments of `patchflow train`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Dataset folder.
    #[arg(long)]
    pub data: PathBuf,
    /// Model file to write.
    #[arg(long)]
    pub out: PathBuf,
    /// GP kind: `spgp`, `spgp-het` or `full`.
    #[arg(long, default_value = "spgp-het")]
    pub gp: String,
    /// Feature kind: `patch` or `gabor`.
    #[arg(long, default_value = "patch")]
    pub feature: String,
    /// Map prior for unobserved cells.
    #[arg(long, default_value_t = 0.5)]
    pub prior: f64,
    /// Training samples per GP.
    #[arg(long, default_value_t = 1600)]
    pub samples: usize,
    /// Pseudo-inputs per sparse GP.
    #[arg(long, default_value_t = 100)]
    pub pseudo: usize,
    /// Seed of sampling and initialisation.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

/// Runs `patchflow train`.
pub fn run(args: Args) -> anyhow::Result<()> {
    anyhow::bail!("patchflow train is not built yet ({args:?})")
}
