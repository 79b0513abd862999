//! Report writers: `metrics.json`, `tables.csv`, `report.md` and plots for the benchmark; `cv.json`
//! and `cv.md` for cross-validation.

mod breakdown;
mod csv;
mod cv;
mod files;
mod json;
mod markdown;
mod object_plot;
mod perception_markdown;
mod plot;
mod scene_markdown;
mod scores;
#[cfg(test)]
mod synthetic;
mod writer;

pub use cv::{CvFeature, CvGp, CvReport, CvRow, write_cv_report};
pub(crate) use files::{create_dir, fmt_opt, write_atomic};
pub use json::{metrics_json, metrics_json_value};
pub(crate) use plot::{FONT, ensure_font};
pub use plot::{plot_heading, plot_speed};
#[cfg(test)]
pub(crate) use synthetic::synthetic_situation;
pub use writer::{ReportFiles, write_report};
