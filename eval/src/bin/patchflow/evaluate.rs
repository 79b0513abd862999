//! `patchflow evaluate`: every method on the situations of a dataset; metrics, tables and plots.

use std::path::PathBuf;

use anyhow::Context;
use patchflow_dataset::Dataset;
use patchflow_eval::{
    BaselineParams, GpMethod, PerceptionTiming, evaluate_dataset, method_prefix, progress_bar,
    scans_to_evaluate, write_report,
};
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
    let methods = gp_methods(&estimators)?;
    let dataset = Dataset::open(&args.data)?;
    let (report, perception) = evaluate_with_bar(&dataset, &methods)?;
    let files = write_report(&report, &args.out)?;
    println!("perception: {}", perception.summary());
    println!("wrote {}", files.report_md.display());
    Ok(())
}

/// One method per estimator, named after its GP kind; two estimators of one kind are an error.
pub fn gp_methods(estimators: &[MotionEstimator]) -> anyhow::Result<Vec<GpMethod<'_>>> {
    let mut methods: Vec<GpMethod<'_>> = Vec::new();
    for estimator in estimators {
        let prefix = method_prefix(estimator.gp_kind());
        anyhow::ensure!(
            !methods.iter().any(|m| m.prefix == prefix),
            "two models of kind {prefix}: give one per GP kind"
        );
        methods.push(GpMethod { prefix, estimator });
    }
    Ok(methods)
}

/// Evaluates the dataset's situations with a progress bar over the scans.
pub fn evaluate_with_bar(
    dataset: &Dataset,
    methods: &[GpMethod<'_>],
) -> anyhow::Result<(patchflow_eval::BenchmarkReport, PerceptionTiming)> {
    let bar = progress_bar(scans_to_evaluate(dataset)?, "evaluating scans");
    let result = evaluate_dataset(dataset, methods, &BaselineParams::default(), &|| bar.inc(1));
    bar.finish_and_clear();
    Ok(result?)
}
