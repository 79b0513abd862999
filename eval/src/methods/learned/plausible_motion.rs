//! A model's whole-scan prediction checked before anything scores, tracks or plots it: a broken
//! model file (a target transform of 1e200, say) predicts astronomical or non-finite speeds, and
//! those would print 300-digit numbers into reports, `null` into metrics.json and hang the
//! plotting library (issue 26). The bound is `flow`'s: no road user moves at 1000 m/s.

use patchflow_learn::ScanMotion;

/// Fastest believable predicted speed, m/s (the bound `flow` and `score` use as well).
pub(crate) const MAX_PREDICTED_MPS: f64 = 1000.0;

/// Why `motion` is not believable, or `None` when every cluster's and point's heading is finite
/// and its speed finite and at most [`MAX_PREDICTED_MPS`].
pub(crate) fn implausible_motion(motion: &ScanMotion) -> Option<String> {
    let bad = |heading_rad: f64, speed_mps: f64| {
        !heading_rad.is_finite() || !speed_mps.is_finite() || speed_mps.abs() > MAX_PREDICTED_MPS
    };
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
        .map(|(what, heading, speed)| {
            format!(
                "the model predicts a speed of {speed} m/s at heading {heading} rad for {what} \
                 (more than {MAX_PREDICTED_MPS} m/s, or not a number): the model file is broken"
            )
        })
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
    fn a_speed_that_is_not_a_number_is_refused() {
        assert!(implausible_motion(&motion(f64::NAN)).is_some());
    }
}
