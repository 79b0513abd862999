//! Evaluates every sequence of a dataset (thesis 4.4 and the whole scene): the library entry
//! point behind `patchflow evaluate` and the evaluation stage of `patchflow bench`.

use patchflow_dataset::{Dataset, SequenceReader};
use patchflow_learn::{MotionEstimator, MovingClassifier};

use crate::error::EvalError;
use crate::methods::baselines::baseline_params::BaselineParams;
use crate::report::benchmark_report::BenchmarkReport;
use crate::scene::scene_evaluation::evaluate_sequence;

/// The sequences [`evaluate_dataset`] evaluates: every one with at least two sweeps, in the
/// dataset's order. Those marking a target also get the per-target tables and come first in
/// the whole-scene results.
pub fn sequences_to_evaluate(dataset: &Dataset) -> Result<Vec<String>, EvalError> {
    let names: Vec<String> = dataset
        .sequences()
        .iter()
        .filter(|info| info.sweeps >= 2)
        .map(|info| info.name.clone())
        .collect();
    if names.is_empty() {
        return Err(EvalError::BadResult {
            situation: dataset.root().display().to_string(),
            reason: "no sequence has at least two sweeps".into(),
        });
    }
    Ok(names)
}

/// Number of scans [`evaluate_dataset`] will evaluate (every sweep but the first of each sequence).
pub fn scans_to_evaluate(dataset: &Dataset) -> Result<u64, EvalError> {
    let mut total = 0;
    for name in sequences_to_evaluate(dataset)? {
        total += dataset.sequence(&name)?.len().saturating_sub(1) as u64;
    }
    Ok(total)
}

/// Evaluates every sequence of a dataset with the given estimators (one per GP kind), the
/// moving classifier when given (the `+MOS` read-outs; GP-KF and GP-ICP take its decision),
/// GP-KF, GP-ICP and the four baselines, scans in order; `on_scan` is called once per scan
/// evaluated.
///
/// ```no_run
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// use std::path::Path;
/// use patchflow_eval::{BaselineParams, evaluate_dataset, write_report};
/// let estimator = patchflow_learn::MotionEstimator::load(Path::new("models/spgp-het.json"))?;
/// let dataset = patchflow_dataset::Dataset::open(Path::new("data/situations"))?;
/// let report = evaluate_dataset(&dataset, &[estimator], &BaselineParams::default(), None, &|| {})?;
/// write_report(&report, Path::new("report"))?;
/// # Ok(())
/// # }
/// ```
pub fn evaluate_dataset(
    dataset: &Dataset,
    estimators: &[MotionEstimator],
    baselines: &BaselineParams,
    moving: Option<&MovingClassifier>,
    on_scan: &(dyn Fn() + Sync),
) -> Result<BenchmarkReport, EvalError> {
    for (k, e) in estimators.iter().enumerate() {
        if estimators[..k].iter().any(|o| o.gp_kind() == e.gp_kind()) {
            return Err(EvalError::BadParameter {
                name: "estimators",
                reason: format!("two models of kind {}: give one per GP kind", e.gp_kind()),
            });
        }
    }
    let mut report = BenchmarkReport::default();
    for name in sequences_to_evaluate(dataset)? {
        let sequence = dataset.sequence(&name)?;
        if let Some(description) = description_of(&sequence) {
            report.descriptions.insert(name.clone(), description);
        }
        let run = evaluate_sequence(&sequence, estimators, baselines, moving, on_scan)?;
        report.situations.extend(run.target);
        report.scenes.push(run.scene);
    }
    // The situations first, in dataset order, then the sequences without a target.
    let situations: Vec<String> = report.situations.iter().map(|s| s.name.clone()).collect();
    report
        .scenes
        .sort_by_key(|scene| !situations.contains(&scene.name));
    Ok(report)
}

/// The `description` of the scenario a sequence was generated from, when it states one.
fn description_of(sequence: &SequenceReader) -> Option<String> {
    let text = sequence.scenario_toml().ok()?;
    let name = &sequence.info().name;
    let scenario = patchflow_sim::Scenario::from_toml(&text, "scenario.toml", name).ok()?;
    let description = scenario.description.trim();
    (!description.is_empty()).then(|| description.to_owned())
}
