//! `patchflow cv`: K-fold cross-validation tables after thesis Tables 4.1 to 4.4.

use std::path::PathBuf;

use patchflow_dataset::Dataset;
use patchflow_eval::{CvParams, CvReport, cross_validate_samples, progress_bar, write_cv_report};
use patchflow_learn::{FeatureKind, FeatureParams, SampleSet};

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
    let sets = collect_samples(&dataset, &params.priors, params.samples, params.seed)?;
    let report = cv_with_samples(&sets, &params)?;
    write_cv_report(&report, &args.out)?;
    println!("wrote {}", args.out.join("cv.md").display());
    Ok(())
}

/// Importance-samples map patches for several priors in one pass over the dataset, with a
/// progress bar (thesis 3.1.2; the maps of all priors share their beam tracing).
pub fn collect_samples(
    dataset: &Dataset,
    priors: &[f64],
    n: usize,
    seed: u64,
) -> anyhow::Result<Vec<SampleSet>> {
    let bar = progress_bar(0, "sampling patches");
    let sets = SampleSet::collect_priors(
        dataset,
        &FeatureParams::default(),
        priors,
        FeatureKind::Patch,
        n,
        seed,
        &|done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        },
    );
    bar.finish_and_clear();
    Ok(sets?)
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
