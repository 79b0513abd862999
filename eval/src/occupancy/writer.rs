//! Writes an occupancy report into a folder: `occupancy.json`, `occupancy.md` and
//! `plots/occupancy_<scenario>_<method>.png`.

use std::path::{Path, PathBuf};

use super::OccupancyReport;
use super::json::occupancy_json;
use super::markdown::occupancy_markdown;
use super::plot::{figure_file_name, plot_occupancy_figure};
use crate::error::EvalError;
use crate::report::{create_dir, write_atomic};

/// The files an occupancy report consists of.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OccupancyFiles {
    /// `DIR/occupancy.json`.
    pub json: PathBuf,
    /// `DIR/occupancy.md`.
    pub markdown: PathBuf,
    /// `DIR/plots/occupancy_*.png`, one per scenario and method.
    pub plots: Vec<PathBuf>,
}

/// Writes the report files into `dir` (created if needed).
pub fn write_occupancy_report(
    report: &OccupancyReport,
    dir: &Path,
) -> Result<OccupancyFiles, EvalError> {
    let plots_dir = dir.join("plots");
    create_dir(&plots_dir)?;
    let mut files = OccupancyFiles {
        json: dir.join("occupancy.json"),
        markdown: dir.join("occupancy.md"),
        plots: Vec::new(),
    };
    write_atomic(&files.json, occupancy_json(report)?.as_bytes())?;
    write_atomic(&files.markdown, occupancy_markdown(report).as_bytes())?;
    for scores in &report.scenarios {
        for method in scores.methods.keys() {
            let path = plots_dir.join(figure_file_name(&scores.name, method));
            plot_occupancy_figure(scores, method, &path)?;
            files.plots.push(path);
        }
    }
    Ok(files)
}
