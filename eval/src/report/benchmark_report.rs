//! The benchmark's results as one value: per situation the per-target tables, per sequence the
//! whole-scene results, and the run's notes, stage timings, seed and cross-validation tables.
//! Plain data, serialisable; the report files are rendered from it.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::cv::cv_report::CvReport;
use crate::report::stage_timing::StageTiming;
use crate::scene::result::{SceneResult, SituationResult};

/// Everything the report writer needs.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct BenchmarkReport {
    /// The situations with a target, in report order (the per-target tables, thesis 4.4).
    pub situations: Vec<SituationResult>,
    /// Every sequence evaluated as a whole scene, in report order.
    #[serde(default)]
    pub scenes: Vec<SceneResult>,
    /// Free-text notes for the report's notes section (one bullet each).
    pub notes: Vec<String>,
    /// Seconds spent per stage, for the timing table.
    pub timings: Vec<StageTiming>,
    /// Seed of the run, recorded in metrics.json when known.
    pub seed: Option<u64>,
    /// Each sequence's description from its scenario file, shown in `report.md` (a user's own
    /// scenarios are described by their own words, not the thesis').
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub descriptions: BTreeMap<String, String>,
    /// Sequences with scene figures (`plots/<name>_scene.png`, `plots/<name>_cloud.png`) and
    /// the sweep they show, linked from `report.md`.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub scene_figures: BTreeMap<String, usize>,
    /// Cross-validation tables, included in `report.md` when present.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cv: Option<CvReport>,
}
