//! One external method's running scores on one sequence: every scored point's predicted flow into
//! the same scene-flow tally the built-in methods use, its moving decision into the
//! moving-object counts, and each actor's motion derived from its points' predicted flow.

use std::collections::BTreeMap;

use patchflow_dataset::Sweep;
use patchflow_learn::SweepFeatures;

use crate::methods::estimate::MotionEstimate;
use crate::scene::moving_iou::{MovingIou, is_moving_displacement};
use crate::scene::objects::MIN_OBJECT_POINTS;
use crate::scene::scene_flow::SceneFlowTally;
use crate::scene::scene_point::ScenePoints;
use crate::scene::truth_at_scan::TruthAtScan;

/// What one method's predictions scored so far.
#[derive(Debug, Clone, Default)]
pub struct ExternalTally {
    /// Scene flow on the scored points, as `evaluate` tallies it (with its moving-object counts
    /// by predicted displacement).
    pub flow: SceneFlowTally,
    /// Moving-object segmentation by the folder's `moving/` mask, when it has one.
    pub mask: Option<MovingIou>,
    /// Every actor with enough scored points at every scan: its truth ...
    pub object_truth: Vec<TruthAtScan>,
    /// ... and the mean predicted velocity of its predicted points (`None`: none predicted).
    pub object_estimates: Vec<Option<MotionEstimate>>,
}

/// Sums of an actor's predicted velocities on one scan.
#[derive(Default)]
struct ActorSums {
    points: usize,
    predicted: usize,
    velocity_xy_mps: [f64; 2],
}

impl ExternalTally {
    /// Scores scan `scan` (sweep `sweep`, its sliced points `points` from `features`) with the
    /// predicted velocities `flow` (one per point of the sweep) and the optional moving mask.
    /// A point with no prediction (NaN) stands still and is static, as in `evaluate`. A point
    /// truly moves when its true displacement exceeds 0.5 m/s × Δt (Argoverse 2's dynamic).
    pub fn add_scan(
        &mut self,
        scan: usize,
        features: &SweepFeatures,
        sweep: &Sweep,
        points: &ScenePoints,
        flow: &[[f32; 3]],
        moving: Option<&[bool]>,
    ) {
        let mut actors: BTreeMap<u16, ActorSums> = BTreeMap::new();
        for (i, point) in features.points().iter().enumerate().take(points.len()) {
            let raw = flow[point.index];
            let predicted = raw.iter().all(|c| c.is_finite());
            let v = if predicted {
                raw.map(f64::from)
            } else {
                [0.0; 3]
            };
            let displacement = v.map(|c| c * points.dt_secs);
            self.flow.add(
                displacement,
                points.truth_m[i],
                points.class[i],
                points.dt_secs,
            );
            if let Some(mask) = moving {
                let truly = is_moving_displacement(points.truth_m[i], points.dt_secs);
                self.mask
                    .get_or_insert_with(MovingIou::default)
                    .add(mask[point.index], truly);
            }
            if points.actor[i] != 0 {
                let sums = actors.entry(points.actor[i]).or_default();
                sums.points += 1;
                if predicted {
                    sums.predicted += 1;
                    sums.velocity_xy_mps[0] += v[0];
                    sums.velocity_xy_mps[1] += v[1];
                }
            }
        }
        for actor in &sweep.objects {
            let Some(sums) = actors.get(&actor.id) else {
                continue;
            };
            if sums.points < MIN_OBJECT_POINTS {
                continue;
            }
            let [sx, sy] = features.sensor_xy();
            self.object_truth.push(TruthAtScan {
                range_m: Some((actor.centre_m[0] - sx).hypot(actor.centre_m[1] - sy)),
                target_points: Some(sums.points),
                ..TruthAtScan::from_velocity(scan, [actor.velocity_mps[0], actor.velocity_mps[1]])
            });
            let n = sums.predicted as f64;
            self.object_estimates.push(
                (sums.predicted > 0)
                    .then(|| MotionEstimate::from_velocity(sums.velocity_xy_mps.map(|s| s / n))),
            );
        }
    }
}
