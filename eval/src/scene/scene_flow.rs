//! Per-point scene-flow metrics (SPEC §6): every scored point's predicted displacement over the
//! sweep interval against the dataset's exact flow, with the metrics scene-flow papers report.
//!
//! - EPE3D: mean end-point error ‖d̂ − d‖ in metres (FlowNet3D, Liu et al. 2019; NSFP's
//!   `scene_flow_metrics`, `Lilac-Lee/Neural_Scene_Flow_Prior:utils.py`).
//! - AccStrict / AccRelax: share of points with EPE < 0.05 m / 0.10 m *or* relative error
//!   EPE/‖d‖ < 5 % / 10 %; Outliers: EPE > 0.3 m *or* relative error > 10 % (same source; the
//!   relative error divides by ‖d‖ + 1e-20, so a static point with any error counts as an outlier).
//! - Three-way EPE (Argoverse 2, `argoverse/av2-api:src/av2/evaluation/scene_flow/eval.py`): the
//!   mean of the EPE over foreground-dynamic, foreground-static and background-static points;
//!   dynamic means faster than 0.5 m/s (0.05 m per 0.1 s sweep); background-dynamic is left out.
//! - Normalised dynamic EPE (bucketed EPE, Khatri, Vedder et al. 2024,
//!   `kylevedder/BucketedSceneFlowEval:bucketed_scene_flow_eval/eval/bucketed_epe.py`): per class,
//!   points go into 50 buckets of true displacement per sweep (edges 0, 1/49, …, 1 m, then ∞);
//!   each bucket above the first scores its mean EPE divided by its mean true displacement, a
//!   class the mean over its non-empty buckets, the whole the mean over classes. A zero-flow
//!   prediction scores exactly 1; the first ("static") bucket's raw EPE is reported beside it.

use serde::{Deserialize, Serialize};

use crate::scene::moving_iou::MovingIou;
use crate::scene::scene_point::FlowClass;

/// Dynamic above this true speed (Argoverse 2: 0.05 m per 0.1 s); kept beside the IoU counts.
pub use crate::scene::moving_iou::DYNAMIC_SPEED_MPS;

/// Speed buckets of the normalised EPE: 49 up to 1 m per sweep, one above.
pub const SPEED_BUCKETS: usize = 50;

/// Running sums of one method's per-point errors; tallies of several scans merge by addition.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SceneFlowTally {
    points: u64,
    epe_sum_m: f64,
    strict: u64,
    relax: u64,
    outliers: u64,
    /// Foreground dynamic, foreground static, background static.
    threeway: [ErrorSum; 3],
    /// Per class (in `FlowClass::ALL` order) and speed bucket.
    buckets: Vec<Bucket>,
    /// Moving-object segmentation of the points (moving when displaced faster than 0.5 m/s).
    #[serde(default)]
    moving: MovingIou,
}

#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
struct ErrorSum {
    points: u64,
    epe_sum_m: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
struct Bucket {
    points: u64,
    epe_sum_m: f64,
    displacement_sum_m: f64,
}

/// The scene-flow scores of one method (`None` where no point was scored).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SceneFlowMetrics {
    /// Points scored.
    pub points: u64,
    /// Mean end-point error, metres.
    pub epe3d_m: Option<f64>,
    /// Share with EPE < 0.05 m or relative error < 5 %.
    pub acc_strict: Option<f64>,
    /// Share with EPE < 0.10 m or relative error < 10 %.
    pub acc_relax: Option<f64>,
    /// Share with EPE > 0.3 m or relative error > 10 %.
    pub outliers: Option<f64>,
    /// Mean EPE on foreground points faster than 0.5 m/s, metres.
    pub epe_fg_dynamic_m: Option<f64>,
    /// Mean EPE on the other foreground points, metres.
    pub epe_fg_static_m: Option<f64>,
    /// Mean EPE on background points no faster than 0.5 m/s, metres.
    pub epe_bg_static_m: Option<f64>,
    /// Argoverse 2 three-way EPE: the mean of the three above (of those with points), metres.
    pub epe_threeway_m: Option<f64>,
    /// Bucketed EPE: mean over classes of the mean normalised error of the dynamic buckets.
    pub normalised_dynamic_epe: Option<f64>,
    /// Bucketed EPE: mean over classes of the raw EPE of the static bucket, metres.
    pub bucketed_static_epe_m: Option<f64>,
    /// IoU of the moving class per point (LiDAR-MOS), the method's displacement read as a
    /// moving/static segmentation.
    pub moving_iou: Option<f64>,
}

impl Default for SceneFlowTally {
    fn default() -> Self {
        Self {
            points: 0,
            epe_sum_m: 0.0,
            strict: 0,
            relax: 0,
            outliers: 0,
            threeway: [ErrorSum::default(); 3],
            buckets: vec![Bucket::default(); FlowClass::ALL.len() * SPEED_BUCKETS],
            moving: MovingIou::default(),
        }
    }
}

