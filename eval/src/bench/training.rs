//! The GP fits of a benchmark run: one estimator per GP kind and training seed (thesis 3.1.3),
//! the thesis preset's models beside them (on the nine tracks only), all fitted in parallel and
//! saved under `OUT/models`; and how the further seeds' target runs pair them.

use std::path::Path;

use patchflow_dataset::Dataset;
use patchflow_learn::{EstimatorParams, GpKind, MotionEstimator, SampleSet};
use rayon::prelude::*;

use crate::bench::run_files::model_file;
use crate::error::EvalError;
use crate::pipeline::plan::{BenchPlan, TRAINING_TRAFFIC};
use crate::pipeline::progress::spinner;

/// Trains one estimator per GP kind of the plan for each `(samples, seed)` draw, all fits in
/// parallel (each is seeded on its own, so the models do not depend on the threads), and saves
/// them to `out/models`; one vector per draw, GP kinds in plan order.
pub(crate) fn train_seeds(
    dataset: &Dataset,
    thesis_dataset: &Dataset,
    draws: &[(&SampleSet, u64)],
    thesis_draws: &[(&SampleSet, u64)],
    plan: &BenchPlan,
    out: &Path,
) -> Result<(Vec<Vec<MotionEstimator>>, Vec<MotionEstimator>), EvalError> {
    let models = out.join("models");
    std::fs::create_dir_all(&models).map_err(|e| EvalError::io(&models, e))?;
    // (draw, GP kind, thesis preset): every kind of the plan on the default's draws, SPGP-HET
    // alone on the thesis preset's.
    let mut fits: Vec<(usize, GpKind, bool)> = (0..draws.len())
        .flat_map(|d| plan.gps.iter().map(move |&gp| (d, gp, false)))
        .collect();
    fits.extend((0..thesis_draws.len()).map(|d| (d, GpKind::SpgpHet, true)));
    let spinner = spinner(&format!(
        "fitting {} GPs ({} kinds × {} seeds × 3, and {} thesis-preset models)",
        fits.len() * 3,
        plan.gps.len(),
        draws.len(),
        thesis_draws.len()
    ));
    let fitted = fits
        .par_iter()
        .map(|&(d, gp, thesis)| {
            let (set, seed) = if thesis { thesis_draws[d] } else { draws[d] };
            let base = if thesis {
                EstimatorParams::thesis()
            } else {
                plan.estimator.clone()
            };
            let params = EstimatorParams {
                gp,
                samples: plan.samples,
                pseudo_inputs: plan.pseudo_inputs,
                max_iters: plan.max_iters,
                seed,
                ..base
            };
            let data = if thesis { thesis_dataset } else { dataset };
            MotionEstimator::fit_samples(set, &params).map(|e| e.with_sequences(data))
        })
        .collect::<Result<Vec<_>, _>>();
    spinner.finish_and_clear();
    let mut runs: Vec<Vec<MotionEstimator>> = vec![Vec::new(); draws.len()];
    let mut thesis_runs = Vec::new();
    for ((d, gp, thesis), estimator) in fits.into_iter().zip(fitted?) {
        if thesis {
            let file = model_file(plan, gp, thesis_draws[d].1).replace(".json", "-thesis.json");
            estimator.save(&out.join(file))?;
            thesis_runs.push(estimator);
        } else {
            estimator.save(&out.join(model_file(plan, gp, draws[d].1)))?;
            runs[d].push(estimator);
        }
    }
    Ok((runs, thesis_runs))
}

/// The thesis preset's training data in `train`: every sequence but the training traffic added
/// for the default ([`TRAINING_TRAFFIC`]), i.e. the nine tracks of the thesis' data on the
/// default plan; an error naming the folder if nothing is left.
pub(crate) fn thesis_tracks(train: &Dataset) -> Result<Dataset, EvalError> {
    Ok(train.restricted_to(&|name| !TRAINING_TRAFFIC.contains(&name))?)
}

/// The target runs of the further seeds with the thesis preset's models: the first seed's
/// thesis model alone, then each further seed's models with its thesis model.
pub(crate) fn target_runs_with_thesis(
    further: &[Vec<MotionEstimator>],
    thesis: &[MotionEstimator],
) -> Vec<Vec<MotionEstimator>> {
    let mut runs = Vec::with_capacity(further.len() + 1);
    if let Some(first) = thesis.first() {
        runs.push(vec![first.clone()]);
    }
    for (k, models) in further.iter().enumerate() {
        let mut run = models.clone();
        run.extend(thesis.get(k + 1).cloned());
        runs.push(run);
    }
    runs
}

/// The first `n` samples of a set (samples are in dataset order, so this is itself a sample).
pub(crate) fn first(set: &SampleSet, n: usize) -> SampleSet {
    SampleSet {
        samples: set.samples.iter().take(n).cloned().collect(),
        ..set.clone()
    }
}
