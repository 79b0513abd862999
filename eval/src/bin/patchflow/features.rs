//! `patchflow features`: importance-sampled patch or Gabor features with motion targets, as a CSV.

use std::path::PathBuf;

/// Arguments of `patchflow features`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Dataset folder.
    #[arg(long)]
    pub data: PathBuf,
    /// CSV file to write.
    #[arg(long)]
    pub out: PathBuf,
    /// Feature kind: `patch` (242 map values) or `gabor` (16 filter responses).
    #[arg(long, default_value = "patch")]
    pub feature: String,
    /// Map prior for unobserved cells.
    #[arg(long, default_value_t = 0.5)]
    pub prior: f64,
    /// Number of samples drawn by importance sampling.
    #[arg(long, default_value_t = 1600)]
    pub samples: usize,
    /// Seed of the sampling.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

/// Runs `patchflow features`.
pub fn run(args: Args) -> anyhow::Result<()> {
    anyhow::bail!("patchflow features is not built yet ({args:?})")
}
