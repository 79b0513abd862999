//! The report: the benchmark's results as one value ([`BenchmarkReport`]) with the thesis' own
//! numbers beside them, and its renderings: `metrics.json`, `tables.csv`, `report.md`,
//! `perception.json` and plots for the benchmark; `cv.json` and `cv.md` for cross-validation.

pub(crate) mod benchmark_report;
mod birds_eye;
mod breakdown;
mod chart;
mod cloud_view;
mod csv;
mod cv;
mod files;
mod font;
mod json;
mod map_view;
mod markdown;
mod object_plot;
mod perception_markdown;
pub(crate) mod perception_summary;
mod plot;
pub(crate) mod png_file;
mod report_model;
mod scene_figure;
mod scene_markdown;
mod scores;
pub(crate) mod stage_timing;
mod summary_plot;
#[cfg(test)]
mod synthetic;
pub mod thesis_tables;
mod world_chart;
mod write_once;
mod writer;

pub(crate) use cv::render_cv;
pub use cv::write_cv_report;
pub(crate) use files::{create_dir, fmt_opt, write_atomic, write_json_atomic};
pub(crate) use font::{FONT, ensure_font};
pub use json::metrics_json;
pub use map_view::write_map_figure;
pub(crate) use plot::palette_colour;
pub(crate) use report_model::{ReportExtras, ReportModel};
pub use scene_figure::{SceneFigures, write_dataset_scene_figures, write_scene_figures};
pub(crate) use scores::SituationMetrics;
#[cfg(test)]
pub(crate) use synthetic::{synthetic_report, synthetic_situation};
pub(crate) use write_once::WriteOnce;
pub(crate) use writer::write_model;
pub use writer::{ReportFiles, write_report, write_report_with};
