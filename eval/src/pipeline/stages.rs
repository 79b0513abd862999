//! The benchmark's long stages with progress on the terminal (indicatif bars on stderr, hidden
//! when stderr is not a terminal); `patchflow generate`, `cv` and `evaluate` run them too.

use std::cell::RefCell;
use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;
use std::sync::Mutex;

use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use patchflow_dataset::{Dataset, Manifest};
use patchflow_learn::{FeatureKind, FeatureParams, MotionEstimator, MovingClassifier, SampleSet};
use patchflow_occupancy::{AheadParams, OccupancyParams, OccupancySequence, SampleParams};
use patchflow_sim::{GenerateOptions, Progress, ScenarioSource, generate_dataset};

use crate::cv::cross_validation::cross_validate_samples;
use crate::cv::cv_params::CvParams;
use crate::cv::cv_report::CvReport;
use crate::error::EvalError;
use crate::methods::baselines::baseline_params::BaselineParams;
use crate::occupancy::{
    OccupancyReport, SequenceKind, dgpom_method, dgpom_notes, evaluate_occupancy,
    height_slice_note, learn_motion_map, occupancy_methods, occupancy_methods_with,
    occupancy_notes, occupancy_sequences, predict_ahead_with,
};
use crate::pipeline::dataset_evaluation::{evaluate_dataset, scans_to_evaluate};
use crate::pipeline::progress::{ProgressLines, progress_bar, progress_line, stderr_is_terminal};
use crate::report::benchmark_report::BenchmarkReport;

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
    // On a log, a line at every tenth of a sequence's sweeps: a long one shows it is moving.
    let logged: Mutex<HashMap<String, (ProgressLines, usize, usize)>> = Mutex::new(HashMap::new());
    // Without a terminal the bars are hidden: a line per finished sequence shows the progress.
    let (lines, start) = (!stderr_is_terminal(), std::time::Instant::now());
    let on_progress = |event: Progress| {
        if let (true, Progress::SequenceDone { name, skipped }) = (lines, &event) {
            let done = if *skipped {
                "already complete"
            } else {
                "generated"
            };
            progress_line(start, &format!("  {name}: {done}"));
        }
        let Ok(mut open) = open.lock() else { return };
        match event {
            Progress::Waiting { name } => {
                let _ = bars.println(format!(
                    "{name:>12} is being written by another run; waiting for it"
                ));
            }
            Progress::Estimate { name, estimate } => {
                let text = format!("{name:>12} will take {}", estimate.summary());
                if lines {
                    progress_line(start, text.trim_start());
                } else {
                    let _ = bars.println(text);
                }
            }
            Progress::WorldBuilding { name, long } => {
                if let Some(bar) = open.get(&name) {
                    // The elapsed time keeps moving while the world is built.
                    bar.enable_steady_tick(std::time::Duration::from_millis(500));
                    bar.set_message("building the world");
                }
                if lines && long {
                    progress_line(start, &format!("  {name}: building the world"));
                }
            }
            Progress::WorldBuilt { name, secs } => {
                if let Some(bar) = open.get(&name) {
                    bar.set_message(format!("world built in {secs:.1} s"));
                }
                if lines && secs >= 2.0 {
                    progress_line(start, &format!("  {name}: world built in {secs:.1} s"));
                }
            }
            Progress::SequenceStarted { name, sweeps } if lines => {
                if let Ok(mut logged) = logged.lock() {
                    let label = format!("{name} sweeps");
                    logged.insert(name, (ProgressLines::new(&label), 0, sweeps as usize));
                }
            }
            Progress::SweepDone { name, .. } if lines => {
                if let Ok(mut logged) = logged.lock()
                    && let Some((log, done, total)) = logged.get_mut(&name)
                {
                    *done += 1;
                    log.update(*done, *total);
                }
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
            Progress::SweepDamaged {
                name,
                index,
                reason,
            } => {
                let _ = bars.println(format!(
                    "{name:>12} sweep {index} left by an earlier run is damaged ({reason}); writing it again"
                ));
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

/// Importance-samples map patches with `features` for several priors in one pass over the
/// dataset (thesis 3.1.2; the maps of all priors share their beam tracing), with a progress bar.
/// `features` is a preset's (`EstimatorParams::features`): its prior is replaced by each of
/// `priors`.
pub fn collect_samples_with_bar(
    dataset: &Dataset,
    features: &FeatureParams,
    priors: &[f64],
    n: usize,
    seed: u64,
) -> Result<Vec<SampleSet>, EvalError> {
    let draws: Vec<(f64, u64)> = priors.iter().map(|&prior| (prior, seed)).collect();
    collect_feature_draws_with_bar(dataset, features, &draws, n)
}

/// Importance-samples map patches with `features` for several `(prior, seed)` draws in one pass
/// over the dataset (each prior's maps built once and shared by its seeds), with a progress bar.
pub(crate) fn collect_feature_draws_with_bar(
    dataset: &Dataset,
    features: &FeatureParams,
    draws: &[(f64, u64)],
    n: usize,
) -> Result<Vec<SampleSet>, EvalError> {
    let bar = progress_bar(0, "sampling patches");
    let lines = ProgressLines::new("sweeps sampled");
    let sets = SampleSet::collect_draws(
        dataset,
        features,
        draws,
        FeatureKind::Patch,
        n,
        &|done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
            lines.update(done, total);
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
    let lines = ProgressLines::new("cross-validation fits");
    let report = cross_validate_samples(sets, params, &|done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
        lines.update(done, total);
    });
    bar.finish_and_clear();
    report
}

/// Evaluates every sequence of a dataset with a progress bar over the scans (with the moving
/// classifier when given).
pub fn evaluate_with_bar(
    dataset: &Dataset,
    estimators: &[MotionEstimator],
    moving: Option<&MovingClassifier>,
) -> Result<BenchmarkReport, EvalError> {
    let total = scans_to_evaluate(dataset)?;
    let bar = progress_bar(total, "evaluating scans");
    let lines = ProgressLines::new("scans evaluated");
    let done = std::sync::atomic::AtomicUsize::new(0);
    let result = evaluate_dataset(
        dataset,
        estimators,
        &BaselineParams::default(),
        moving,
        &|| {
            bar.inc(1);
            let done = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            lines.update(done, total as usize);
        },
    );
    bar.finish_and_clear();
    result
}

/// Maps every planar scanner's sequence of a dataset with every occupancy method at the query
/// times of `params` (the DGPOM paper's protocol by default: DGPOM where the scenario has a
/// training run, whose motion map is learned first), then DGPOM's predictions ahead from the
/// start scans of `ahead` (Figure 10), with a progress bar over the maps; `patchflow occupancy`
/// runs it with the defaults.
pub fn occupancy_with_bar(
    dataset: &Dataset,
    seed: u64,
    params: &OccupancyParams,
    ahead: &AheadParams,
) -> Result<OccupancyReport, EvalError> {
    let names = occupancy_sequences(dataset)?;
    let trained = names
        .iter()
        .filter(|n| {
            let training = format!("{n}_train");
            dataset.sequences().iter().any(|s| s.name == training)
        })
        .count();
    let methods_per_scenario = occupancy_methods(&SampleParams::default(), None).len();
    let maps = (names.len() * methods_per_scenario + trained) * params.query_scans.len()
        + trained * ahead.start_scans.len();
    let bar = progress_bar(maps as u64, "occupancy maps");
    // DGPOM's motion map is learned from the training run before the scenario is mapped.
    let motion_maps = RefCell::new(BTreeMap::new());
    // The DGPOM method of each scenario, kept so predicting ahead reuses its fits.
    let dgpom_methods = RefCell::new(BTreeMap::new());
    let methods_for =
        |sequence: &OccupancySequence, kind: SequenceKind, training: Option<&OccupancySequence>| {
            let map = match training {
                Some(training) => {
                    bar.set_message("DGPOM motion map");
                    let map = learn_motion_map(training)?;
                    bar.set_message("occupancy maps");
                    motion_maps
                        .borrow_mut()
                        .insert(sequence.name.clone(), Arc::clone(&map));
                    Some(map)
                }
                None => None,
            };
            let samples = kind.sample_params(seed);
            let dgpom = map.map(|map| dgpom_method(&samples, map));
            if let Some(method) = &dgpom {
                dgpom_methods
                    .borrow_mut()
                    .insert(sequence.name.clone(), method.clone());
            }
            Ok(occupancy_methods_with(&samples, dgpom))
        };
    let on_map = |_: &str, _: &str, _: usize| bar.inc(1);
    let report = evaluate_occupancy(dataset, &methods_for, params, seed, &on_map);
    let mut report = report?;
    report.motion_maps = motion_maps.into_inner();
    bar.set_message("DGPOM predicting ahead");
    // A start time that is also a query time reuses that map's fit.
    predict_ahead_with(
        dataset,
        &mut report,
        ahead,
        &|| bar.inc(1),
        &dgpom_methods.into_inner(),
    )?;
    bar.finish_and_clear();
    report.notes = occupancy_notes(params);
    if report
        .kinds
        .values()
        .any(|&k| k == SequenceKind::HeightSlice)
    {
        report.notes.push(height_slice_note());
    }
    if !report.motion_maps.is_empty() {
        report.notes.extend(dgpom_notes(ahead));
    }
    Ok(report)
}
