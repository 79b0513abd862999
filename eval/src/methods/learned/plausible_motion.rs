//! A model's whole-scan prediction checked before anything scores, tracks or plots it: a broken
//! model file (a target transform of 1e200, say) predicts astronomical or non-finite speeds, and
//! those would print 300-digit numbers into reports, `null` into metrics.json and hang the
//! plotting library (issue 26). The bound is `flow`'s: no road user moves at 1000 m/s.

use patchflow_learn::{ClusterEstimate, ScanMotion};

/// Fastest believable predicted speed, m/s (the bound `flow` and `score` use as well).
pub(crate) const MAX_PREDICTED_MPS: f64 = 1000.0;

/// Why a model's estimate for one cluster is not believable, or `None`: the check every
/// estimator's target estimate passes, including those of estimators trained with other feature
/// parameters than the first (they predict the target only, not the whole scan).
pub(crate) fn implausible_estimate(estimate: &ClusterEstimate, what: &str) -> Option<String> {
    [estimate.all, estimate.best]
        .into_iter()
        .flatten()
        .find(|m| bad(m.heading_rad, m.speed_mps))
        .map(|m| refusal(m.speed_mps, m.heading_rad, what))
}

fn bad(heading_rad: f64, speed_mps: f64) -> bool {
    !heading_rad.is_finite() || !speed_mps.is_finite() || speed_mps.abs() > MAX_PREDICTED_MPS
}

fn refusal(speed: f64, heading: f64, what: &str) -> String {
    format!(
        "the model predicts a speed of {speed:e} m/s at heading {heading:e} rad for {what} \
         (more than {MAX_PREDICTED_MPS} m/s, or not a number): the model file is broken"
    )
}

/// Why `motion` is not believable, or `None` when every cluster's and point's heading is finite
/// and its speed finite and at most [`MAX_PREDICTED_MPS`].
pub(crate) fn implausible_motion(motion: &ScanMotion) -> Option<String> {
    let merged = motion.clusters.iter().enumerate().flat_map(|(c, e)| {
        e.iter()
            .flat_map(|e| [e.all, e.best])
            .flatten()
            .map(move |m| (format!("cluster {c}"), m.heading_rad, m.speed_mps))
    });
    let points = motion
        .points
        .iter()
        .enumerate()
        .filter_map(|(i, p)| p.map(|p| (format!("point {i}"), p.heading_rad, p.speed_mps)));
    merged
        .chain(points)
        .find(|(_, heading, speed)| bad(*heading, *speed))
        .map(|(what, heading, speed)| refusal(speed, heading, &what))
}

#[cfg(test)]
mod tests {
    use super::*;
    use patchflow_learn::{ClusterEstimate, ClusterMotion, PointMotion};

    fn motion(speed_mps: f64) -> ScanMotion {
        let cluster = ClusterMotion {
            heading_rad: 0.3,
            heading_var: 0.1,
            speed_mps,
            speed_var: 0.2,
            heading_votes: 12,
        };
        let point = PointMotion {
            heading_rad: 0.3,
            heading_var: 0.1,
            speed_mps: 4.0,
            speed_var: 0.2,
        };
        ScanMotion {
            clusters: vec![
                None,
                Some(ClusterEstimate {
                    all: Some(cluster),
                    best: None,
                }),
            ],
            points: vec![Some(point), None],
            timing: Default::default(),
        }
    }

    #[test]
    fn a_street_speed_is_believed() {
        assert_eq!(implausible_motion(&motion(12.0)), None);
    }

    #[test]
    fn an_astronomical_speed_is_refused_naming_the_cluster() {
        let reason = implausible_motion(&motion(1e200)).unwrap();
        assert!(
            reason.contains("cluster 1") && reason.contains("1000"),
            "{reason}"
        );
    }

    #[test]
    fn a_target_estimate_of_any_estimator_is_checked_on_its_own() {
        let estimate = motion(1e200).clusters[1].unwrap();
        let reason = implausible_estimate(&estimate, "the target").unwrap();
        assert!(
            reason.contains("the target") && reason.contains("1e200"),
            "{reason}"
        );
        let street = motion(12.0).clusters[1].unwrap();
        assert_eq!(implausible_estimate(&street, "the target"), None);
    }

    #[test]
    fn a_speed_that_is_not_a_number_is_refused() {
        assert!(implausible_motion(&motion(f64::NAN)).is_some());
    }
}
