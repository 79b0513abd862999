//! One benchmark run from scenarios to report, stage by stage (SPEC §7, `patchflow bench`).

use std::path::Path;

use patchflow_dataset::Dataset;
use patchflow_learn::{EstimatorParams, GpKind, MotionEstimator, SampleSet};
use patchflow_sim::{GenerateOptions, ScenarioSource, Shard};

use crate::bench::notes::notes;
use crate::bench::plan::BenchPlan;
use crate::bench::stages::{
    collect_samples_with_bar, cross_validate_with_bar, evaluate_with_bar, generate_with_progress,
    occupancy_with_bar,
};
use crate::cpu_time::load_average;
use crate::error::EvalError;
use crate::occupancy::{OccupancyReport, occupancy_section, write_occupancy_report};
use crate::perception_summary::PerceptionSummary;
use crate::progress::{StageTimer, StageTiming, spinner};
use crate::report::{CvReport, ReportFiles, write_cv_report, write_report};
use crate::result::BenchmarkReport;
use crate::study::{realism_in_bench, realism_sections};

/// What a benchmark run produced.
#[derive(Debug, Clone)]
pub struct BenchOutcome {
    /// Every method's results (also written to `OUT/metrics.json`, `tables.csv`, `report.md`).
    pub report: BenchmarkReport,
    /// The cross-validation tables (`OUT/cv.json`, `cv.md`).
    pub cv: CvReport,
    /// The report files written.
    pub files: ReportFiles,
    /// The perception cost per sequence and over all scans.
    pub perception: Vec<PerceptionSummary>,
    /// The occupancy maps' scores (`OUT/occupancy.json`, `occupancy.md`), if the plan maps any.
    pub occupancy: Option<OccupancyReport>,
}

/// Runs a benchmark into `out`: the datasets under `out/data`, the models under `out/models`,
/// the report files in `out`. `on_stage` hears of every stage as it finishes.
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
    let mut timer = StageTimer::new();
    let mut stage = |name: &str, work: &mut dyn FnMut() -> Result<(), EvalError>| {
        timer.time(name, work)?;
        if let Some(t) = timer.timings().last() {
            on_stage(t);
        }
        Ok::<(), EvalError>(())
    };
    let data = out.join("data");
    let (mut train, mut situations) = (None, None);
    let (mut sets, mut estimators, mut cv, mut report) = (Vec::new(), Vec::new(), None, None);

    // 1. Simulate the training tracks and the evaluation sequences (SPEC §3).
    stage("generate training tracks", &mut || {
        train = Some(generate(&plan.training, &data.join("train"), plan.seed)?);
        Ok(())
    })?;
    stage("generate situations", &mut || {
        situations = Some(generate(
            &plan.situations,
            &data.join("situations"),
            plan.seed,
        )?);
        Ok(())
    })?;
    let (train, situations) = train.zip(situations).ok_or_else(|| missing("datasets"))?;
    // 2. Importance-sample map patches once per prior (thesis 3.1.2); prior 0.5 also trains.
    stage("sample patches", &mut || {
        sets = collect_samples_with_bar(&train, &plan.cv.priors, plan.samples, plan.seed)?;
        Ok(())
    })?;
    let training_set = sets
        .iter()
        .find(|s| (s.prior - 0.5).abs() < 1e-12)
        .ok_or_else(|| missing("a sample set with prior 0.5 (CvParams::priors)"))?;
    // 3. One estimator per GP kind on the same samples (thesis 3.1.3).
    stage("train SPGP and SPGP-HET", &mut || {
        estimators = plan
            .gps
            .iter()
            .map(|&gp| train_estimator(&train, training_set, plan, gp, out))
            .collect::<Result<_, _>>()?;
        Ok(())
    })?;
    // 4. Cross-validation tables (thesis 4.3, Tables 4.1-4.4).
    let cv_sets: Vec<SampleSet> = sets.iter().map(|s| first(s, plan.cv.samples)).collect();
    stage("cross-validation", &mut || {
        cv = Some(cross_validate_with_bar(&cv_sets, &plan.cv)?);
        Ok(())
    })?;
    // 5. Every method on every sequence (thesis 4.4 and the whole scene).
    let load_before = load_average();
    stage("evaluate situations", &mut || {
        report = Some(evaluate_with_bar(&situations, &estimators)?);
        Ok(())
    })?;
    let load = load_before.zip(load_average());
    let (cv, mut report) = cv.zip(report).ok_or_else(|| missing("results"))?;
    // 5b. The realism study (issue #10): the situations at every rung, the same models.
    let mut realism = None;
    stage("realism study", &mut || {
        realism = Some(realism_in_bench(plan, &report, &estimators, out)?);
        Ok(())
    })?;
    // 6. Occupancy maps of the DGPOM paper's T-junction (its Section 3.1, Table 1, Figure 6); the
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
            occupancy = Some(occupancy_with_bar(&maps, plan.seed)?);
            Ok(())
        })?;
    }
    // 7. The report.
    report.seed = Some(plan.seed);
    report.notes = notes(plan, &estimators, load);
    report.cv = Some(cv.clone());
    report.timings = timer.timings().to_vec();
    let files = write_report(&report, out)?;
    write_cv_report(&cv, out)?;
    if let Some(occupancy) = &occupancy {
        write_occupancy_report(occupancy, out)?;
        append(&files.report_md, &occupancy_section(occupancy))?;
    }
    if let Some(realism) = &realism {
        append(&files.report_md, &realism_sections(realism, &cv))?;
    }
    let perception = PerceptionSummary::of_scenes(&report.scenes);
    Ok(BenchOutcome {
        report,
        cv,
        files,
        perception,
        occupancy,
    })
}

/// Appends `text` to the file at `path`, after a blank line.
fn append(path: &Path, text: &str) -> Result<(), EvalError> {
    let mut content = std::fs::read_to_string(path).map_err(|e| EvalError::io(path, e))?;
    content.push('\n');
    content.push_str(text);
    std::fs::write(path, content).map_err(|e| EvalError::io(path, e))
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

fn train_estimator(
    dataset: &Dataset,
    set: &SampleSet,
    plan: &BenchPlan,
    gp: GpKind,
    out: &Path,
) -> Result<MotionEstimator, EvalError> {
    let params = EstimatorParams {
        gp,
        samples: plan.samples,
        pseudo_inputs: plan.pseudo_inputs,
        max_iters: plan.max_iters,
        seed: plan.seed,
        ..EstimatorParams::default()
    };
    let spinner = spinner(&format!("fitting 3 {gp} GPs"));
    let estimator = MotionEstimator::fit_samples(set, &params).map(|e| e.with_sequences(dataset));
    spinner.finish_and_clear();
    let estimator = estimator?;
    let models = out.join("models");
    std::fs::create_dir_all(&models).map_err(|e| EvalError::io(&models, e))?;
    estimator.save(&models.join(format!("{gp}.json")))?;
    Ok(estimator)
}

/// The first `n` samples of a set (samples are in dataset order, so this is itself a sample).
fn first(set: &SampleSet, n: usize) -> SampleSet {
    SampleSet {
        samples: set.samples.iter().take(n).cloned().collect(),
        ..set.clone()
    }
}