/// ‖a − b‖ (for a zero prediction exactly ‖b‖, bit for bit).
pub fn end_point_error(predicted_m: [f64; 3], truth_m: [f64; 3]) -> f64 {
    let e = [
        predicted_m[0] - truth_m[0],
        predicted_m[1] - truth_m[1],
        predicted_m[2] - truth_m[2],
    ];
    (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt()
}

/// The speed bucket of a true displacement per sweep (metres).
fn bucket_of(displacement_m: f64) -> usize {
    if displacement_m >= 1.0 {
        SPEED_BUCKETS - 1
    } else {
        ((displacement_m * (SPEED_BUCKETS - 1) as f64).floor() as usize).min(SPEED_BUCKETS - 2)
    }
}

impl SceneFlowTally {
    /// Scores one point: predicted and true displacement over a sweep interval of `dt_secs`.
    pub fn add(
        &mut self,
        predicted_m: [f64; 3],
        truth_m: [f64; 3],
        class: FlowClass,
        dt_secs: f64,
    ) {
        let epe = end_point_error(predicted_m, truth_m);
        let displacement = end_point_error([0.0; 3], truth_m);
        let relative = epe / (displacement + 1e-20);
        self.points += 1;
        self.epe_sum_m += epe;
        self.strict += u64::from(epe < 0.05 || relative < 0.05);
        self.relax += u64::from(epe < 0.1 || relative < 0.1);
        self.outliers += u64::from(epe > 0.3 || relative > 0.1);
        let dynamic = displacement > DYNAMIC_SPEED_MPS * dt_secs;
        self.moving.add_displacements(predicted_m, truth_m, dt_secs);
        let way = match (class.is_foreground(), dynamic) {
            (true, true) => Some(0),
            (true, false) => Some(1),
            (false, false) => Some(2),
            (false, true) => None,
        };
        if let Some(way) = way {
            self.threeway[way].points += 1;
            self.threeway[way].epe_sum_m += epe;
        }
        let bucket = &mut self.buckets[class.index() * SPEED_BUCKETS + bucket_of(displacement)];
        bucket.points += 1;
        bucket.epe_sum_m += epe;
        bucket.displacement_sum_m += displacement;
    }

    /// Adds another tally's points.
    pub fn merge(&mut self, other: &Self) {
        self.points += other.points;
        self.epe_sum_m += other.epe_sum_m;
        self.strict += other.strict;
        self.relax += other.relax;
        self.outliers += other.outliers;
        for (a, b) in self.threeway.iter_mut().zip(&other.threeway) {
            a.points += b.points;
            a.epe_sum_m += b.epe_sum_m;
        }
        for (a, b) in self.buckets.iter_mut().zip(&other.buckets) {
            a.points += b.points;
            a.epe_sum_m += b.epe_sum_m;
            a.displacement_sum_m += b.displacement_sum_m;
        }
        self.moving.merge(&other.moving);
    }

    /// The moving-object segmentation counts.
    pub fn moving(&self) -> MovingIou {
        self.moving
    }

    /// Points scored so far.
    pub fn points(&self) -> u64 {
        self.points
    }

    /// The scores.
    pub fn metrics(&self) -> SceneFlowMetrics {
        let share = |count: u64| (self.points > 0).then(|| count as f64 / self.points as f64);
        let mean = |s: &ErrorSum| (s.points > 0).then(|| s.epe_sum_m / s.points as f64);
        let [fg_dynamic, fg_static, bg_static] = self.threeway.map(|s| mean(&s));
        let per_class: Vec<(Option<f64>, Option<f64>)> = FlowClass::ALL
            .iter()
            .map(|class| {
                let row = &self.buckets[class.index() * SPEED_BUCKETS..][..SPEED_BUCKETS];
                let ratios: Vec<f64> = row[1..]
                    .iter()
                    .filter(|b| b.points > 0)
                    .map(|b| b.epe_sum_m / b.displacement_sum_m)
                    .collect();
                let static_epe =
                    (row[0].points > 0).then(|| row[0].epe_sum_m / row[0].points as f64);
                (static_epe, mean_of(&ratios))
            })
            .collect();
        let statics: Vec<f64> = per_class.iter().filter_map(|c| c.0).collect();
        let dynamics: Vec<f64> = per_class.iter().filter_map(|c| c.1).collect();
        let ways: Vec<f64> = [fg_dynamic, fg_static, bg_static]
            .into_iter()
            .flatten()
            .collect();
        SceneFlowMetrics {
            points: self.points,
            epe3d_m: share(0).map(|_| self.epe_sum_m / self.points as f64),
            acc_strict: share(self.strict),
            acc_relax: share(self.relax),
            outliers: share(self.outliers),
            epe_fg_dynamic_m: fg_dynamic,
            epe_fg_static_m: fg_static,
            epe_bg_static_m: bg_static,
            epe_threeway_m: mean_of(&ways),
            normalised_dynamic_epe: mean_of(&dynamics),
            bucketed_static_epe_m: mean_of(&statics),
            moving_iou: self.moving.iou(),
        }
    }
}

fn mean_of(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

#[cfg(test)]
#[path = "scene_flow_tests.rs"]
mod tests;
