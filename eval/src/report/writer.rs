//! Writes a whole benchmark report into a folder: `metrics.json`, `tables.csv`, `report.md`,
//! `perception.json` (the scan timings, which differ run to run), and the plots
//! `plots/<situation>_heading.png`, `plots/<situation>_speed.png`, `plots/summary_rmse.png` and, when sequences were
//! evaluated as whole scenes, `plots/objects_epe_by_range.png` and `plots/objects_epe_by_points.png`.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use crate::error::EvalError;
use crate::report::benchmark_report::BenchmarkReport;
use crate::report::csv::tables_csv;
use crate::report::files::{create_dir, write_atomic};
use crate::report::json::{metrics_text, metrics_value};
use crate::report::markdown::report_markdown;
use crate::report::object_plot::{ObjectAxis, plot_object_epe};
use crate::report::perception_summary::PerceptionSummary;
use crate::report::plot::{plot_heading, plot_speed};
use crate::report::scores::ReportScores;
use crate::report::summary_plot::plot_summary;
use crate::scene::objects::ObjectScan;

/// The files a report consists of.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReportFiles {
    /// `DIR/metrics.json`.
    pub metrics_json: PathBuf,
    /// `DIR/tables.csv`.
    pub tables_csv: PathBuf,
    /// `DIR/report.md`.
    pub report_md: PathBuf,
    /// `DIR/perception.json`: per sequence and over all scans, median and worst of every stage.
    pub perception_json: PathBuf,
    /// `DIR/plots/*.png`, heading then speed per situation, the summary, then the two object plots.
    pub plots: Vec<PathBuf>,
}

/// Scores every method of every situation and writes the report files into `dir` (created if needed).
/// Situation names must be unique and usable as file names (letters, digits, `_`, `-`, `.`).
///
/// ```no_run
/// use patchflow_eval::{BenchmarkReport, write_report};
/// let files = write_report(&BenchmarkReport::default(), std::path::Path::new("results/report")).unwrap();
/// println!("{}", files.report_md.display());
/// ```
pub fn write_report(report: &BenchmarkReport, dir: &Path) -> Result<ReportFiles, EvalError> {
    Ok(write_report_scored(report, dir)?.0)
}

/// [`write_report`], also handing back the scores it computed once, so that callers print the
/// same numbers without scoring again.
pub(crate) fn write_report_scored(
    report: &BenchmarkReport,
    dir: &Path,
) -> Result<(ReportFiles, ReportScores), EvalError> {
    check_names(report)?;
    let scores = ReportScores::of(report)?;

    let plots_dir = dir.join("plots");
    create_dir(&plots_dir)?;
    let files = ReportFiles {
        metrics_json: dir.join("metrics.json"),
        tables_csv: dir.join("tables.csv"),
        report_md: dir.join("report.md"),
        perception_json: dir.join("perception.json"),
        plots: report
            .situations
            .iter()
            .flat_map(|s| {
                [
                    plots_dir.join(format!("{}_heading.png", s.name)),
                    plots_dir.join(format!("{}_speed.png", s.name)),
                ]
            })
            .collect(),
    };
    let json = metrics_value(report, &scores)
        .and_then(|value| metrics_text(&value))
        .map_err(|err| match err {
            EvalError::Json { source, .. } => EvalError::Json {
                path: files.metrics_json.clone(),
                source,
            },
            other => other,
        })?;
    write_atomic(&files.metrics_json, json.as_bytes())?;
    write_atomic(&files.tables_csv, tables_csv(&scores).as_bytes())?;
    write_atomic(
        &files.report_md,
        report_markdown(report, &scores).as_bytes(),
    )?;
    for (situation, pair) in report.situations.iter().zip(files.plots.chunks(2)) {
        plot_heading(situation, &pair[0])?;
        plot_speed(situation, &pair[1])?;
    }
    let mut files = files;
    if !report.situations.is_empty() {
        let path = plots_dir.join("summary_rmse.png");
        plot_summary(&scores.situations, &path)?;
        files.plots.push(path);
    }
    if !report.scenes.is_empty() {
        let perception = PerceptionSummary::of_scenes(&report.scenes);
        let text = serde_json::to_string_pretty(&perception).map_err(|source| EvalError::Json {
            path: files.perception_json.clone(),
            source,
        })?;
        write_atomic(&files.perception_json, format!("{text}\n").as_bytes())?;
        let objects: Vec<ObjectScan> = report
            .scenes
            .iter()
            .flat_map(|s| s.objects.iter().cloned())
            .collect();
        for (axis, name) in [
            (ObjectAxis::Range, "objects_epe_by_range.png"),
            (ObjectAxis::Points, "objects_epe_by_points.png"),
        ] {
            let path = plots_dir.join(name);
            plot_object_epe(&objects, axis, &path)?;
            files.plots.push(path);
        }
    }
    Ok((files, scores))
}

fn check_names(report: &BenchmarkReport) -> Result<(), EvalError> {
    let mut seen = BTreeSet::new();
    for s in &report.situations {
        let usable = !s.name.is_empty()
            && !s.name.starts_with('.')
            && s.name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'));
        if !usable {
            return Err(EvalError::BadResult {
                situation: s.name.clone(),
                reason: "a situation name must be letters, digits, '_', '-' or '.'".into(),
            });
        }
        if !seen.insert(s.name.as_str()) {
            return Err(EvalError::BadResult {
                situation: s.name.clone(),
                reason: "the situation appears twice".into(),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "writer_tests.rs"]
mod tests;
