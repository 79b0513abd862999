//! `patchflow cv`: K-fold cross-validation tables after thesis Tables 4.1 to 4.4.

use patchflow_dataset::Dataset;
use patchflow_eval::stages::{collect_samples_with_bar, cross_validate_with_bar};
use patchflow_eval::{CvParams, write_cv_report};
use patchflow_learn::EstimatorParams;

use crate::choices::PresetChoice;
use crate::common::DataAndReport;

/// Arguments of `patchflow cv`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub io: DataAndReport,
    /// Number of folds.
    #[arg(long, default_value_t = 5)]
    pub folds: usize,
    /// Whose training set to cross-validate: `default` (what `train` and `bench` train on: the
    /// default's slice and patch maps, with mirror images) or `thesis` (`train --preset thesis`).
    #[arg(long, value_enum, default_value_t = PresetChoice::Default)]
    pub preset: PresetChoice,
}

/// Runs `patchflow cv`.
pub fn run(args: Args) -> anyhow::Result<()> {
    args.io.check_output(&[])?;
    let dataset = Dataset::open(&args.io.data)?;
    let preset = EstimatorParams::from(args.preset);
    let params = CvParams {
        folds: args.folds,
        mirror_images: preset.mirror_images,
        ..CvParams::default()
    };
    let sets = collect_samples_with_bar(
        &dataset,
        &preset.features,
        &params.priors,
        params.samples,
        params.seed,
    )?;
    let report = cross_validate_with_bar(&sets, &params)?;
    write_cv_report(&report, &args.io.out)?;
    println!("wrote {}", args.io.out.join("cv.md").display());
    Ok(())
}
