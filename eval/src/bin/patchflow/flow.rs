//! `patchflow flow`: a trained estimator's per-point scene flow for every sweep of a dataset,
//! written beside the dataset's layout (`OUT/sequences/<name>/flow/NNNNNN.bin`) for other tools.

use std::path::PathBuf;

use anyhow::Context;
use patchflow_dataset::Dataset;
use patchflow_eval::progress::progress_bar;
use patchflow_eval::{GpReadout, export_flow};
use patchflow_learn::MotionEstimator;

use crate::choices::ReadoutChoice;
use crate::output_guard::{Input, OutputKind, check_output};

/// Arguments of `patchflow flow`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Dataset folder.
    #[arg(long)]
    pub data: PathBuf,
    /// Trained model file (from `patchflow train`).
    #[arg(long)]
    pub model: PathBuf,
    /// Folder to write (`sequences/<name>/flow/NNNNNN.bin`: float32 vx, vy, vz per point, world
    /// frame, m/s, as the dataset's own `flow/`; NaN where the pipeline sees no point).
    #[arg(long)]
    pub out: PathBuf,
    /// How clusters move their points: `all` or `best` (the merged estimate, thesis 3.1.4), or
    /// `point` (each point its own prediction).
    #[arg(long, value_enum, default_value_t = ReadoutChoice::All)]
    pub readout: ReadoutChoice,
}

/// Runs `patchflow flow`.
pub fn run(args: Args) -> anyhow::Result<()> {
    check_output(
        &args.out,
        OutputKind::Folder,
        &[
            Input::new("--data", &args.data),
            Input::new("--model", &args.model),
        ],
    )?;
    let readout: GpReadout = args.readout.into();
    let estimator = MotionEstimator::load(&args.model)
        .with_context(|| format!("loading model {}", args.model.display()))?;
    let dataset = Dataset::open(&args.data)?;
    let sweeps: u64 = dataset
        .sequences()
        .iter()
        .map(|s| u64::from(s.sweeps))
        .sum();
    let bar = progress_bar(sweeps, "exporting flow");
    let written = export_flow(&dataset, &estimator, readout, &args.out, &|| bar.inc(1));
    bar.finish_and_clear();
    println!(
        "wrote the flow of {} sweeps into {}",
        written?,
        args.out.display()
    );
    Ok(())
}
