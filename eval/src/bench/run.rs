//! One benchmark run from scenarios to report, stage by stage (SPEC §7, `patchflow bench`).

use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;

use patchflow_dataset::Dataset;
use patchflow_learn::{
    EstimatorParams, MOVING_FILE_NAME, MotionEstimator, MovingClassifier, MovingParams, SampleSet,
};
use patchflow_sim::{GenerateOptions, ScenarioSource, Shard};

use crate::bench::notes::notes;
use crate::bench::run_report::write_run_report;
use crate::bench::seed_spread::SeedSpread;
use crate::bench::training::{first, target_runs_with_thesis, thesis_tracks, train_seeds};
use crate::cv::cv_report::CvReport;
use crate::error::EvalError;
use crate::methods::method::Method;
use crate::occupancy::OccupancyReport;
use crate::pipeline::data_folders::{remove_data, remove_empty_dir};
use crate::pipeline::plan::BenchPlan;
use crate::pipeline::progress::{StageTimer, progress_line, spinner};
use crate::pipeline::short_tracks::shortened_tracks;
use crate::pipeline::stages::{
    collect_feature_draws_with_bar, cross_validate_with_bar, evaluate_with_bar,
    generate_with_progress, occupancy_with_bar,
};
use crate::pipeline::target_runs::evaluate_targets;
use crate::report::benchmark_report::BenchmarkReport;
use crate::report::perception_summary::PerceptionSummary;
use crate::report::stage_timing::StageTiming;
use crate::report::{ReportFiles, write_dataset_scene_figures};
use crate::scene::cpu_time::load_average;
use crate::scene::metrics::MethodMetrics;
use crate::study::realism_in_bench;

/// What a benchmark run produced.
#[derive(Debug, Clone)]
pub struct BenchOutcome {
    /// Every method's results (also written to `OUT/metrics.json`, `tables.csv`, `report.md`).
    pub report: BenchmarkReport,
    /// The cross-validation tables (`OUT/cv.json`, `cv.md`).
    pub cv: CvReport,
    /// The report files written.
    pub files: ReportFiles,
    /// Each situation's per-target metrics, as scored once for the report files (in report
    /// order): the numbers to print.
    pub situation_metrics: Vec<(String, BTreeMap<Method, MethodMetrics>)>,
    /// The perception cost per sequence and over all scans.
    pub perception: Vec<PerceptionSummary>,
    /// The occupancy maps' scores (`OUT/occupancy.json`, `occupancy.md`), if the plan maps any.
    pub occupancy: Option<OccupancyReport>,
    /// The headline figures' mean ± std over the training seeds.
    pub spread: SeedSpread,
}

