//! `patchflow score`: prediction folders of any method (the layout `patchflow flow` writes) scored
//! against a dataset by the code that scores the built-in methods
//! ([`patchflow_eval::score_predictions`]), with the built-in methods beside them when models are
//! given.

use std::path::PathBuf;

use patchflow_dataset::Dataset;
use patchflow_eval::progress::progress_bar;
use patchflow_eval::{PredictionFolder, scans_to_evaluate, score_predictions};

use crate::common::{DataAndReport, load_models};
use crate::output_guard::Input;

/// Arguments of `patchflow score`.
#[derive(Debug, clap::Args)]
#[command(mut_arg("data", |a| a.help("Dataset folder the predictions were made on")))]
#[command(mut_arg("out", |a| a.help(
    "Report folder to write (`metrics.json`, `tables.csv`, `report.md`)"
)))]
pub struct Args {
    #[command(flatten)]
    pub io: DataAndReport,
    /// A prediction folder, `PATH` or `PATH=NAME` (`sequences/<name>/flow/NNNNNN.bin`: float32
    /// vx, vy, vz per point, world frame, m/s, NaN where no prediction; optional
    /// `sequences/<name>/moving/NNNNNN.bin`, one uint8 per point). Repeat for several methods.
    #[arg(long, required = true)]
    pub predictions: Vec<String>,
    /// Trained model file: its built-in methods are evaluated and reported beside, and its
    /// features decide the scored points. Repeat for several GP kinds.
    #[arg(long)]
    pub model: Vec<PathBuf>,
}

/// Runs `patchflow score`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let folders = args
        .predictions
        .iter()
        .map(|a| PredictionFolder::parse(a))
        .collect::<Result<Vec<_>, _>>()?;
    let inputs: Vec<Input<'_>> = (folders.iter().map(|f| Input::new("--predictions", &f.root)))
        .chain(args.model.iter().map(|m| Input::new("--model", m)))
        .collect();
    args.io.check_output(&inputs)?;
    let (estimators, moving) = load_models(&args.model)?;
    let dataset = Dataset::open(&args.io.data)?;
    let passes = 1 + u64::from(!estimators.is_empty());
    let bar = progress_bar(scans_to_evaluate(&dataset)? * passes, "scoring scans");
    let report = score_predictions(&dataset, &folders, &estimators, moving.as_ref(), &|| {
        bar.inc(1)
    });
    bar.finish_and_clear();
    let files = report?.write(&args.io.out)?;
    println!("wrote {}", files.report_md.display());
    Ok(())
}
