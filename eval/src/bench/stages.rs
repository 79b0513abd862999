//! The benchmark's long stages with progress on the terminal (indicatif bars on stderr, hidden
//! when stderr is not a terminal); `patchflow generate`, `cv` and `evaluate` run them too.

use std::collections::HashMap;
use std::sync::Mutex;

use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use patchflow_dataset::{Dataset, Manifest};
use patchflow_learn::{FeatureKind, FeatureParams, MotionEstimator, SampleSet};
use patchflow_occupancy::{OccupancyParams, OccupancySequence};
use patchflow_sim::{GenerateOptions, Progress, ScenarioSource, generate_dataset};

use crate::baseline_params::BaselineParams;
use crate::cross_validation::cross_validate_samples;
use crate::cv_params::CvParams;
use crate::dataset_evaluation::{evaluate_dataset, scans_to_evaluate};
use crate::error::EvalError;
use crate::occupancy::{
    OccupancyReport, evaluate_occupancy, occupancy_methods, occupancy_notes, occupancy_sequences,
};
use crate::progress::progress_bar;
use crate::report::CvReport;
use crate::result::BenchmarkReport;

/// Simulates scenarios into a dataset with one progress bar per sequence.
pub fn generate_with_progress(
    sources: &[ScenarioSource],
    options: &GenerateOptions,
) -> Result<Manifest, EvalError> {
    let bars = MultiProgress::new();
    let style = ProgressStyle::with_template(
        "{prefix:>12} [{bar:40}] {pos}/{len} sweeps {elapsed} (eta {eta}) {msg}",
    )
    .unwrap_or_else(|_| ProgressStyle::default_bar())
    .progress_chars("=> ");
    let open: Mutex<HashMap<String, ProgressBar>> = Mutex::new(HashMap::new());
    let on_progress = |event: Progress| {
        let Ok(mut open) = open.lock() else { return };
        match event {
            Progress::Waiting { name } => {
                let _ = bars.println(format!(
                    "{name:>12} is being written by another run; waiting for it"
                ));
            }
            Progress::SequenceStarted { name, sweeps } => {
                let bar = bars.add(
                    ProgressBar::new(u64::from(sweeps))
                        .with_style(style.clone())
                        .with_prefix(name.clone()),
                );
                open.insert(name, bar);
            }
            Progress::SweepDone { name, points, .. } => {
                if let Some(bar) = open.get(&name) {
                    bar.inc(1);
                    if points > 0 {
                        bar.set_message(format!("{points} points"));
                    }
                }
            }
            Progress::SequenceDone { name, skipped } => match open.remove(&name) {
                Some(bar) => bar.finish_with_message("done"),
                None if skipped => {
                    let _ = bars.println(format!("{name:>12} already complete, skipped"));
                }
                None => {}
            },
        }
    };
    generate_dataset(sources, options, &on_progress).map_err(|source| EvalError::Sim {
        out: options.out.clone(),
        source,
    })
}

/// Importance-samples map patches for several priors in one pass over the dataset (thesis
/// 3.1.2; the maps of all priors share their beam tracing), with a progress bar.
pub fn collect_samples_with_bar(
    dataset: &Dataset,
    priors: &[f64],
    n: usize,
    seed: u64,
) -> Result<Vec<SampleSet>, EvalError> {
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
pub fn cross_validate_with_bar(
    sets: &[SampleSet],
    params: &CvParams,
) -> Result<CvReport, EvalError> {
    let bar = progress_bar(0, "cross-validation");
    let report = cross_validate_samples(sets, params, &|done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    });
    bar.finish_and_clear();
    report
}

/// Evaluates every sequence of a dataset with a progress bar over the scans.
pub fn evaluate_with_bar(
    dataset: &Dataset,
    estimators: &[MotionEstimator],
) -> Result<BenchmarkReport, EvalError> {
    let bar = progress_bar(scans_to_evaluate(dataset)?, "evaluating scans");
    let result = evaluate_dataset(dataset, estimators, &BaselineParams::default(), &|| {
        bar.inc(1)
    });
    bar.finish_and_clear();
    result
}

/// Maps every planar scanner's sequence of a dataset with every occupancy method (the DGPOM
/// paper's protocol), with a progress bar over the maps; `patchflow occupancy` runs it too.
pub fn occupancy_with_bar(dataset: &Dataset, seed: u64) -> Result<OccupancyReport, EvalError> {
    let params = OccupancyParams::default();
    let methods_per_scenario = occupancy_methods(seed).len();
    let maps =
        occupancy_sequences(dataset)?.len() * params.query_scans.len() * methods_per_scenario;
    let bar = progress_bar(maps as u64, "occupancy maps");
    let methods_for =
        |_: &OccupancySequence, _: Option<&OccupancySequence>| Ok(occupancy_methods(seed));
    let report = evaluate_occupancy(dataset, &methods_for, &params, seed, &|_, _, _| bar.inc(1));
    bar.finish_and_clear();
    let mut report = report?;
    report.notes = occupancy_notes(&params);
    Ok(report)
}
