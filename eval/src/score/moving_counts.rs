//! Moving-object segmentation scored per point as the SemanticKITTI moving-object benchmark does
//! (LiDAR-MOS, Chen et al. 2021): the intersection over union of the moving class,
//! TP / (TP + FP + FN), truth from the dataset's moving labels (classes 252-259).

use serde::{Deserialize, Serialize};

/// Per-point counts of one method's moving decisions; counts of several scans add up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct MovingCounts {
    /// Moving, predicted moving.
    pub true_positives: u64,
    /// Static, predicted moving.
    pub false_positives: u64,
    /// Moving, predicted static.
    pub false_negatives: u64,
    /// Static, predicted static.
    pub true_negatives: u64,
}

impl MovingCounts {
    /// Counts one point.
    pub fn add(&mut self, predicted_moving: bool, truly_moving: bool) {
        match (predicted_moving, truly_moving) {
            (true, true) => self.true_positives += 1,
            (true, false) => self.false_positives += 1,
            (false, true) => self.false_negatives += 1,
            (false, false) => self.true_negatives += 1,
        }
    }

    /// Adds another set of counts.
    pub fn merge(&mut self, other: &Self) {
        self.true_positives += other.true_positives;
        self.false_positives += other.false_positives;
        self.false_negatives += other.false_negatives;
        self.true_negatives += other.true_negatives;
    }

    /// IoU of the moving class; `None` when no point is moving in truth or prediction.
    ///
    /// ```
    /// use patchflow_eval::MovingCounts;
    /// let mut c = MovingCounts::default();
    /// for (p, t) in [(true, true), (true, true), (true, false), (false, true), (false, false)] {
    ///     c.add(p, t);
    /// }
    /// assert_eq!(c.iou(), Some(0.5));
    /// ```
    pub fn iou(&self) -> Option<f64> {
        let union = self.true_positives + self.false_positives + self.false_negatives;
        (union > 0).then(|| self.true_positives as f64 / union as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn predicting_the_truth_scores_an_iou_of_one() {
        let mut c = MovingCounts::default();
        for t in [true, false, true, false, false] {
            c.add(t, t);
        }
        assert_eq!(c.iou(), Some(1.0));
    }

    #[test]
    fn predicting_nothing_moving_scores_zero_where_something_moves() {
        let mut c = MovingCounts::default();
        c.add(false, true);
        c.add(false, false);
        assert_eq!(c.iou(), Some(0.0));
    }

    #[test]
    fn a_scene_where_nothing_moves_and_nothing_is_predicted_has_no_iou() {
        let mut c = MovingCounts::default();
        c.add(false, false);
        assert_eq!(c.iou(), None);
    }

    #[test]
    fn merged_counts_equal_the_counts_of_all_points() {
        let points = [(true, true), (false, true), (true, false), (false, false)];
        let (mut first, mut second, mut all) = (
            MovingCounts::default(),
            MovingCounts::default(),
            MovingCounts::default(),
        );
        for (k, &(p, t)) in points.iter().enumerate() {
            if k < 2 {
                first.add(p, t);
            } else {
                second.add(p, t);
            }
            all.add(p, t);
        }
        first.merge(&second);
        assert_eq!(first, all);
    }
}
