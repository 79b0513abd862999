//! One method's scores in `patchflow score`, built-in or external alike: the scene-flow metrics of
//! SPEC §6, the moving-object IoU and the heading and speed of the moving objects, from running
//! sums that add up over scans and sequences.

use serde::Serialize;

use crate::error::EvalError;
use crate::methods::estimate::MotionEstimate;
use crate::scene::metrics::{MIN_SCORED_SPEED_MPS, MethodMetrics, score_method};
use crate::scene::moving_iou::MovingIou;
use crate::scene::scene_flow::{SceneFlowMetrics, SceneFlowTally};
use crate::scene::truth_at_scan::TruthAtScan;

/// Where a method's rows come from.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MethodSource {
    /// A prediction folder, scored from its files.
    Predictions(String),
    /// A method built into patchflow, evaluated on the dataset by `evaluate`'s code.
    BuiltIn,
    /// A built-in method that reads the truth association (an upper bound, not ranked).
    Oracle,
}

/// Running sums of one method.
#[derive(Debug, Clone)]
pub struct MethodTally {
    /// Where the method comes from.
    pub source: MethodSource,
    /// Whether its estimates have a heading (not ZERO-FLOW).
    pub has_heading: bool,
    /// Scene flow on the scored points.
    pub flow: SceneFlowTally,
    /// Moving-object segmentation by a prediction folder's own `moving/` mask (without one, the
    /// scene-flow tally's decision by predicted displacement counts).
    pub mask: Option<MovingIou>,
    /// Moving objects' truth at every scan they were scored ...
    pub object_truth: Vec<TruthAtScan>,
    /// ... and the method's estimate for each.
    pub object_estimates: Vec<Option<MotionEstimate>>,
}

/// One method's scores.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MethodScores {
    /// Where the method comes from.
    pub source: MethodSource,
    /// Scene-flow metrics on the scored points.
    pub scene_flow: SceneFlowMetrics,
    /// IoU of the moving class, per point (`None`: nothing moving in truth or prediction): by
    /// the folder's `moving/` mask where it has one, else by the predicted displacement.
    pub moving_iou: Option<f64>,
    /// Whether the IoU comes from a `moving/` mask.
    pub moving_from_mask: bool,
    /// Moving object scans scored (true speed at least 0.5 m/s).
    pub object_scans: usize,
    /// Heading and speed of the moving objects, as the per-target tables score them.
    pub objects: MethodMetrics,
}

impl MethodTally {
    /// An empty tally.
    pub fn new(source: MethodSource, has_heading: bool) -> Self {
        Self {
            source,
            has_heading,
            flow: SceneFlowTally::default(),
            mask: None,
            object_truth: Vec::new(),
            object_estimates: Vec::new(),
        }
    }

    /// Adds the object scans whose truth moves (the heading is undefined for standing ones).
    pub fn add_objects(&mut self, truth: &[TruthAtScan], estimates: &[Option<MotionEstimate>]) {
        for (t, e) in truth.iter().zip(estimates) {
            if t.speed_mps >= MIN_SCORED_SPEED_MPS {
                self.object_truth.push(*t);
                self.object_estimates.push(*e);
            }
        }
    }

    /// Adds another tally of the same method (another sequence).
    pub fn merge(&mut self, other: &Self) {
        self.flow.merge(&other.flow);
        match (&mut self.mask, &other.mask) {
            (Some(a), Some(b)) => a.merge(b),
            (None, Some(b)) => self.mask = Some(*b),
            _ => {}
        }
        self.object_truth.extend(&other.object_truth);
        self.object_estimates.extend(&other.object_estimates);
    }

    /// The scores.
    pub fn scores(&self) -> Result<MethodScores, EvalError> {
        let mut objects = score_method(&self.object_truth, &self.object_estimates)?;
        if !self.has_heading {
            objects.heading_rmse_deg = None;
            objects.heading_me_deg = None;
        }
        let scene_flow = self.flow.metrics();
        Ok(MethodScores {
            source: self.source.clone(),
            scene_flow,
            moving_iou: self.mask.map_or(scene_flow.moving_iou, |m| m.iou()),
            moving_from_mask: self.mask.is_some(),
            object_scans: self.object_truth.len(),
            objects,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standing_objects_are_left_out_of_the_heading_and_speed_scores() {
        let mut tally = MethodTally::new(MethodSource::BuiltIn, true);
        let truth = [
            TruthAtScan::from_velocity(0, [5.0, 0.0]),
            TruthAtScan::from_velocity(1, [0.0, 0.0]),
        ];
        let estimate = Some(MotionEstimate::from_velocity([0.0, 5.0]));
        tally.add_objects(&truth, &[estimate, estimate]);
        let scores = tally.scores().unwrap();
        assert_eq!(scores.object_scans, 1);
        assert!((scores.objects.heading_rmse_deg.unwrap() - 90.0).abs() < 1e-9);
    }

    #[test]
    fn a_method_without_heading_reports_none() {
        let mut tally = MethodTally::new(MethodSource::BuiltIn, false);
        let truth = [TruthAtScan::from_velocity(0, [5.0, 0.0])];
        tally.add_objects(&truth, &[Some(MotionEstimate::from_velocity([0.0, 0.0]))]);
        let scores = tally.scores().unwrap();
        assert_eq!(scores.objects.heading_rmse_deg, None);
        assert!((scores.objects.speed_rmse_mps.unwrap() - 5.0).abs() < 1e-12);
    }
}
