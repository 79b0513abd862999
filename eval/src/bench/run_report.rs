//! The report of one benchmark run, built once and written once (issue 29): the report model
//! scores the results a single time; the spread over training seeds, the GP estimator against the
//! README's bar (read from those scores), the DGPOM section and the realism study join it as
//! sections and `metrics.json` entries; then every file is rendered in one pass and written once
//! with the atomic write: `metrics.json`, `tables.csv`, `report.md`, `perception.json`, `cv.json`,
//! `cv.md`, `occupancy.json` and `occupancy.md`.

use std::collections::BTreeMap;
use std::path::Path;

use patchflow_sim::Realism;

use crate::bench::bar_check::{bar_entry, bar_rows, ideal_scores};
use crate::bench::bar_markdown::bar_markdown;
use crate::bench::run_files::run_entries;
use crate::bench::seed_spread::SeedSpread;
use crate::error::EvalError;
use crate::methods::method::Method;
use crate::occupancy::{OccupancyReport, occupancy_section, write_occupancy_report};
use crate::pipeline::plan::BenchPlan;
use crate::report::benchmark_report::BenchmarkReport;
use crate::report::{
    ReportExtras, ReportFiles, ReportModel, WriteOnce, create_dir, render_cv, write_model,
};
use crate::scene::metrics::MethodMetrics;
use crate::scene::result::SituationResult;
use crate::study::{StudyReport, realism_sections};

/// What writing a run's report gives back.
pub(crate) struct WrittenReport {
    /// The report files.
    pub files: ReportFiles,
    /// Each situation's per-target metrics as the report scored them, in report order.
    pub situation_metrics: Vec<(String, BTreeMap<Method, MethodMetrics>)>,
    /// The headline figures over the training seeds.
    pub spread: SeedSpread,
}

/// Builds the run's report model from `report` (its cv tables included) and the further seeds'
/// target runs, and writes every report file into `out`, each once.
pub(crate) fn write_run_report(
    plan: &BenchPlan,
    report: &BenchmarkReport,
    further_targets: &[Vec<SituationResult>],
    realism: Option<&StudyReport>,
    occupancy: Option<&OccupancyReport>,
    out: &Path,
) -> Result<WrittenReport, EvalError> {
    let seeds = plan.training_seeds();
    let mut runs = vec![report.situations.clone()];
    runs.extend(further_targets.iter().cloned());
    let spread = SeedSpread::of(&seeds, &runs)?;
    let mut model = ReportModel::new(report)?;
    let bar = bar_rows(
        &report.situations,
        &model.scores.situations,
        &ideal_scores(realism),
    );
    let mut extras = ReportExtras::default();
    extras
        .after_summary
        .push(bar_markdown(&bar, Realism::default().name()));
    if seeds.len() > 1 {
        extras.after_summary.push(spread.markdown());
    }
    if let Some(occupancy) = occupancy {
        extras.at_end.push(occupancy_section(occupancy));
    }
    let cv = report.cv.clone().unwrap_or_default();
    if let Some(realism) = realism {
        extras.at_end.push(realism_sections(realism, &cv, plan));
    }
    extras.metrics = run_entries(plan, &spread);
    extras.metrics.extend(bar_entry(&bar)?);
    model.extras = extras;

    let mut written = WriteOnce::new();
    let files = write_model(&model, out, &mut written)?;
    create_dir(out)?;
    let (cv_json, cv_md) = render_cv(&cv)?;
    written.write(&out.join("cv.json"), cv_json.as_bytes())?;
    written.write(&out.join("cv.md"), cv_md.as_bytes())?;
    if let Some(occupancy) = occupancy {
        write_occupancy_report(occupancy, out)?;
    }
    Ok(WrittenReport {
        files,
        situation_metrics: model
            .scores
            .situations
            .into_iter()
            .map(|(name, _, metrics)| (name, metrics))
            .collect(),
        spread,
    })
}
