//! Scores of one method in one situation (SPEC §6): heading RMSE and mean absolute error in degrees
//! (errors wrapped to [−180°, 180°], scored only where the true speed is at least 0.5 m/s), speed
//! RMSE and mean absolute error in m/s, coverage, and velocity end-point error in m/s.
//! RMSE and ME follow thesis eq. 4.1; "ME" is the mean of the absolute errors.

use patchflow_dataset::wrap_angle_rad;
use serde::{Deserialize, Serialize};

use crate::error::EvalError;
use crate::methods::estimate::MotionEstimate;
use crate::scene::truth_at_scan::TruthAtScan;

/// Below this true speed the heading is ill-defined and not scored (AV2's dynamic threshold).
pub const MIN_SCORED_SPEED_MPS: f64 = 0.5;

/// Signed heading error `wrap(estimate − truth)` in degrees, in [−180°, 180°).
pub fn heading_error_deg(estimate_rad: f64, truth_rad: f64) -> f64 {
    wrap_angle_rad(estimate_rad - truth_rad).to_degrees()
}

/// The scores of one method in one situation. A score over an empty set of scans is `None`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MethodMetrics {
    /// Heading RMSE, degrees, over scans with an estimate and true speed ≥ 0.5 m/s.
    pub heading_rmse_deg: Option<f64>,
    /// Mean absolute heading error, degrees, over the same scans.
    pub heading_me_deg: Option<f64>,
    /// Speed RMSE, m/s, over scans with an estimate.
    pub speed_rmse_mps: Option<f64>,
    /// Mean absolute speed error, m/s, over the same scans.
    pub speed_me_mps: Option<f64>,
    /// Share of scans with an estimate, in [0, 1].
    pub coverage: f64,
    /// Mean velocity end-point error ‖v̂ − v‖, m/s, over scans with an estimate.
    pub epe_mps: Option<f64>,
    /// Scans with an estimate.
    pub estimated_scans: usize,
    /// Scans whose heading was scored.
    pub heading_scored_scans: usize,
}

/// Scores `estimates` against `truth` (aligned scan by scan).
///
/// ```
/// use patchflow_eval::{MotionEstimate, TruthAtScan, score_method};
/// let truth = [TruthAtScan::from_velocity(0, [5.0, 0.0]), TruthAtScan::from_velocity(1, [5.0, 0.0])];
/// let estimates = [None, Some(MotionEstimate::from_velocity([0.0, 4.0]))];
/// let m = score_method(&truth, &estimates).unwrap();
/// assert!((m.heading_rmse_deg.unwrap() - 90.0).abs() < 1e-9);
/// assert!((m.coverage - 0.5).abs() < 1e-12);
/// ```
pub fn score_method(
    truth: &[TruthAtScan],
    estimates: &[Option<MotionEstimate>],
) -> Result<MethodMetrics, EvalError> {
    if truth.len() != estimates.len() {
        return Err(EvalError::BadResult {
            situation: "-".into(),
            reason: format!(
                "{} truth entries but {} estimates",
                truth.len(),
                estimates.len()
            ),
        });
    }
    let mut heading_errors_deg = Vec::new();
    let mut speed_errors_mps = Vec::new();
    let mut endpoint_errors_mps = Vec::new();
    for (t, e) in truth.iter().zip(estimates) {
        let Some(e) = e else { continue };
        if t.speed_mps >= MIN_SCORED_SPEED_MPS {
            heading_errors_deg.push(heading_error_deg(e.heading_rad, t.heading_rad));
        }
        speed_errors_mps.push(e.speed_mps - t.speed_mps);
        endpoint_errors_mps.push(
            (e.velocity_xy_mps[0] - t.velocity_xy_mps[0])
                .hypot(e.velocity_xy_mps[1] - t.velocity_xy_mps[1]),
        );
    }
    let coverage = if truth.is_empty() {
        0.0
    } else {
        speed_errors_mps.len() as f64 / truth.len() as f64
    };
    Ok(MethodMetrics {
        heading_rmse_deg: rmse(&heading_errors_deg),
        heading_me_deg: mean_abs(&heading_errors_deg),
        speed_rmse_mps: rmse(&speed_errors_mps),
        speed_me_mps: mean_abs(&speed_errors_mps),
        coverage,
        epe_mps: mean_abs(&endpoint_errors_mps),
        estimated_scans: speed_errors_mps.len(),
        heading_scored_scans: heading_errors_deg.len(),
    })
}

