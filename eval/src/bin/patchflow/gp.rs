//! `patchflow gp fit` and `patchflow gp predict`: Gaussian-process regression on any CSV.

use std::path::PathBuf;

/// Arguments of `patchflow gp`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(subcommand)]
    command: GpCommand,
}

#[derive(Debug, clap::Subcommand)]
enum GpCommand {
    /// Fit a GP to a CSV with a header: all columns but the last are inputs, the last is the target.
    Fit(FitArgs),
    /// Predict with a fitted model at the inputs of a CSV; writes `mean,var,var_y`.
    Predict(PredictArgs),
}

/// Arguments of `patchflow gp fit`.
#[derive(Debug, clap::Args)]
struct FitArgs {
    /// Training CSV.
    #[arg(long)]
    csv: PathBuf,
    /// Model file to write.
    #[arg(long)]
    out: PathBuf,
    /// `full`, `spgp` or `spgp-het`.
    #[arg(long, default_value = "spgp")]
    kind: String,
    /// Number of pseudo-inputs.
    #[arg(long, default_value_t = 100)]
    pseudo: usize,
    /// Optimiser iteration limit.
    #[arg(long, default_value_t = 200)]
    iters: usize,
    /// Seed of the initialisation.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Target column name (default: the last column).
    #[arg(long)]
    target: Option<String>,
    /// Comma-separated column names to leave out of the inputs.
    #[arg(long)]
    ignore: Option<String>,
}

/// Arguments of `patchflow gp predict`.
#[derive(Debug, clap::Args)]
struct PredictArgs {
    /// Model file from `gp fit`.
    #[arg(long)]
    model: PathBuf,
    /// CSV with the model's input columns.
    #[arg(long)]
    csv: PathBuf,
    /// Output CSV (default: standard output).
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Runs `patchflow gp ...`.
pub fn run(args: Args) -> anyhow::Result<()> {
    anyhow::bail!("patchflow gp is not built yet ({args:?})")
}
