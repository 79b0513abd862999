//! The benchmark result model: per situation the ground truth at every scan and every method's
//! per-scan estimates, per sequence the whole-scene results; the whole benchmark adds notes and
//! stage timings. Plain data, serialisable.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::error::EvalError;
use crate::methods::estimate::MotionEstimate;
use crate::methods::method::Method;
use crate::scene::metrics::{MethodMetrics, score_method};
use crate::scene::objects::ObjectScan;
use crate::scene::perception_timing::ScanTiming;
use crate::scene::scene_flow::SceneFlowTally;
use crate::scene::truth_at_scan::TruthAtScan;

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

/// One sequence seen as a whole scene: scene flow of every method on every scored point, every
/// actor at every scan, and what each scan's perception cost.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct SceneResult {
    /// Sequence name.
    pub name: String,
    /// Scans evaluated.
    pub scans: usize,
    /// Per method, the per-point errors of all scans.
    pub scene_flow: BTreeMap<Method, SceneFlowTally>,
    /// Every actor with enough points at every scan.
    pub objects: Vec<ObjectScan>,
    /// Per scan, the perception's stages.
    pub timing: Vec<ScanTiming>,
}