/// Root mean square (thesis eq. 4.1); `None` for no values.
pub fn rmse(errors: &[f64]) -> Option<f64> {
    (!errors.is_empty())
        .then(|| (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt())
}

/// Mean absolute value; `None` for no values.
pub fn mean_abs(errors: &[f64]) -> Option<f64> {
    (!errors.is_empty()).then(|| errors.iter().map(|e| e.abs()).sum::<f64>() / errors.len() as f64)
}

/// The median (the mean of the middle two of an even count); `None` for no values.
pub(crate) fn median(values: impl Iterator<Item = f64>) -> Option<f64> {
    let mut v: Vec<f64> = values.collect();
    v.sort_by(f64::total_cmp);
    let mid = v.len() / 2;
    match v.len() {
        0 => None,
        n if n.is_multiple_of(2) => Some(0.5 * (v[mid - 1] + v[mid])),
        _ => Some(v[mid]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_of_an_even_count_is_the_mean_of_the_middle_two() {
        assert_eq!(median([4.0, 1.0, 3.0, 2.0].into_iter()), Some(2.5));
        assert_eq!(median([5.0, 1.0, 3.0].into_iter()), Some(3.0));
        assert_eq!(median(std::iter::empty()), None);
    }

    fn estimate(heading_deg: f64, speed_mps: f64) -> Option<MotionEstimate> {
        let h = heading_deg.to_radians();
        Some(MotionEstimate::from_velocity([
            speed_mps * h.cos(),
            speed_mps * h.sin(),
        ]))
    }

    fn truth(scan: usize, heading_deg: f64, speed_mps: f64) -> TruthAtScan {
        let h = heading_deg.to_radians();
        TruthAtScan {
            scan,
            heading_rad: h,
            speed_mps,
            velocity_xy_mps: [speed_mps * h.cos(), speed_mps * h.sin()],
            range_m: None,
            target_points: None,
            target_hidden_ends: None,
        }
    }

    #[test]
    fn heading_errors_wrap_across_plus_minus_180_degrees() {
        assert!(
            (heading_error_deg(179f64.to_radians(), (-179f64).to_radians()) + 2.0).abs() < 1e-9
        );
        assert!(
            (heading_error_deg((-170f64).to_radians(), 170f64.to_radians()) - 20.0).abs() < 1e-9
        );
        assert!((heading_error_deg(10f64.to_radians(), 370f64.to_radians())).abs() < 1e-9);
        let e = heading_error_deg(std::f64::consts::PI, 0.0).abs();
        assert!((e - 180.0).abs() < 1e-9);
    }

    #[test]
    fn hand_computed_rmse_and_me_for_three_scans() {
        // Heading errors +2°, −4° (wrapped across ±180°), 0°; speed errors +1, −1, 0.5.
        let t = [
            truth(0, 178.0, 5.0),
            truth(1, -178.0, 5.0),
            truth(2, 90.0, 5.0),
        ];
        let e = [
            estimate(-180.0, 6.0),
            estimate(178.0, 4.0),
            estimate(90.0, 5.5),
        ];
        let m = score_method(&t, &e).unwrap();
        assert!((m.heading_rmse_deg.unwrap() - (20.0f64 / 3.0).sqrt()).abs() < 1e-9);
        assert!((m.heading_me_deg.unwrap() - 2.0).abs() < 1e-9);
        assert!((m.speed_rmse_mps.unwrap() - (2.25f64 / 3.0).sqrt()).abs() < 1e-9);
        assert!((m.speed_me_mps.unwrap() - 2.5 / 3.0).abs() < 1e-9);
        assert_eq!(m.coverage, 1.0);
    }

    #[test]
    fn headings_below_half_a_metre_per_second_are_not_scored() {
        let t = [truth(0, 0.0, 0.4), truth(1, 0.0, 0.5)];
        let e = [estimate(90.0, 0.4), estimate(10.0, 0.5)];
        let m = score_method(&t, &e).unwrap();
        assert_eq!(m.heading_scored_scans, 1);
        assert!((m.heading_rmse_deg.unwrap() - 10.0).abs() < 1e-9);
        // Speed is still scored on both scans.
        assert_eq!(m.estimated_scans, 2);
    }

    #[test]
    fn coverage_counts_scans_with_an_estimate_and_epe_is_the_velocity_difference() {
        let t = [
            truth(0, 0.0, 3.0),
            truth(1, 0.0, 3.0),
            truth(2, 0.0, 3.0),
            truth(3, 0.0, 3.0),
        ];
        let e = [None, estimate(90.0, 4.0), None, None];
        let m = score_method(&t, &e).unwrap();
        assert!((m.coverage - 0.25).abs() < 1e-12);
        assert!((m.epe_mps.unwrap() - 5.0).abs() < 1e-9); // |(0,4) − (3,0)| = 5
    }

    #[test]
    fn a_method_without_estimates_has_no_error_scores() {
        let m = score_method(&[truth(0, 0.0, 3.0)], &[None]).unwrap();
        assert!(m.heading_rmse_deg.is_none() && m.speed_me_mps.is_none() && m.epe_mps.is_none());
        assert_eq!(m.coverage, 0.0);
    }

    #[test]
    fn misaligned_lengths_are_an_error() {
        assert!(score_method(&[truth(0, 0.0, 3.0)], &[]).is_err());
    }
}
