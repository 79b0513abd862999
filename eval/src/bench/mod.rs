//! The benchmark driver behind `patchflow bench` (SPEC §7): runs the pipeline's stages from the
//! scenarios to the report (generate, sample, train, cross-validate, evaluate, the realism study,
//! the DGPOM paper's T-junction), then writes the report once: the spread over training seeds and
//! the GP estimator against the README's bar beside the scores.

mod bar_check;
mod bar_markdown;
mod notes;
mod run;
mod run_files;
mod run_report;
mod seed_spread;
mod training;

pub(crate) use bar_check::{BAR_HEADING_DEG, BAR_SPEED_MPS, heading_under_bar, speed_under_bar};
pub use run::{BenchOutcome, run_bench};
pub use seed_spread::{MethodSpread, SeedFigure, SeedSpread};
