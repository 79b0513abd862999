//! Writes a whole benchmark report into a folder: `metrics.json`, `tables.csv`, `report.md`,
//! `perception.json` (the scan timings, which differ run to run), and the plots
//! `plots/<situation>_heading.png`, `plots/<situation>_speed.png`, `plots/summary_rmse.png` and, when sequences were
//! evaluated as whole scenes, `plots/objects_epe_by_range.png` and `plots/objects_epe_by_points.png`.

use std::path::{Path, PathBuf};

use crate::error::EvalError;
use crate::report::benchmark_report::BenchmarkReport;
use crate::report::files::create_dir;
use crate::report::object_plot::{ObjectAxis, plot_object_epe};
use crate::report::plot::{plot_heading, plot_speed};
use crate::report::report_model::ReportModel;
use crate::report::summary_plot::plot_summary;
use crate::report::write_once::WriteOnce;
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
    write_report_with(report, serde_json::Map::new(), dir)
}

/// [`write_report`] with top-level `metrics.json` entries beside the SPEC §7 shape (what produced
/// the numbers: the models, their seeds), rendered in the same pass so the file is written once.
pub fn write_report_with(
    report: &BenchmarkReport,
    metrics_entries: serde_json::Map<String, serde_json::Value>,
    dir: &Path,
) -> Result<ReportFiles, EvalError> {
    let mut model = ReportModel::new(report)?;
    model.extras.metrics = metrics_entries;
    write_model(&model, dir, &mut WriteOnce::new())
}

/// Writes the files of a report model into `dir` (created if needed), each once through `files`:
/// the text files rendered in one pass, then the plots.
pub(crate) fn write_model(
    model: &ReportModel<'_>,
    dir: &Path,
    files: &mut WriteOnce,
) -> Result<ReportFiles, EvalError> {
    let report = model.results;
    let plots_dir = dir.join("plots");
    create_dir(&plots_dir)?;
    let mut paths = ReportFiles {
        metrics_json: dir.join("metrics.json"),
        tables_csv: dir.join("tables.csv"),
        report_md: dir.join("report.md"),
        perception_json: dir.join("perception.json"),
        plots: Vec::new(),
    };
    let rendered = model.render().map_err(|err| match err {
        EvalError::Json { source, .. } => EvalError::Json {
            path: paths.metrics_json.clone(),
            source,
        },
        other => other,
    })?;
    files.write(&paths.metrics_json, rendered.metrics_json.as_bytes())?;
    files.write(&paths.tables_csv, rendered.tables_csv.as_bytes())?;
    files.write(&paths.report_md, rendered.report_md.as_bytes())?;
    if let Some(text) = &rendered.perception_json {
        files.write(&paths.perception_json, text.as_bytes())?;
    }
    for situation in &report.situations {
        let heading = plots_dir.join(format!("{}_heading.png", situation.name));
        let speed = plots_dir.join(format!("{}_speed.png", situation.name));
        plot_heading(situation, &heading)?;
        plot_speed(situation, &speed)?;
        paths.plots.extend([heading, speed]);
    }
    if !report.situations.is_empty() {
        let path = plots_dir.join("summary_rmse.png");
        plot_summary(&model.scores.situations, &path)?;
        paths.plots.push(path);
    }
    if !report.scenes.is_empty() {
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
            paths.plots.push(path);
        }
    }
    Ok(paths)
}

#[cfg(test)]
#[path = "writer_tests.rs"]
mod tests;
