//! `patchflow check`'s run: every world simulated in turn, each model read on every check's
//! target under thesis 4.4's target protocol (the per-target tables of `evaluate`), and the
//! readings tallied against the bar.
//!
//! The models share each scan's maps and the baselines run once per world; each model's GP-KF
//! reads that model alone, so a model's readings are those `evaluate` gives it on its own.

use std::path::Path;

use patchflow_dataset::Dataset;
use patchflow_learn::{MergeRule, MotionEstimator};
use patchflow_sim::{GenerateOptions, Shard};

use crate::check::check_plan::CheckPlan;
use crate::check::check_report::{CheckReport, CheckedModel};
use crate::check::target_reading::{TargetReading, checked_methods, readings_of};
use crate::error::EvalError;
use crate::methods::baselines::baseline_params::BaselineParams;
use crate::methods::method::Method;
use crate::pipeline::data_folders::{remove_data, remove_empty_dir};
use crate::pipeline::progress::{progress_line, spinner};
use crate::pipeline::stages::generate_with_progress;
use crate::pipeline::target_runs::evaluate_runs_with_baselines;

/// A trained model and the name its readings carry (its file as given).
#[derive(Debug, Clone)]
pub struct CheckModel {
    /// The name of its readings.
    pub name: String,
    /// The model.
    pub estimator: MotionEstimator,
}

/// Reads `models` on every check of `plan` in every world; the worlds' data go under
/// `out/data/world-W` and are deleted once read unless the plan keeps them.
///
/// ```no_run
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// use std::path::Path;
/// use patchflow_eval::{CheckModel, CheckPlan, run_checks};
/// let plan = CheckPlan {
///     scenarios: vec![patchflow_sim::ScenarioSource::File("my_check.toml".into())],
///     worlds: vec![7, 8, 9],
///     realism: None,
///     keep_data: false,
/// };
/// let path = Path::new("results/bench/models/spgp-het.json");
/// let model = CheckModel {
///     name: path.display().to_string(),
///     estimator: patchflow_learn::MotionEstimator::load(path)?,
/// };
/// let report = run_checks(&plan, &[model], Path::new("checks"))?;
/// report.write(Path::new("checks"))?;
/// # Ok(())
/// # }
/// ```
pub fn run_checks(
    plan: &CheckPlan,
    models: &[CheckModel],
    out: &Path,
) -> Result<CheckReport, EvalError> {
    let checks = plan.check_names()?;
    if models.is_empty() {
        return Err(EvalError::BadParameter {
            name: "--model",
            reason: "no model given".into(),
        });
    }
    let mut methods = Vec::with_capacity(models.len());
    for model in models {
        let readout =
            Method::of_target_readout(&model.estimator, MergeRule::All).ok_or_else(|| {
                EvalError::BadParameter {
                    name: "--model",
                    reason: format!("{}: the model has no ALL read-out", model.name),
                }
            })?;
        methods.push(checked_methods(readout));
    }
    let runs: Vec<Vec<MotionEstimator>> =
        models.iter().map(|m| vec![m.estimator.clone()]).collect();
    let start = std::time::Instant::now();
    let mut readings: Vec<TargetReading> = Vec::new();
    for &world in &plan.worlds {
        let data = out.join("data").join(format!("world-{world}"));
        let options = GenerateOptions {
            out: data.clone(),
            seed: world,
            shard: Shard::ALL,
            overwrite: false,
            realism: plan.realism,
        };
        generate_with_progress(&plan.scenarios, &options)?;
        let bar = spinner(&format!("world {world}: reading the targets"));
        let results =
            evaluate_runs_with_baselines(&Dataset::open(&data)?, &runs, &BaselineParams::default());
        bar.finish_and_clear();
        for ((model, methods), situations) in models.iter().zip(&methods).zip(results?) {
            for check in &checks {
                // A dataset kept from an earlier run may hold sequences of other scenarios.
                let result = situations
                    .iter()
                    .find(|s| &s.name == check)
                    .ok_or_else(|| EvalError::BadResult {
                        situation: check.clone(),
                        reason: format!("world {world}: no target read (fewer than two sweeps?)"),
                    })?;
                readings.extend(readings_of(result, world, &model.name, methods)?);
            }
        }
        if !plan.keep_data {
            remove_data(&data)?;
        }
        progress_line(
            start,
            &format!("world {world}: {} checks read", checks.len()),
        );
    }
    if !plan.keep_data {
        remove_empty_dir(&out.join("data"))?;
    }
    let models = models
        .iter()
        .map(|m| CheckedModel {
            file: m.name.clone(),
            gp: m.estimator.gp_kind().to_string(),
            seed: m.estimator.training().seed,
        })
        .collect();
    let realism = plan.realism.map(|r| r.to_string());
    Ok(CheckReport::new(
        checks,
        plan.worlds.clone(),
        realism,
        models,
        readings,
    ))
}