/// Runs a benchmark into `out`: the datasets under `out/data` (deleted once used unless
/// `plan.keep_data`), the models under `out/models`, the report files in `out`. Every stage's
/// start and end is a line on stderr (a log shows progress without a terminal); `on_stage` hears
/// of every stage as it finishes.
///
/// ```no_run
/// use patchflow_eval::{BenchPlan, run_bench};
/// let outcome = run_bench(&BenchPlan::quick(), std::path::Path::new("results/quick"), &|stage| {
///     println!("{}: {:.1} s", stage.stage, stage.seconds)
/// })
/// .unwrap();
/// println!("{}", outcome.files.report_md.display());
/// ```
pub fn run_bench(
    plan: &BenchPlan,
    out: &Path,
    on_stage: &dyn Fn(&StageTiming),
) -> Result<BenchOutcome, EvalError> {
    let run_start = Instant::now();
    let mut timer = StageTimer::new();
    let mut stage = |name: &str, work: &mut dyn FnMut() -> Result<(), EvalError>| {
        progress_line(run_start, &format!("{name}: started"));
        timer.time(name, work)?;
        if let Some(t) = timer.timings().last() {
            let cpu = t
                .cpu_seconds
                .map_or_else(String::new, |c| format!(" ({c:.1} s CPU)"));
            progress_line(
                run_start,
                &format!("{name}: done in {:.1} s{cpu}", t.seconds),
            );
            on_stage(t);
        }
        Ok::<(), EvalError>(())
    };
    let data = out.join("data");
    let (mut train, mut situations) = (None, None);
    let (mut sets, mut estimators, mut cv, mut report) = (Vec::new(), Vec::new(), None, None);
    let seeds = plan.training_seeds();
    let (mut further, mut further_targets) = (Vec::new(), Vec::new());
    let mut thesis_models: Vec<MotionEstimator> = Vec::new();

    // 1. Simulate the training tracks (SPEC §3); the evaluation sequences follow training.
    stage("generate training tracks", &mut || {
        let scenarios = data.join("scenarios");
        let tracks = shortened_tracks(&plan.training, plan.training_sweep_share, &scenarios)?;
        train = Some(generate(&tracks, &data.join("train"), plan.seed)?);
        Ok(())
    })?;
    let train = train.ok_or_else(|| missing("training dataset"))?;
    // 2. Importance-sample map patches once per prior (thesis 3.1.2); prior 0.5 also trains.
    //    The further seeds draw their own samples (prior 0.5) in the same pass over the maps.
    let further_seeds = seeds.get(1..).unwrap_or_default();
    let (mut further_sets, mut thesis_sets) = (Vec::new(), Vec::new());
    stage("sample patches", &mut || {
        let mut draws: Vec<(f64, u64)> = plan.cv.priors.iter().map(|&p| (p, plan.seed)).collect();
        draws.extend(further_seeds.iter().map(|&seed| (0.5, seed)));
        // The default's own map and slice settings (its height slice is not the thesis').
        sets =
            collect_feature_draws_with_bar(&train, &plan.estimator.features, &draws, plan.samples)?;
        further_sets = sets.split_off(plan.cv.priors.len());
        // The thesis preset's own draws: its speed patches carry no heading jitter.
        // They come from the thesis' data alone: the nine tracks, not the generated traffic.
        if plan.thesis_preset {
            let thesis = EstimatorParams::thesis();
            let draws: Vec<(f64, u64)> = seeds.iter().map(|&seed| (0.5, seed)).collect();
            thesis_sets = collect_feature_draws_with_bar(
                &thesis_tracks(&train)?,
                &thesis.features,
                &draws,
                plan.samples,
            )?;
        }
        Ok(())
    })?;
    let training_set = sets
        .iter()
        .find(|s| (s.prior() - 0.5).abs() < 1e-12)
        .ok_or_else(|| missing("a sample set with prior 0.5 (CvParams::priors)"))?;
    // 3. One estimator per GP kind and training seed, each on its seed's samples (thesis
    //    3.1.3); the further seeds' GPs give the spread over seeds. The fits are independent and
    //    run in parallel.
    stage(
        &format!("train {}, every seed", plan.gp_names().join(" and ")),
        &mut || {
            let mut draws: Vec<(&SampleSet, u64)> = vec![(training_set, plan.seed)];
            draws.extend(further_sets.iter().zip(further_seeds.iter().copied()));
            let thesis_draws: Vec<(&SampleSet, u64)> =
                thesis_sets.iter().zip(seeds.iter().copied()).collect();
            let (runs, thesis_runs) = train_seeds(
                &train,
                &thesis_tracks(&train)?,
                &draws,
                &thesis_draws,
                plan,
                out,
            )?;
            let mut runs = runs.into_iter();
            estimators = runs.next().unwrap_or_default();
            further = runs.collect();
            thesis_models = thesis_runs;
            Ok(())
        },
    )?;
    // 3b. The moving/static classifier on the training tracks' maps (issue 27), saved beside
    //     the models.
    let mut moving = None;
    stage("train moving classifier", &mut || {
        let features = estimators
            .first()
            .map(|e| e.feature_params().clone())
            .ok_or_else(|| missing("estimator"))?;
        let params = MovingParams {
            seed: plan.seed,
            ..MovingParams::default()
        };
        let bar = spinner("fitting the moving classifier");
        let classifier = MovingClassifier::train(&train, &features, &params);
        bar.finish_and_clear();
        let classifier = classifier?;
        classifier.save(&out.join("models").join(MOVING_FILE_NAME))?;
        moving = Some(classifier);
        Ok(())
    })?;
    let moving = moving.ok_or_else(|| missing("moving classifier"))?;
    // 4. Simulate the evaluation sequences (SPEC §3). The training tracks are no longer needed:
    //    without `keep_data` they go first, so the two datasets are never on disk together.
    if !plan.keep_data {
        remove_data(&data.join("train"))?;
        remove_data(&data.join("scenarios"))?;
    }
    stage("generate situations", &mut || {
        situations = Some(generate(
            &plan.situations,
            &data.join("situations"),
            plan.seed,
        )?);
        Ok(())
    })?;
    let situations = situations.ok_or_else(|| missing("situations dataset"))?;
    // 5. Cross-validation tables (thesis 4.3, Tables 4.1-4.4).
    let cv_sets: Vec<SampleSet> = sets.iter().map(|s| first(s, plan.cv.samples)).collect();
    stage("cross-validation", &mut || {
        cv = Some(cross_validate_with_bar(&cv_sets, &plan.cv)?);
        Ok(())
    })?;
    // 6. Every method on every sequence (thesis 4.4 and the whole scene); the further seeds'
    //    GPs on the targets only (the baselines do not learn).
    let load_before = load_average();
    stage("evaluate situations", &mut || {
        report = Some(evaluate_with_bar(&situations, &estimators, Some(&moving))?);
        Ok(())
    })?;
    let load = load_before.zip(load_average());
    let mut thesis_targets = Vec::new();
    if !further.is_empty() || !thesis_models.is_empty() {
        stage("evaluate further seeds", &mut || {
            // One pass over the maps: the thesis preset of every seed beside the further seeds'
            // models (run k + 1 is seed k's thesis model, for seeds past the first with its
            // further models).
            let runs = target_runs_with_thesis(&further, &thesis_models);
            let mut results = evaluate_targets(&situations, &runs)?.into_iter();
            if !thesis_models.is_empty() {
                thesis_targets = results.next().unwrap_or_default();
            }
            further_targets = results.collect();
            Ok(())
        })?;
    }
    let (cv, mut report) = cv.zip(report).ok_or_else(|| missing("results"))?;
    // The thesis preset's rows of the first seed beside the default's.
    for (situation, thesis) in report.situations.iter_mut().zip(thesis_targets) {
        situation.methods.extend(thesis.methods);
    }
    // A bird's-eye view and a point cloud of each situation, from the data before it goes.
    let names: Vec<String> = report.situations.iter().map(|s| s.name.clone()).collect();
    stage("scene figures", &mut || {
        report.scene_figures =
            write_dataset_scene_figures(&situations, &names, &out.join("plots"))?;
        Ok(())
    })?;
    if !plan.keep_data {
        remove_data(&data.join("situations"))?;
    }
    // 7. The realism study (issue #10): the situations at every rung, the same models.
    let mut realism = None;
    stage("realism study", &mut || {
        realism = Some(realism_in_bench(
            plan,
            &report,
            &estimators,
            Some(&moving),
            out,
        )?);
        Ok(())
    })?;
    // 8. Occupancy maps of the DGPOM paper's T-junction (its Section 3.1, Table 1, Figure 6); the
    //    training run is generated beside it for methods that learn beforehand.
    let mut occupancy = None;
    if !plan.occupancy.is_empty() {
        let mut maps = None;
        stage("generate T-junction", &mut || {
            maps = Some(generate(
                &plan.occupancy,
                &data.join("occupancy"),
                plan.seed,
            )?);
            Ok(())
        })?;
        let maps = maps.ok_or_else(|| missing("occupancy dataset"))?;
        stage("occupancy maps", &mut || {
            occupancy = Some(occupancy_with_bar(
                &maps,
                plan.seed,
                &plan.occupancy_params,
                &plan.ahead_params,
            )?);
            Ok(())
        })?;
        if !plan.keep_data {
            remove_data(&data.join("occupancy"))?;
        }
    }
    if !plan.keep_data {
        remove_empty_dir(&data)?;
    }
    // 9. The report, built once and written once: the scores, the spread over the training
    //    seeds, and (10.) the GP estimator against the README's bar, read from those scores.
    report.seed = Some(plan.seed);
    report.notes = notes(plan, &estimators, load);
    report.cv = Some(cv.clone());
    report.timings = timer.timings().to_vec();
    let written = write_run_report(
        plan,
        &report,
        &further_targets,
        realism.as_ref(),
        occupancy.as_ref(),
        out,
    )?;
    let perception = PerceptionSummary::of_scenes(&report.scenes);
    Ok(BenchOutcome {
        report,
        cv,
        files: written.files,
        situation_metrics: written.situation_metrics,
        perception,
        occupancy,
        spread: written.spread,
    })
}

fn missing(what: &str) -> EvalError {
    EvalError::BadResult {
        situation: "bench".into(),
        reason: format!("a stage left no {what}"),
    }
}

fn generate(sources: &[ScenarioSource], out: &Path, seed: u64) -> Result<Dataset, EvalError> {
    let options = GenerateOptions {
        out: out.to_owned(),
        seed,
        shard: Shard::ALL,
        // Each scenario's own rung: `urban` for every shipped file, which names none.
        realism: None,
        overwrite: false,
    };
    generate_with_progress(sources, &options)?;
    Ok(Dataset::open(out)?)
}
