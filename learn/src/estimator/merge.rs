//! Merging per-point predictions into one estimate per cluster (thesis 3.1.4).
//!
//! ALL multiplies every prediction's Gaussian (eqs. 3.35-3.37): the result is a vote weighted by
//! inverse variance. BEST first fits a Gaussian to the predicted variances and keeps only the
//! predictions whose variance lies more than one standard deviation below their mean (the
//! BEST-merge rule, on raw variances; cross-validation's low-log-variance rule differs, see
//! [`best_merge_subset`]), then multiplies those; when none qualifies it falls back to ALL.
//!
//! Headings are merged in the world frame as 2-D Gaussians over the unit vector
//! (cos α, sin α): each point's prediction relative to its own bearing is rotated by that bearing,
//! its covariance with it, and the product of 2-D Gaussians (the vector form of eqs. 3.36-3.37)
//! gives the merged vector, whose angle is the heading. Merging angles directly would break at ±π.

use nalgebra::{Matrix2, Vector2};

/// How per-point predictions of one cluster are combined (thesis 3.1.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum MergeRule {
    /// Product of all Gaussians (eqs. 3.35-3.37).
    All,
    /// Product of the predictions whose variance is below mean − 1 std of the variances.
    Best,
}

/// One scalar Gaussian prediction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gaussian {
    /// Mean.
    pub mean: f64,
    /// Variance (must be positive and finite to take part).
    pub var: f64,
}

/// One point's heading prediction, already rotated into the world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadingVote {
    /// Mean of (cos α, sin α) in the world frame.
    pub mean: Vector2<f64>,
    /// Covariance of that vector in the world frame.
    pub cov: Matrix2<f64>,
}

impl HeadingVote {
    /// Turns a prediction of (sin, cos) of the heading relative to the bearing into a world vote.
    ///
    /// `bearing_rad` is the world-frame direction sensor → point; the relative angle is
    /// α − bearing, so the world vector is the relative one rotated by the bearing.
    pub fn from_relative(bearing_rad: f64, sin_rel: Gaussian, cos_rel: Gaussian) -> Self {
        let (s, c) = bearing_rad.sin_cos();
        let rotation = Matrix2::new(c, -s, s, c);
        let mean = rotation * Vector2::new(cos_rel.mean, sin_rel.mean);
        let cov =
            rotation * Matrix2::new(cos_rel.var, 0.0, 0.0, sin_rel.var) * rotation.transpose();
        Self { mean, cov }
    }

    /// This vote's own heading (the angle of its mean vector) and the delta-method variance,
    /// `None` when the vector has no direction.
    pub fn heading(&self) -> Option<(f64, f64)> {
        angle_of(self.mean, &self.cov)
    }

    /// Scalar spread used to rank votes for BEST: the trace of the covariance.
    fn spread(&self) -> f64 {
        self.cov.trace()
    }
}

/// A merged heading: angle CCW from world +x and an approximate angular variance (rad²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MergedHeading {
    /// Heading, radians in (−π, π].
    pub heading_rad: f64,
    /// Variance of the heading by the delta method, rad².
    pub var_rad2: f64,
    /// Number of votes that took part.
    pub votes: usize,
}

/// Merges scalar predictions (eqs. 3.35-3.37); `None` if no prediction has a usable variance.
pub fn merge_scalar(predictions: &[Gaussian], rule: MergeRule) -> Option<Gaussian> {
    let usable: Vec<Gaussian> = predictions
        .iter()
        .copied()
        .filter(|g| usable_var(g.var) && g.mean.is_finite())
        .collect();
    let chosen = best_merge_subset(&usable, |g| g.var, rule);
    let precision: f64 = chosen.iter().map(|g| 1.0 / g.var).sum();
    if chosen.is_empty() || !precision.is_finite() || precision <= 0.0 {
        return None;
    }
    let var = 1.0 / precision; // eq. 3.36
    let mean = chosen.iter().map(|g| var * g.mean / g.var).sum(); // eq. 3.37
    Some(Gaussian { mean, var })
}

/// Merges world-frame heading votes by the product of 2-D Gaussians; `None` if none is usable
/// or the merged vector has no direction.
pub fn merge_heading(votes: &[HeadingVote], rule: MergeRule) -> Option<MergedHeading> {
    let usable: Vec<(HeadingVote, Matrix2<f64>)> = votes
        .iter()
        .filter(|v| v.mean.iter().all(|x| x.is_finite()) && usable_var(v.spread()))
        .filter_map(|v| v.cov.try_inverse().map(|info| (*v, info)))
        .collect();
    let chosen = best_merge_subset(&usable, |(v, _)| v.spread(), rule);
    if chosen.is_empty() {
        return None;
    }
    let information: Matrix2<f64> = chosen.iter().map(|(_, info)| info).sum();
    let cov = information.try_inverse()?;
    let mean = cov
        * chosen
            .iter()
            .map(|(v, info)| info * v.mean)
            .sum::<Vector2<f64>>();
    let (heading_rad, var_rad2) = angle_of(mean, &cov)?;
    Some(MergedHeading {
        heading_rad,
        var_rad2,
        votes: chosen.len(),
    })
}

