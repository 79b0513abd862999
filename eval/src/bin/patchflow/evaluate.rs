//! `patchflow evaluate`: every method on the situations of a dataset; metrics, tables and plots.

use std::path::PathBuf;

use anyhow::Context;
use patchflow_dataset::Dataset;
use patchflow_eval::stages::evaluate_with_bar;
use patchflow_eval::{PerceptionSummary, write_report};
use patchflow_learn::MotionEstimator;

/// Arguments of `patchflow evaluate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Trained model file (from `patchflow train`); repeat to compare several (e.g. SPGP and SPGP-HET).
    #[arg(long, required = true)]
    pub model: Vec<PathBuf>,
    /// Dataset folder holding the situations (sequences with an actor marked `target`).
    #[arg(long)]
    pub data: PathBuf,
    /// Report folder to write.
    #[arg(long)]
    pub out: PathBuf,
}

/// Runs `patchflow evaluate`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let estimators = args
        .model
        .iter()
        .map(|path| {
            MotionEstimator::load(path).with_context(|| format!("loading model {}", path.display()))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let dataset = Dataset::open(&args.data)?;
    let report = evaluate_with_bar(&dataset, &estimators)?;
    let files = write_report(&report, &args.out)?;
    if let Some(all) = PerceptionSummary::of_scenes(&report.scenes).last() {
        println!("perception: {}", all.line());
    }
    println!("wrote {}", files.report_md.display());
    Ok(())
}
