//! Every score the report files show, computed once: the per-target metrics of each situation
//! (thesis 4.4), per sequence each method's scene-flow metrics and its scores on the moving
//! objects, and over all sequences the object scores per group.

use std::collections::BTreeMap;

use crate::error::EvalError;
use crate::methods::method::Method;
use crate::report::benchmark_report::BenchmarkReport;
use crate::scene::metrics::MethodMetrics;
use crate::scene::objects::{ObjectGroup, ObjectMetrics, ObjectScan, score_objects};
use crate::scene::scene_flow::{SceneFlowMetrics, SceneFlowTally};

/// Metrics of every situation with a target, in report order: (name, scans, method → metrics).
pub(crate) type SituationMetrics = (String, usize, BTreeMap<Method, MethodMetrics>);

/// Everything the report files print.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ReportScores {
    /// Per-target metrics per situation.
    pub situations: Vec<SituationMetrics>,
    /// Whole-scene scores per sequence.
    pub scenes: Vec<SceneScores>,
    /// Object scores over all sequences, per group.
    pub objects: Vec<(ObjectGroup, BTreeMap<Method, ObjectMetrics>)>,
    /// Scene flow over all sequences' points.
    pub pooled_flow: BTreeMap<Method, SceneFlowMetrics>,
}

impl ReportScores {
    /// Scores a benchmark report.
    pub fn of(report: &BenchmarkReport) -> Result<Self, EvalError> {
        let situations = report
            .situations
            .iter()
            .map(|s| Ok((s.name.clone(), s.scans, s.metrics()?)))
            .collect::<Result<_, EvalError>>()?;
        let mut pooled: BTreeMap<Method, SceneFlowTally> = BTreeMap::new();
        for scene in &report.scenes {
            for (method, tally) in &scene.scene_flow {
                pooled.entry(*method).or_default().merge(tally);
            }
        }
        Ok(Self {
            situations,
            scenes: scene_scores(report),
            objects: pooled_object_scores(report),
            pooled_flow: pooled.iter().map(|(m, t)| (*m, t.metrics())).collect(),
        })
    }
}

/// One sequence's whole-scene scores.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SceneScores {
    /// Sequence name.
    pub name: String,
    /// Scans evaluated.
    pub scans: usize,
    /// Per method, the scene-flow metrics over all scored points of all scans.
    pub scene_flow: BTreeMap<Method, SceneFlowMetrics>,
    /// Per method, the scores on every moving object of the sequence (none if it had none).
    pub objects: BTreeMap<Method, ObjectMetrics>,
}

/// The scores of every sequence, in report order.
fn scene_scores(report: &BenchmarkReport) -> Vec<SceneScores> {
    report
        .scenes
        .iter()
        .map(|scene| SceneScores {
            name: scene.name.clone(),
            scans: scene.scans,
            scene_flow: scene
                .scene_flow
                .iter()
                .map(|(m, tally)| (*m, tally.metrics()))
                .collect(),
            objects: score_objects(&scene.objects, ObjectGroup::Moving).unwrap_or_default(),
        })
        .collect()
}

/// Every group of object scans over all sequences that has members, with each method's scores.
fn pooled_object_scores(
    report: &BenchmarkReport,
) -> Vec<(ObjectGroup, BTreeMap<Method, ObjectMetrics>)> {
    let objects: Vec<ObjectScan> = report
        .scenes
        .iter()
        .flat_map(|s| s.objects.iter().cloned())
        .collect();
    ObjectGroup::all()
        .into_iter()
        .filter_map(|group| Some((group, score_objects(&objects, group)?)))
        .collect()
}
