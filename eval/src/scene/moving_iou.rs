//! Moving-object segmentation scored per point as the SemanticKITTI moving-object benchmark does
//! (LiDAR-MOS, Chen et al. 2021): the intersection over union of the moving class,
//! `IoU = TP / (TP + FP + FN)`, with a point moving when its true displacement over the sweep
//! interval exceeds [`DYNAMIC_SPEED_MPS`] × Δt (Argoverse 2's dynamic threshold) and predicted
//! moving when the method's displacement does.
//!
//! Counts of several scans and sequences merge by addition, so pooled IoUs are exact.
//! `patchflow score` reuses [`MovingIou`] on flow files.

use serde::{Deserialize, Serialize};

/// Dynamic above this true speed (Argoverse 2: 0.05 m per 0.1 s), m/s; the scene-flow
/// metrics' three-way split uses the same.
pub const DYNAMIC_SPEED_MPS: f64 = 0.5;

/// Per-point counts of the moving class.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct MovingIou {
    /// Moving and predicted moving.
    pub true_positives: u64,
    /// Static but predicted moving.
    pub false_positives: u64,
    /// Moving but predicted static.
    pub false_negatives: u64,
}

/// Whether a displacement over `dt_secs` is motion (more than `DYNAMIC_SPEED_MPS` (0.5 m/s) × Δt in the
/// ground plane and height together).
pub fn is_moving_displacement(displacement_m: [f64; 3], dt_secs: f64) -> bool {
    let [x, y, z] = displacement_m;
    (x * x + y * y + z * z).sqrt() > DYNAMIC_SPEED_MPS * dt_secs
}

impl MovingIou {
    /// Counts one point.
    pub fn add(&mut self, predicted_moving: bool, truly_moving: bool) {
        match (predicted_moving, truly_moving) {
            (true, true) => self.true_positives += 1,
            (true, false) => self.false_positives += 1,
            (false, true) => self.false_negatives += 1,
            (false, false) => {}
        }
    }

    /// Counts one point by its predicted and true displacement over `dt_secs`.
    pub fn add_displacements(&mut self, predicted_m: [f64; 3], truth_m: [f64; 3], dt_secs: f64) {
        self.add(
            is_moving_displacement(predicted_m, dt_secs),
            is_moving_displacement(truth_m, dt_secs),
        );
    }

    /// Adds another accumulator's counts.
    pub fn merge(&mut self, other: &Self) {
        self.true_positives += other.true_positives;
        self.false_positives += other.false_positives;
        self.false_negatives += other.false_negatives;
    }

    /// IoU of the moving class; `None` when no point is moving or predicted moving.
    pub fn iou(&self) -> Option<f64> {
        let union = self.true_positives + self.false_positives + self.false_negatives;
        (union > 0).then(|| self.true_positives as f64 / union as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iou_is_true_positives_over_the_union_of_predicted_and_true_moving_points() {
        let mut iou = MovingIou::default();
        iou.add(true, true);
        iou.add(true, true);
        iou.add(true, false);
        iou.add(false, true);
        iou.add(false, false);
        assert!((iou.iou().unwrap() - 0.5).abs() < 1e-12);
    }

    #[test]
    fn a_scene_without_motion_or_predicted_motion_has_no_iou() {
        let mut iou = MovingIou::default();
        iou.add(false, false);
        assert_eq!(iou.iou(), None);
    }

    #[test]
    fn a_displacement_is_motion_above_half_a_metre_per_second() {
        assert!(is_moving_displacement([0.06, 0.0, 0.0], 0.1));
        assert!(!is_moving_displacement([0.04, 0.0, 0.0], 0.1));
        let mut iou = MovingIou::default();
        iou.add_displacements([0.5, 0.0, 0.0], [0.0; 3], 0.1);
        assert_eq!(iou.false_positives, 1);
        let mut other = MovingIou::default();
        other.add_displacements([0.5, 0.0, 0.0], [0.5, 0.0, 0.0], 0.1);
        iou.merge(&other);
        assert_eq!(iou.iou(), Some(0.5));
    }
}
