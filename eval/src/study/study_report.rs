//! A whole study as `study.json` holds it (what was held fixed and every point's results, in
//! sorted order), and where each point's own result file lives before the merge.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::study::plan_stamp::PlanStamp;
use crate::study::point_result::PointResult;

/// A whole study: what was held fixed and every point's results, in sorted order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyReport {
    /// The study's name (`realism`, `rate`, `channels`).
    pub study: String,
    /// Unit of the varied factor.
    pub unit: String,
    /// Seed of generation, sampling and training.
    pub seed: u64,
    /// Training samples, pseudo-inputs and optimiser iterations per GP.
    pub samples: usize,
    /// Pseudo-inputs per sparse GP.
    pub pseudo_inputs: usize,
    /// Optimiser iterations per GP.
    pub max_iters: usize,
    /// Labels of the target's point bins of `by_points`.
    pub point_bins: Vec<String>,
    /// The points.
    pub points: Vec<PointResult>,
}

/// One point's file before the merge: its result and the plan it was run with (the merge refuses
/// points of another plan).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointFile {
    /// The plan the point was run with.
    pub plan: PlanStamp,
    /// The point's result.
    pub result: PointResult,
}

/// The file a point's result is written to.
pub fn point_file(out: &Path, index: usize) -> PathBuf {
    out.join("points").join(format!("{index:03}.json"))
}