/// The angle of a 2-D Gaussian's mean vector and its variance by the delta method; `None` when
/// the mean has no direction.
fn angle_of(mean: Vector2<f64>, cov: &Matrix2<f64>) -> Option<(f64, f64)> {
    let norm2 = mean.norm_squared();
    if norm2.is_nan() || norm2 <= 1e-12 {
        return None;
    }
    // Delta method: the angle's gradient w.r.t. (x, y) is (−y, x) / |m|².
    let gradient = Vector2::new(-mean.y, mean.x) / norm2;
    let var_rad2 = (gradient.transpose() * cov * gradient)[(0, 0)];
    Some((mean.y.atan2(mean.x), var_rad2))
}

fn usable_var(var: f64) -> bool {
    var.is_finite() && var > 0.0
}

/// ALL keeps everything; BEST keeps the items whose spread is below mean − 1 std of the raw
/// spreads (thesis 3.1.4), falling back to everything when none qualifies.
///
/// This is the *BEST-merge rule*, on raw variances as the thesis states it; cross-validation's
/// *low-log-variance rule* (`eval/src/cv_fold.rs`, thesis 4.3.1) fits its Gaussian to
/// log variances instead. They differ on purpose: the merge falls back to ALL when its subset is
/// empty, so an empty subset costs nothing, while cross-validation has no fallback and on
/// right-skewed map-patch variances the raw rule leaves its subset empty.
fn best_merge_subset<T: Copy>(items: &[T], spread: impl Fn(&T) -> f64, rule: MergeRule) -> Vec<T> {
    if rule == MergeRule::All || items.len() < 2 {
        return items.to_vec();
    }
    let n = items.len() as f64;
    let mean = items.iter().map(&spread).sum::<f64>() / n;
    let std = (items
        .iter()
        .map(|x| (spread(x) - mean).powi(2))
        .sum::<f64>()
        / n)
        .sqrt();
    let best: Vec<T> = items
        .iter()
        .copied()
        .filter(|x| spread(x) < mean - std)
        .collect();
    if best.is_empty() {
        items.to_vec()
    } else {
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn g(mean: f64, var: f64) -> Gaussian {
        Gaussian { mean, var }
    }

    #[test]
    fn all_merge_is_the_inverse_variance_weighted_mean() {
        let merged =
            merge_scalar(&[g(1.0, 1.0), g(3.0, 1.0), g(10.0, 4.0)], MergeRule::All).unwrap();
        let var = 1.0 / (1.0 + 1.0 + 0.25);
        assert!((merged.var - var).abs() < 1e-12);
        assert!((merged.mean - var * (1.0 + 3.0 + 2.5)).abs() < 1e-12);
    }

    #[test]
    fn best_merge_keeps_only_predictions_a_std_below_the_mean_variance() {
        let predictions = [
            g(5.0, 0.1),
            g(0.0, 1.0),
            g(0.0, 1.0),
            g(0.0, 1.0),
            g(0.0, 1.1),
        ];
        let merged = merge_scalar(&predictions, MergeRule::Best).unwrap();
        assert!((merged.mean - 5.0).abs() < 1e-12 && (merged.var - 0.1).abs() < 1e-12);
    }

    #[test]
    fn best_merge_falls_back_to_all_when_variances_are_equal() {
        let predictions = [g(1.0, 0.5), g(2.0, 0.5)];
        let best = merge_scalar(&predictions, MergeRule::Best).unwrap();
        let all = merge_scalar(&predictions, MergeRule::All).unwrap();
        assert_eq!(best, all);
    }

    #[test]
    fn unusable_variances_are_ignored_and_none_left_gives_none() {
        assert!(
            merge_scalar(
                &[g(1.0, 0.0), g(f64::NAN, 1.0), g(2.0, f64::INFINITY)],
                MergeRule::All
            )
            .is_none()
        );
        let merged = merge_scalar(&[g(1.0, 0.0), g(2.0, 0.5)], MergeRule::All).unwrap();
        assert_eq!(merged.mean, 2.0);
    }

    #[test]
    fn relative_headings_from_different_bearings_merge_to_the_common_world_heading() {
        let world_heading = 3.0_f64; // close to π, where naive angle averaging breaks
        let votes: Vec<HeadingVote> = [-1.2, 0.3, 2.9]
            .iter()
            .map(|&bearing: &f64| {
                let rel = world_heading - bearing;
                HeadingVote::from_relative(bearing, g(rel.sin(), 0.05), g(rel.cos(), 0.05))
            })
            .collect();
        let merged = merge_heading(&votes, MergeRule::All).unwrap();
        assert!(
            (merged.heading_rad - world_heading).abs() < 1e-9,
            "{merged:?}"
        );
        assert_eq!(merged.votes, 3);
    }

    #[test]
    fn a_confident_vote_outweighs_a_vague_one() {
        let confident = HeadingVote::from_relative(0.0, g(0.0, 0.01), g(1.0, 0.01)); // heading 0
        let vague = HeadingVote::from_relative(0.0, g(1.0, 1.0), g(0.0, 1.0)); // heading π/2
        let merged = merge_heading(&[confident, vague], MergeRule::All).unwrap();
        assert!(merged.heading_rad.abs() < 0.02, "{merged:?}");
    }

    #[test]
    fn opposite_votes_of_equal_weight_have_no_direction() {
        let east = HeadingVote::from_relative(0.0, g(0.0, 0.1), g(1.0, 0.1));
        let west = HeadingVote::from_relative(0.0, g(0.0, 0.1), g(-1.0, 0.1));
        assert!(merge_heading(&[east, west], MergeRule::All).is_none());
    }
}
