//! Running a study (issue #10): each point of this shard (every N-th in sorted order, like
//! `generate --shard`) is generated, trained and evaluated on its own and written to
//! `OUT/points/NNN.json`; the unsharded run then merges them into `study.json`, so a sharded run
//! merged afterwards writes the same bytes.

use std::collections::BTreeMap;
use std::path::Path;

use patchflow_dataset::Dataset;
use patchflow_learn::{
    EstimatorParams, FeatureParams, MotionEstimator, MovingClassifier, MovingParams, SampleSet,
};
use patchflow_sim::{GenerateOptions, ScenarioSource, Shard};

use crate::error::EvalError;
use crate::pipeline::progress::spinner;
use crate::pipeline::short_tracks::shortened_tracks;
use crate::pipeline::stages::{
    collect_feature_draws_with_bar, evaluate_with_bar, generate_with_progress,
};
use crate::report::{create_dir, write_json_atomic};
use crate::study::merge::{StudyFiles, merge_study};
use crate::study::plan::{StudyPlan, StudyPoint};
use crate::study::plan_stamp::PlanStamp;
use crate::study::point_result::PointResult;
use crate::study::scenario_setting::apply_setting;
use crate::study::sensor_setting::SensorSetting;
use crate::study::study_report::{PointFile, point_file};

/// Runs this shard's points of a study into `out` (datasets under `out/data`); with the whole
/// study (`Shard::ALL`) also merges them into `study.json`, `study.md` and plots.
/// `on_point` hears of every point as it finishes.
///
/// ```no_run
/// use patchflow_eval::{BenchPlan, StudyFactor, StudyPlan, run_study};
/// use patchflow_sim::Shard;
/// let plan = StudyPlan::from_bench(StudyFactor::Rate, &BenchPlan::quick());
/// let files = run_study(&plan, std::path::Path::new("results/study-rate"), Shard::ALL, &|p| {
///     println!("{} done", p.label)
/// })
/// .unwrap();
/// println!("{:?}", files.map(|f| f.study_md));
/// ```
pub fn run_study(
    plan: &StudyPlan,
    out: &Path,
    shard: Shard,
    on_point: &dyn Fn(&PointResult),
) -> Result<Option<StudyFiles>, EvalError> {
    let mut trained: BTreeMap<String, (Vec<MotionEstimator>, MovingClassifier)> = BTreeMap::new();
    for point in plan.points.iter().filter(|p| shard.takes(p.index)) {
        // Models of one training setting serve every point that shares it (the realism study).
        let key = point.train.key();
        if !trained.contains_key(&key) {
            let estimators = train_for(plan, &point.train, out)?;
            trained.insert(key.clone(), estimators);
        }
        let (estimators, moving) = match trained.get(&key) {
            Some((estimators, moving)) => (&estimators[..], Some(moving)),
            None => (&[][..], None),
        };
        let result = evaluate_point(plan, point, estimators, moving, out)?;
        write_point(out, plan, &result)?;
        on_point(&result);
    }
    if shard == Shard::ALL {
        return merge_study(plan, out).map(Some);
    }
    Ok(None)
}

/// Writes a point's result to its file, stamped with the plan it was run with.
pub(crate) fn write_point(
    out: &Path,
    plan: &StudyPlan,
    result: &PointResult,
) -> Result<(), EvalError> {
    let path = point_file(out, result.index);
    create_dir(&out.join("points"))?;
    let file = PointFile {
        plan: PlanStamp::of(plan),
        result: result.clone(),
    };
    write_json_atomic(&path, &file)
}

/// Simulates the training tracks with a setting (`plan.training_sweep_share` of their sweeps),
/// samples patches with the setting's features (thesis 3.1.2, prior 0.5) and trains one
/// estimator per GP kind on them (thesis 3.1.3), and the moving classifier on the same maps.
fn train_for(
    plan: &StudyPlan,
    setting: &SensorSetting,
    out: &Path,
) -> Result<(Vec<MotionEstimator>, MovingClassifier), EvalError> {
    let folder = out.join("data").join(setting.data_key());
    let tracks = shortened_tracks(
        &plan.training,
        plan.training_sweep_share,
        &folder.join("train-short-scenarios"),
    )?;
    let train = generate(plan, &tracks, setting, out, "train")?;
    let features = setting.features();
    let set = sample_patches(&train, &features, plan.samples, plan.seed)?;
    let bar = spinner(&format!(
        "fitting the moving classifier ({})",
        setting.key()
    ));
    let moving = MovingClassifier::train(
        &train,
        &features,
        &MovingParams {
            seed: plan.seed,
            ..MovingParams::default()
        },
    );
    bar.finish_and_clear();
    let moving = moving?;
    let estimators = plan
        .gps
        .iter()
        .map(|&gp| {
            let params = EstimatorParams {
                gp,
                features: features.clone(),
                samples: plan.samples,
                pseudo_inputs: plan.pseudo_inputs,
                max_iters: plan.max_iters,
                seed: plan.seed,
                ..EstimatorParams::default()
            };
            let bar = spinner(&format!("fitting 3 {gp} GPs ({})", setting.key()));
            let estimator = MotionEstimator::fit_samples(&set, &params);
            bar.finish_and_clear();
            Ok(estimator?.with_sequences(&train))
        })
        .collect::<Result<Vec<_>, EvalError>>()?;
    Ok((estimators, moving))
}

/// Importance-samples `n` map patches of `features` (prior 0.5) from a dataset (thesis 3.1.2),
/// with a progress bar.
fn sample_patches(
    dataset: &Dataset,
    features: &FeatureParams,
    n: usize,
    seed: u64,
) -> Result<SampleSet, EvalError> {
    let sets = collect_feature_draws_with_bar(dataset, features, &[(0.5, seed)], n);
    sets?
        .into_iter()
        .next()
        .ok_or_else(|| EvalError::BadResult {
            situation: "study".into(),
            reason: "sampling gave no sample set".into(),
        })
}

/// Simulates the situations with the point's setting and runs every method on them (thesis 4.4).
pub(crate) fn evaluate_point(
    plan: &StudyPlan,
    point: &StudyPoint,
    estimators: &[MotionEstimator],
    moving: Option<&MovingClassifier>,
    out: &Path,
) -> Result<PointResult, EvalError> {
    let situations = generate(plan, &plan.situations, &point.evaluate, out, "situations")?;
    let report = evaluate_with_bar(&situations, estimators, moving)?;
    PointResult::from_report(point, &report)
}

/// Generates `sources` with a setting into `out/data/<data key>/<part>` (resumed if there; the
/// points of the cell study share one).
pub(crate) fn generate(
    plan: &StudyPlan,
    sources: &[ScenarioSource],
    setting: &SensorSetting,
    out: &Path,
    part: &str,
) -> Result<Dataset, EvalError> {
    let folder = out.join("data").join(setting.data_key());
    let sources = apply_setting(sources, setting, &folder.join(format!("{part}-scenarios")))?;
    let data = folder.join(part);
    let options = GenerateOptions {
        out: data.clone(),
        seed: plan.seed,
        shard: Shard::ALL,
        realism: setting.realism,
        overwrite: false,
    };
    generate_with_progress(&sources, &options)?;
    Ok(Dataset::open(&data)?)
}
