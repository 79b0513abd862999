//! The realism study inside `bench` (issue #10): the models `bench` trained on the default rung
//! (`urban`) and its evaluation of the five situations there, plus the same situations generated
//! at the other rungs and evaluated with the same models; written to `OUT/realism/` as a study.
//! The study scores the target only, so the other rungs get the per-target evaluation (every
//! method on the target, the situations in parallel) and not the whole scene.

use std::path::Path;

use patchflow_learn::{MotionEstimator, MovingClassifier};
use patchflow_sim::Realism;

use crate::cv::cv_report::CvReport;
use crate::error::EvalError;
use crate::methods::baselines::baseline_params::BaselineParams;
use crate::pipeline::data_folders::remove_data;
use crate::pipeline::plan::{BenchPlan, source_name};
use crate::pipeline::target_runs::evaluate_targets_with_baselines;
use crate::report::benchmark_report::BenchmarkReport;
use crate::study::discussion::discussion_section;
use crate::study::markdown::study_section;
use crate::study::merge::merge_study;
use crate::study::plan::{StudyFactor, StudyPlan};
use crate::study::point_result::PointResult;
use crate::study::run::{generate, write_point};
use crate::study::study_report::StudyReport;

/// Runs the realism study on `bench`'s models; `urban` is bench's own evaluation (the default
/// rung), reused rather than repeated. Returns the study as merged into `out/realism/study.json`.
pub fn realism_in_bench(
    plan: &BenchPlan,
    urban: &BenchmarkReport,
    estimators: &[MotionEstimator],
    moving: Option<&MovingClassifier>,
    out: &Path,
) -> Result<StudyReport, EvalError> {
    let mut study = StudyPlan::from_bench(StudyFactor::Realism, plan);
    // `--quick` evaluates fewer situations, the same ones at every rung.
    let kept = |name: &str| {
        plan.realism_situations.is_empty() || plan.realism_situations.iter().any(|n| n == name)
    };
    study.situations.retain(|s| kept(&source_name(s)));
    study.points.retain(|p| {
        plan.realism_rungs.is_empty()
            || p.evaluate
                .realism
                .is_some_and(|r| plan.realism_rungs.contains(&r))
    });
    let urban = BenchmarkReport {
        situations: urban
            .situations
            .iter()
            .filter(|s| kept(&s.name))
            .cloned()
            .collect(),
        ..BenchmarkReport::default()
    };
    let dir = out.join("realism");
    for point in &study.points {
        let result = if point.evaluate.realism == Some(Realism::Urban) {
            PointResult::from_report(point, &urban)?
        } else {
            let situations = generate(
                &study,
                &study.situations,
                &point.evaluate,
                out,
                "situations",
            )?;
            let report = evaluate_targets_with_baselines(
                &situations,
                estimators,
                &BaselineParams::default(),
                moving,
            )?;
            if !plan.keep_data {
                remove_data(&out.join("data").join(point.evaluate.data_key()))?;
            }
            PointResult::from_report(point, &report)?
        };
        write_point(&dir, &study, &result)?;
    }
    merge_study(&study, &dir)?;
    let path = dir.join("study.json");
    let bytes = std::fs::read(&path).map_err(|e| EvalError::io(&path, e))?;
    serde_json::from_slice(&bytes).map_err(|source| EvalError::Json { path, source })
}

/// The bench report's sections of the realism study: its tables (plots in `realism/plots/`) and
/// the synthetic-to-real discussion; `plan` says whether it covered every situation.
pub fn realism_sections(study: &StudyReport, cv: &CvReport, plan: &BenchPlan) -> String {
    let rungs = match plan.realism_rungs.as_slice() {
        [] => "every rung".to_owned(),
        some => {
            let names: Vec<String> = some.iter().map(|r| format!("`{}`", r.name())).collect();
            format!("the {} rungs", names.join(" and "))
        }
    };
    let which = match plan.realism_situations.as_slice() {
        [] => vec!["the five situations".to_owned()],
        some => some.to_vec(),
    };
    let mut md = if plan.realism_situations.is_empty() && plan.realism_rungs.is_empty() {
        String::from(
            "## Realism study: the five situations at every rung, models trained on `urban`\n\n",
        )
    } else {
        format!(
            "## Realism study: {} at {rungs}, models trained on `urban`\n\nA shorter study than the default `bench` runs (`--quick`): only {} are simulated and evaluated, at {rungs}, and the pooled figures are over them alone.\n\n",
            which.join(" and "),
            which.join(", ")
        )
    };
    md.push_str("Files: `realism/study.json`, `realism/study.md`, `realism/plots/`.\n\n");
    md.push_str(&study_section(study, "###").replace("](plots/", "](realism/plots/"));
    md.push_str(&discussion_section(study, Some(cv), "##"));
    md
}
