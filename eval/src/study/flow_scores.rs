//! The whole-scene side of a study point: every method's scene flow (per-point end-point error
//! over every scored point of every scan) pooled over the situations. It is where `ZERO-FLOW`
//! belongs in a study: it moves nothing, so it has no heading and no target estimate for the
//! per-target tables, but its scene-flow EPE is the floor every method must beat.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::report::benchmark_report::BenchmarkReport;
use crate::scene::scene_flow::SceneFlowTally;

/// One method's scene flow over some sequences.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlowScores {
    /// Mean end-point error over every scored point, metres per sweep interval.
    pub epe3d_m: Option<f64>,
    /// Argoverse 2 three-way EPE (foreground dynamic, foreground static, background), metres.
    pub epe_threeway_m: Option<f64>,
    /// Mean EPE on foreground points faster than 0.5 m/s, metres.
    pub epe_fg_dynamic_m: Option<f64>,
    /// Share of points with EPE < 0.10 m or relative error < 10 %.
    pub acc_relax: Option<f64>,
    /// Points scored.
    pub points: u64,
}

/// Method → scene flow pooled over the report's sequences named in `sequences` (the tallies of
/// every scan added, so a long situation weighs by its points).
pub(crate) fn pooled_scene_flow(
    report: &BenchmarkReport,
    sequences: &[String],
) -> BTreeMap<String, FlowScores> {
    let mut tallies: BTreeMap<String, SceneFlowTally> = BTreeMap::new();
    for scene in report.scenes.iter().filter(|s| sequences.contains(&s.name)) {
        for (method, tally) in &scene.scene_flow {
            tallies
                .entry(method.name().to_owned())
                .or_default()
                .merge(tally);
        }
    }
    tallies
        .into_iter()
        .map(|(method, tally)| {
            let m = tally.metrics();
            let scores = FlowScores {
                epe3d_m: m.epe3d_m,
                epe_threeway_m: m.epe_threeway_m,
                epe_fg_dynamic_m: m.epe_fg_dynamic_m,
                acc_relax: m.acc_relax,
                points: m.points,
            };
            (method, scores)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::method::Method;
    use crate::scene::result::SceneResult;
    use crate::scene::scene_point::FlowClass;

    /// A scene of `points` car points moving 0.5 m per sweep: KF-AUTO off by 0.1 m, ZERO-FLOW
    /// by the whole move.
    fn scene(name: &str, points: usize) -> SceneResult {
        let mut scene_flow: BTreeMap<Method, SceneFlowTally> = BTreeMap::new();
        for _ in 0..points {
            let truth = [0.5, 0.0, 0.0];
            for (method, predicted) in [
                (Method::KfAuto, [0.4, 0.0, 0.0]),
                (Method::ZeroFlow, [0.0; 3]),
            ] {
                scene_flow
                    .entry(method)
                    .or_default()
                    .add(predicted, truth, FlowClass::Car, 0.1);
            }
        }
        SceneResult {
            name: name.into(),
            scans: 1,
            scene_flow,
            ..SceneResult::default()
        }
    }

    fn report() -> BenchmarkReport {
        BenchmarkReport {
            scenes: vec![
                scene("situation1", 30),
                scene("situation4", 20),
                scene("dense", 7),
            ],
            ..BenchmarkReport::default()
        }
    }

    #[test]
    fn pooling_adds_the_points_of_the_named_sequences_only() {
        let one = pooled_scene_flow(&report(), &["situation1".into()]);
        let both = pooled_scene_flow(&report(), &["situation1".into(), "situation4".into()]);
        assert_eq!(one["KF-AUTO"].points, 30);
        assert_eq!(both["KF-AUTO"].points, 50);
    }

    #[test]
    fn zero_flow_is_pooled_with_the_whole_move_as_its_error() {
        let flow = pooled_scene_flow(&report(), &["situation1".into(), "situation4".into()]);
        let zero = flow["ZERO-FLOW"].epe3d_m.unwrap();
        let kf = flow["KF-AUTO"].epe3d_m.unwrap();
        assert!((zero - 0.5).abs() < 1e-12, "{zero}");
        assert!((kf - 0.1).abs() < 1e-9, "{kf}");
    }
}
