//! What one point of a study found: per situation and method the thesis' measures (heading and
//! speed RMSE, coverage, thesis 4.4) against the point's own truth, the same pooled over the five
//! situations, and pooled by the target's number of points in the height slice (where the thesis
//! says ICP fails); beside them every method's scene flow pooled over the situations (with
//! `ZERO-FLOW`). It is the unit a sharded study writes and the merge reads.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::error::EvalError;
use crate::methods::estimate::MotionEstimate;
use crate::report::benchmark_report::BenchmarkReport;
use crate::scene::metrics::{MethodMetrics, score_method};
use crate::scene::truth_at_scan::TruthAtScan;
use crate::study::flow_scores::{FlowScores, pooled_scene_flow};
use crate::study::plan::StudyPoint;

/// Bins of the target's points in the height slice: label and upper edge (as in `report.md`).
pub const POINT_BINS: [(&str, f64); 3] = [
    ("under 50", 50.0),
    ("50-200", 200.0),
    ("200 and more", f64::INFINITY),
];

/// The three measures of a method over some scans.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scores {
    /// Heading RMSE, degrees, over scans with an estimate and a moving target.
    pub heading_rmse_deg: Option<f64>,
    /// Speed RMSE, m/s, over scans with an estimate.
    pub speed_rmse_mps: Option<f64>,
    /// Share of the scans with an estimate.
    pub coverage: f64,
    /// Scans these scores are over.
    pub scans: usize,
}

impl Scores {
    fn of(metrics: &MethodMetrics, scans: usize) -> Self {
        Self {
            heading_rmse_deg: metrics.heading_rmse_deg,
            speed_rmse_mps: metrics.speed_rmse_mps,
            coverage: metrics.coverage,
            scans,
        }
    }
}

/// One study point's results; `study.json` holds one per point, in sorted order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointResult {
    /// Position in sorted order.
    pub index: usize,
    /// Label in tables and plots.
    pub label: String,
    /// The factor's value.
    pub value: f64,
    /// Setting of the training tracks (a folder key, `default` for the scenario files' own).
    pub train: String,
    /// Setting of the evaluated situations.
    pub evaluate: String,
    /// Situation → method → scores.
    pub situations: BTreeMap<String, BTreeMap<String, Scores>>,
    /// Method → scores pooled over every scan of every situation.
    pub pooled: BTreeMap<String, Scores>,
    /// Method → scores pooled over the situations, one per [`POINT_BINS`] bin.
    pub by_points: BTreeMap<String, Vec<Scores>>,
    /// Method → scene flow (every scored point of every scan) pooled over the situations,
    /// `ZERO-FLOW` included.
    #[serde(default)]
    pub scene_flow: BTreeMap<String, FlowScores>,
}

impl PointResult {
    /// Scores a point's evaluation; only situations with a target count.
    pub fn from_report(point: &StudyPoint, report: &BenchmarkReport) -> Result<Self, EvalError> {
        let mut situations = BTreeMap::new();
        let mut all: BTreeMap<String, Vec<(TruthAtScan, Option<MotionEstimate>)>> = BTreeMap::new();
        for situation in &report.situations {
            let metrics = situation.metrics()?;
            let per_method = metrics
                .iter()
                .map(|(m, x)| (m.name().to_owned(), Scores::of(x, situation.scans)))
                .collect();
            situations.insert(situation.name.clone(), per_method);
            for (method, estimates) in &situation.methods {
                all.entry(method.name().to_owned()).or_default().extend(
                    situation
                        .truth
                        .iter()
                        .cloned()
                        .zip(estimates.iter().cloned()),
                );
            }
        }
        let names: Vec<String> = report.situations.iter().map(|s| s.name.clone()).collect();
        let scene_flow = pooled_scene_flow(report, &names);
        let mut pooled = BTreeMap::new();
        let mut by_points = BTreeMap::new();
        for (method, scans) in &all {
            pooled.insert(method.clone(), score(scans.iter())?);
            let bins = POINT_BINS
                .iter()
                .enumerate()
                .map(|(k, _)| score(scans.iter().filter(|(t, _)| bin_of(t) == Some(k))))
                .collect::<Result<Vec<_>, _>>()?;
            by_points.insert(method.clone(), bins);
        }
        Ok(Self {
            index: point.index,
            label: point.label.clone(),
            value: point.value,
            train: point.train.key(),
            evaluate: point.evaluate.key(),
            situations,
            pooled,
            by_points,
            scene_flow,
        })
    }
}

/// The [`POINT_BINS`] bin of a scan's target, if its points are known.
fn bin_of(truth: &TruthAtScan) -> Option<usize> {
    let n = truth.target_points? as f64;
    POINT_BINS.iter().position(|(_, edge)| n < *edge)
}

fn score<'a>(
    scans: impl Iterator<Item = &'a (TruthAtScan, Option<MotionEstimate>)>,
) -> Result<Scores, EvalError> {
    let (truth, estimates): (Vec<TruthAtScan>, Vec<Option<MotionEstimate>>) =
        scans.cloned().unzip();
    Ok(Scores::of(&score_method(&truth, &estimates)?, truth.len()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::synthetic_situation;
    use crate::study::plan::StudyFactor;

    fn report() -> BenchmarkReport {
        let mut situation = synthetic_situation("situation4", 30, 4);
        for (k, truth) in situation.truth.iter_mut().enumerate() {
            truth.target_points = Some(10 * k); // 0 to 290 points: all three bins
        }
        BenchmarkReport {
            situations: vec![situation, synthetic_situation("situation1", 10, 1)],
            ..BenchmarkReport::default()
        }
    }

    #[test]
    fn pooled_scores_cover_every_scan_of_every_situation() {
        let point = &StudyFactor::Rate.points()[1];
        let result = PointResult::from_report(point, &report()).unwrap();
        assert_eq!(result.situations.len(), 2);
        assert_eq!(result.pooled["KF"].scans, 40);
        assert_eq!(result.evaluate, "10hz");
    }

    #[test]
    fn the_point_bins_split_the_scans_whose_points_are_known() {
        let point = &StudyFactor::Rate.points()[0];
        let result = PointResult::from_report(point, &report()).unwrap();
        let scans: Vec<usize> = result.by_points["ICP"].iter().map(|s| s.scans).collect();
        // 0-40 points: 5 scans; 50-190: 15; 200-290: 10; situation1 knows no points.
        assert_eq!(scans, [5, 15, 10]);
    }
}
