//! Writes an occupancy report into a folder: `occupancy.json`, `occupancy.md` and
//! `plots/occupancy_<scenario>_<method>.png`.

use std::path::{Path, PathBuf};

use super::OccupancyReport;
use super::json::occupancy_json;
use super::markdown::occupancy_markdown;
use super::plot::{figure_file_name, plot_occupancy_figure};
use super::plot_dgpom::{ahead_file_name, motion_map_file_name, plot_ahead, plot_motion_map};
use crate::error::EvalError;
use crate::report::{create_dir, write_atomic};

/// The files an occupancy report consists of.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OccupancyFiles {
    /// `DIR/occupancy.json`.
    pub json: PathBuf,
    /// `DIR/occupancy.md`.
    pub markdown: PathBuf,
    /// `DIR/plots/occupancy_*.png`: one per scenario and method, and per scenario with DGPOM its
    /// motion map (Figure 5) and its predictions ahead (Figure 10).
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
            let path = plots_dir.join(figure_file_name(&scores.name, *method));
            plot_occupancy_figure(scores, *method, &path)?;
            files.plots.push(path);
        }
    }
    for (scenario, map) in &report.motion_maps {
        let path = plots_dir.join(motion_map_file_name(scenario));
        plot_motion_map(scenario, map, &path)?;
        files.plots.push(path);
    }
    for (scenario, scores) in &report.ahead {
        let path = plots_dir.join(ahead_file_name(scenario));
        plot_ahead(scenario, scores, &path)?;
        files.plots.push(path);
    }
    Ok(files)
}
