//! The benchmark result model: per situation the ground truth at every scan and every method's
//! per-scan estimates; the whole benchmark adds notes and stage timings. Plain data, serialisable.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::error::EvalError;
use crate::estimate::MotionEstimate;
use crate::method::Method;
use crate::metrics::{MethodMetrics, score_method};
use crate::progress::StageTiming;

/// The target's true motion at one scan.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TruthAtScan {
    /// Scan number within the situation.
    pub scan: usize,
    /// True heading, radians, counter-clockwise from world +x.
    pub heading_rad: f64,
    /// True speed, m/s.
    pub speed_mps: f64,
    /// True velocity, world frame, m/s.
    pub velocity_xy_mps: [f64; 2],
    /// Distance sensor → target centre in the ground plane, metres, when known; the report
    /// breaks the heading error down by it (the height slice thins out with range).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range_m: Option<f64>,
    /// Sliced points in the target's cluster (what ICP and the GP estimators see), when known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target_points: Option<usize>,
}

impl TruthAtScan {
    /// Truth from a world-frame velocity (heading and speed derived from it).
    pub fn from_velocity(scan: usize, velocity_xy_mps: [f64; 2]) -> Self {
        let [vx, vy] = velocity_xy_mps;
        Self {
            scan,
            heading_rad: vy.atan2(vx),
            speed_mps: vx.hypot(vy),
            velocity_xy_mps,
            range_m: None,
            target_points: None,
        }
    }
}

/// One situation's truth and every method's estimates, aligned scan by scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SituationResult {
    /// Situation name, e.g. `situation1`.
    pub name: String,
    /// Number of scans in the situation.
    pub scans: usize,
    /// Truth per scan (`scans` entries).
    pub truth: Vec<TruthAtScan>,
    /// Method → one optional estimate per scan, aligned with `truth`.
    pub methods: BTreeMap<Method, Vec<Option<MotionEstimate>>>,
}

impl SituationResult {
    /// Checks that truth and every method have exactly `scans` entries.
    pub fn validate(&self) -> Result<(), EvalError> {
        let bad = |reason: String| EvalError::BadResult {
            situation: self.name.clone(),
            reason,
        };
        if self.truth.len() != self.scans {
            return Err(bad(format!(
                "{} truth entries for {} scans",
                self.truth.len(),
                self.scans
            )));
        }
        for (method, estimates) in &self.methods {
            if estimates.len() != self.scans {
                return Err(bad(format!(
                    "method {method} has {} estimates for {} scans",
                    estimates.len(),
                    self.scans
                )));
            }
        }
        Ok(())
    }

    /// Scores every method against the truth (SPEC §6); method → metrics.
    pub fn metrics(&self) -> Result<BTreeMap<Method, MethodMetrics>, EvalError> {
        self.validate()?;
        self.methods
            .iter()
            .map(|(method, estimates)| {
                let metrics =
                    score_method(&self.truth, estimates).map_err(|err| EvalError::BadResult {
                        situation: self.name.clone(),
                        reason: format!("method {method}: {err}"),
                    })?;
                Ok((*method, metrics))
            })
            .collect()
    }
}

/// Everything the report writer needs.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct BenchmarkReport {
    /// The situations, in report order.
    pub situations: Vec<SituationResult>,
    /// Free-text notes for the report's notes section (one bullet each).
    pub notes: Vec<String>,
    /// Seconds spent per stage, for the timing table.
    pub timings: Vec<StageTiming>,
    /// Seed of the run, recorded in metrics.json when known.
    pub seed: Option<u64>,
    /// Cross-validation tables, included in `report.md` when present.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cv: Option<crate::report::CvReport>,
}
