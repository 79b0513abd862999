//! `patchflow evaluate`: every method on the situations of a dataset; metrics, tables and plots.

use std::path::PathBuf;

use anyhow::Context;
use patchflow_dataset::Dataset;
use patchflow_eval::stages::evaluate_with_bar;
use patchflow_eval::{PerceptionSummary, write_dataset_scene_figures, write_report_with};
use patchflow_learn::MotionEstimator;

use crate::common::{DataAndReport, load_models};
use crate::output_guard::Input;

/// Arguments of `patchflow evaluate`.
#[derive(Debug, clap::Args)]
#[command(mut_arg("data", |a| a.help(
    "Dataset folder holding the situations (sequences with an actor marked `target`)"
)))]
pub struct Args {
    /// Trained model file (from `patchflow train`); repeat to compare several (e.g. SPGP and SPGP-HET).
    #[arg(long, required = true)]
    pub model: Vec<PathBuf>,
    #[command(flatten)]
    pub io: DataAndReport,
}

/// Runs `patchflow evaluate`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let models: Vec<Input<'_>> = args
        .model
        .iter()
        .map(|m| Input::new("--model", m))
        .collect();
    args.io.check_output(&models)?;
    let (estimators, moving) = load_models(&args.model)?;
    let dataset = Dataset::open(&args.io.data)?;
    let mut report =
        evaluate_with_bar(&dataset, &estimators, moving.as_ref()).with_context(|| {
            let models: Vec<String> = args.model.iter().map(|m| m.display().to_string()).collect();
            format!("evaluating with model {}", models.join(", "))
        })?;
    let names: Vec<String> = report.situations.iter().map(|s| s.name.clone()).collect();
    report.scene_figures =
        write_dataset_scene_figures(&dataset, &names, &args.io.out.join("plots"))?;
    let files = write_report_with(&report, provenance(&args.model, &estimators), &args.io.out)?;
    if let Some(all) = PerceptionSummary::of_scenes(&report.scenes).last() {
        println!("perception: {}", all.line());
    }
    println!("wrote {}", files.report_md.display());
    Ok(())
}

/// The pseudo-inputs the model's GPs actually have (the most of the three; a sparse GP takes
/// no more than its samples, so `--pseudo 100000` on 100 samples uses 100).
pub fn pseudo_inputs_used(estimator: &MotionEstimator) -> usize {
    estimator
        .gps()
        .iter()
        .map(|gp| gp.fit_report().m)
        .max()
        .unwrap_or(0)
}

/// What produced the numbers: the model files as given, each model's training seed and data.
fn provenance(
    paths: &[PathBuf],
    estimators: &[MotionEstimator],
) -> serde_json::Map<String, serde_json::Value> {
    let models: Vec<serde_json::Value> = paths
        .iter()
        .zip(estimators)
        .map(|(path, e)| {
            let training = e.training();
            serde_json::json!({
                "file": path.display().to_string(),
                "gp": e.gp_kind().to_string(),
                "seed": training.seed,
                "samples": training.samples,
                "pseudo_inputs": pseudo_inputs_used(e),
                "pseudo_inputs_requested": training.pseudo_inputs,
                "training_sequences": training.sequences,
            })
        })
        .collect();
    let seeds: Vec<u64> = estimators.iter().map(|e| e.training().seed).collect();
    let mut entries = serde_json::Map::new();
    entries.insert("models".into(), serde_json::json!(models));
    entries.insert("seeds".into(), serde_json::json!(seeds));
    entries
}
