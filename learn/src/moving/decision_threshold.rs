//! The probability above which a cluster is called moving: the one that maximises the moving
//! class's IoU (the LiDAR-MOS score, per point) on the training clusters, each weighed by its
//! points, from held-out probabilities.
//!
//! The classifier is fitted on as many moving as static clusters (on the raw mix, about one moving
//! cluster in thirty, its offset called nearly everything static), so its probabilities answer
//! "moving or static, even odds". A street holds far more static clusters, and at one half many
//! parked cars and bushes would be called moving. The threshold puts the natural mix back: it is
//! read off the whole training set, where the fitted clusters' probabilities are their
//! leave-one-out ones (GPML eq. 5.12, as the squashing's fit) and the rest are predictions.

/// One training cluster's held-out probability of moving and its points by true motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScoredCluster {
    /// Held-out probability that the cluster moves.
    pub probability: f64,
    /// Its points that truly move.
    pub moving_points: usize,
    /// Its points that do not.
    pub static_points: usize,
}

/// The lowest candidate threshold (even odds).
const LOWEST: f64 = 0.5;
/// The highest candidate threshold: above it too few movers would be left to say anything.
const HIGHEST: f64 = 0.99;

/// The threshold in [0.5, 0.99] (steps of 0.01) with the largest point IoU of the moving class over
/// `clusters`, and that IoU. Ties go to the lowest threshold; without any moving point, 0.5.
pub fn iou_threshold(clusters: &[ScoredCluster]) -> (f64, f64) {
    let moving: usize = clusters.iter().map(|c| c.moving_points).sum();
    let mut best = (LOWEST, 0.0);
    let steps = ((HIGHEST - LOWEST) / 0.01).round() as usize;
    for step in 0..=steps {
        let threshold = LOWEST + 0.01 * step as f64;
        let (mut tp, mut fp) = (0usize, 0usize);
        for c in clusters.iter().filter(|c| c.probability > threshold) {
            tp += c.moving_points;
            fp += c.static_points;
        }
        let union = moving + fp;
        let iou = if union == 0 {
            0.0
        } else {
            tp as f64 / union as f64
        };
        if iou > best.1 + 1e-12 {
            best = (threshold, iou);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cluster(probability: f64, moving_points: usize, static_points: usize) -> ScoredCluster {
        ScoredCluster {
            probability,
            moving_points,
            static_points,
        }
    }

    #[test]
    fn many_confident_static_clusters_raise_the_threshold_above_them() {
        // Movers at 0.97; a crowd of parked cars at 0.8: calling them moving would ruin the IoU.
        let mut clusters = vec![cluster(0.97, 100, 0); 5];
        clusters.extend(vec![cluster(0.8, 0, 100); 50]);
        let (threshold, iou) = iou_threshold(&clusters);
        assert!((0.8..0.97).contains(&threshold), "threshold {threshold}");
        assert!((iou - 1.0).abs() < 1e-12, "iou {iou}");
    }

    #[test]
    fn clean_separation_keeps_even_odds() {
        let clusters = [cluster(0.9, 50, 0), cluster(0.1, 0, 50)];
        assert_eq!(iou_threshold(&clusters), (0.5, 1.0));
    }

    #[test]
    fn no_moving_point_gives_even_odds() {
        assert_eq!(iou_threshold(&[cluster(0.7, 0, 10)]).0, 0.5);
    }
}
