//! `patchflow cv`: K-fold cross-validation tables after thesis Tables 4.1 to 4.4.

use std::path::PathBuf;

use patchflow_dataset::Dataset;
use patchflow_eval::{
    CvParams, CvReport, cross_validate, cross_validate_samples, progress_bar, write_cv_report,
};
use patchflow_learn::SampleSet;

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
    let dataset = Dataset::open(&args.data)?;
    let params = CvParams {
        folds: args.folds,
        ..CvParams::default()
    };
    let report = cv_with_bar(&dataset, &params)?;
    write_cv_report(&report, &args.out)?;
    println!("wrote {}", args.out.join("cv.md").display());
    Ok(())
}

/// Cross-validates with a progress bar over configurations × folds.
pub fn cv_with_bar(dataset: &Dataset, params: &CvParams) -> anyhow::Result<CvReport> {
    let bar = progress_bar(0, "cross-validation");
    let report = cross_validate(dataset, params, &|done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    });
    bar.finish_and_clear();
    Ok(report?)
}

/// Cross-validates sample sets already drawn (one per prior), with a progress bar.
pub fn cv_with_samples(sets: &[SampleSet], params: &CvParams) -> anyhow::Result<CvReport> {
    let bar = progress_bar(0, "cross-validation");
    let report = cross_validate_samples(sets, params, &|done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    });
    bar.finish_and_clear();
    Ok(report?)
}
