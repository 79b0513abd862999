//! Runs a baseline method over one situation's scans and returns one optional estimate of the
//! target per scan (thesis 3.2, SPEC §6); the methods themselves run scan by scan in
//! [`BaselineTrackers`](crate::BaselineTrackers).
//!
//! - `ICP`: ICP between the target's cluster at t−1 and at t (oracle association, as the thesis).
//! - `KF`: one constant-velocity Kalman filter on the target's cluster centroid (oracle
//!   association); it coasts through scans where the target is not seen and reports nothing there.
//! - `ICP-AUTO`: clusters are linked scan to scan by nearest predicted centroid with a gate
//!   ([`CentroidAssociator`](crate::CentroidAssociator)); ICP runs between the target cluster and
//!   the cluster it was linked to.
//! - `KF-AUTO`: the multi-target tracker over all clusters
//!   ([`MultiTargetTracker`](crate::MultiTargetTracker)); the estimate is that of the confirmed
//!   track that took the target cluster.
//!
//! In the auto modes the target id is used only to read out the estimate, never to associate.

use std::collections::BTreeMap;

use crate::error::EvalError;
use crate::methods::baselines::baseline_params::BaselineParams;
use crate::methods::baselines::baseline_step::BaselineTrackers;
use crate::methods::estimate::MotionEstimate;
use crate::methods::method::Method;
use crate::methods::observation::ScanObservation;

/// The four baselines.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum BaselineMethod {
    /// ICP with oracle association.
    Icp,
    /// Kalman filter with oracle association.
    Kf,
    /// ICP with its own nearest-centroid association.
    IcpAuto,
    /// Kalman filter with its own multi-target tracking.
    KfAuto,
}

impl BaselineMethod {
    /// All four, in report order.
    pub const ALL: [Self; 4] = [Self::Kf, Self::Icp, Self::KfAuto, Self::IcpAuto];

    /// The benchmark method this baseline reports as (`ICP`, `KF`, `ICP-AUTO`, `KF-AUTO`).
    pub fn method(self) -> Method {
        match self {
            Self::Icp => Method::Icp,
            Self::Kf => Method::Kf,
            Self::IcpAuto => Method::IcpAuto,
            Self::KfAuto => Method::KfAuto,
        }
    }
}

/// Runs `method` over a situation's scans (in time order). `situation` labels errors.
pub fn run_baseline(
    method: BaselineMethod,
    situation: &str,
    scans: &[ScanObservation],
    params: &BaselineParams,
) -> Result<Vec<Option<MotionEstimate>>, EvalError> {
    Ok(run_all_baselines(situation, scans, params)?
        .remove(&method.method())
        .unwrap_or_default())
}

/// Runs all four baselines; method → per-scan estimates of the target.
pub fn run_all_baselines(
    situation: &str,
    scans: &[ScanObservation],
    params: &BaselineParams,
) -> Result<BTreeMap<Method, Vec<Option<MotionEstimate>>>, EvalError> {
    let mut trackers = BaselineTrackers::new(situation, params)?;
    let mut out: BTreeMap<Method, Vec<Option<MotionEstimate>>> = BaselineMethod::ALL
        .iter()
        .map(|m| (m.method(), Vec::with_capacity(scans.len())))
        .collect();
    for scan in scans {
        let target = scan.target_actor;
        let mut wanted = vec![false; scan.clusters.len()];
        if let Some(c) = scan.target_cluster().filter(|&c| c < wanted.len()) {
            wanted[c] = true;
        }
        let step = trackers.step(scan.clone(), &wanted)?;
        for (method, estimates) in &mut out {
            estimates.push(target.and_then(|t| step.actor_estimate(*method, t, scan)));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::baselines::baseline_step::BaselineTrackers;
    use crate::methods::observation::{ActorCluster, ClusterObservation};

    const DT: f64 = 0.1;

    /// The L-shaped visible outline of a car whose reference corner is at `corner`.
    fn car(id: usize, corner: [f64; 2]) -> ClusterObservation {
        let mut points: Vec<[f64; 2]> = (0..45)
            .map(|i| [corner[0] + i as f64 * 0.1, corner[1]])
            .collect();
        points.extend((1..18).map(|i| [corner[0] + 4.4, corner[1] + i as f64 * 0.1]));
        ClusterObservation::from_points(id, points)
    }

    /// A target at (8, 2) m/s, a parked car and a slow car; the target's index rotates in the list.
    fn situation(n: usize) -> Vec<ScanObservation> {
        (0..n)
            .map(|k| {
                let t = k as f64 * DT;
                let target = car(0, [-20.0 + 8.0 * t, 3.0 + 2.0 * t]);
                let parked = car(1, [5.0, -6.0]);
                let slow = car(2, [-10.0, -12.0 + 1.0 * t]);
                let mut clusters = vec![parked, slow];
                let target_cluster = k % 3;
                clusters.insert(target_cluster, target);
                let seen = |cluster| ActorCluster {
                    cluster,
                    points: 62,
                };
                ScanObservation {
                    scan: k,
                    stamp_secs: t,
                    sensor_xy_world: [0.0, 0.0],
                    clusters,
                    // The target is actor 7; the slow car actor 9 (the parked car has no id).
                    actors: BTreeMap::from([
                        (7, seen(target_cluster)),
                        (9, seen(if target_cluster == 2 { 1 } else { 2 })),
                    ]),
                    target_actor: Some(7),
                }
            })
            .collect()
    }

    fn velocity_error(e: &MotionEstimate) -> f64 {
        (e.velocity_xy_mps[0] - 8.0).hypot(e.velocity_xy_mps[1] - 2.0)
    }

    #[test]
    fn oracle_and_auto_icp_recover_the_target_velocity_from_the_second_scan() {
        let scans = situation(12);
        for method in [BaselineMethod::Icp, BaselineMethod::IcpAuto] {
            let estimates = run_baseline(method, "s", &scans, &BaselineParams::default()).unwrap();
            assert!(estimates[0].is_none());
            for e in &estimates[1..] {
                assert!(velocity_error(e.as_ref().unwrap()) < 1e-6, "{method:?}");
            }
        }
    }

    #[test]
    fn oracle_and_auto_kalman_converge_to_the_target_velocity() {
        let scans = situation(40);
        for method in [BaselineMethod::Kf, BaselineMethod::KfAuto] {
            let estimates = run_baseline(method, "s", &scans, &BaselineParams::default()).unwrap();
            let last = estimates.last().unwrap().as_ref().unwrap();
            assert!(velocity_error(last) < 0.2, "{method:?}: {last:?}");
        }
    }

    #[test]
    fn kf_reports_from_the_second_scan_and_kf_auto_once_its_track_is_confirmed() {
        let scans = situation(5);
        let kf = run_baseline(BaselineMethod::Kf, "s", &scans, &BaselineParams::default()).unwrap();
        assert!(kf[0].is_none() && kf[1].is_some());
        let auto = run_baseline(
            BaselineMethod::KfAuto,
            "s",
            &scans,
            &BaselineParams::default(),
        )
        .unwrap();
        assert!(auto[0].is_none() && auto[1].is_none() && auto[2].is_some());
    }

    #[test]
    fn scans_without_the_target_have_no_oracle_estimate() {
        let mut scans = situation(6);
        scans[3].actors.remove(&7);
        let icp =
            run_baseline(BaselineMethod::Icp, "s", &scans, &BaselineParams::default()).unwrap();
        assert!(icp[3].is_none() && icp[4].is_none() && icp[5].is_some());
        let kf = run_baseline(BaselineMethod::Kf, "s", &scans, &BaselineParams::default()).unwrap();
        assert!(kf[3].is_none() && kf[4].is_some());
    }

    #[test]
    fn all_baselines_are_run_under_their_report_names() {
        let all = run_all_baselines("s", &situation(4), &BaselineParams::default()).unwrap();
        let names: Vec<&str> = all.keys().map(|m| m.name()).collect();
        assert_eq!(names, ["KF", "ICP", "KF-AUTO", "ICP-AUTO"]);
        assert!(all.values().all(|v| v.len() == 4));
    }

    #[test]
    fn a_repeated_time_stamp_is_an_error_naming_the_situation_and_scan() {
        let mut scans = situation(4);
        scans[2].stamp_secs = scans[1].stamp_secs;
        let err = run_baseline(
            BaselineMethod::KfAuto,
            "situation9",
            &scans,
            &BaselineParams::default(),
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("situation9") && err.contains("scan 2"),
            "{err}"
        );
    }

    #[test]
    fn baseline_estimates_score_near_zero_error_on_a_clean_constant_velocity_target() {
        use crate::scene::result::SituationResult;
        use crate::scene::truth_at_scan::TruthAtScan;
        let scans = situation(30);
        let situation = SituationResult {
            name: "clean".into(),
            scans: scans.len(),
            truth: (0..scans.len())
                .map(|k| TruthAtScan::from_velocity(k, [8.0, 2.0]))
                .collect(),
            methods: run_all_baselines("clean", &scans, &BaselineParams::default()).unwrap(),
        };
        let metrics = situation.metrics().unwrap();
        let icp = &metrics[&Method::Icp];
        assert!(icp.heading_rmse_deg.unwrap() < 1e-6 && icp.speed_rmse_mps.unwrap() < 1e-6);
        assert!((icp.coverage - 29.0 / 30.0).abs() < 1e-12);
        // The Kalman filters start at rest, so their early scans carry the start-up error.
        assert!(metrics[&Method::Kf].heading_me_deg.unwrap() < 10.0);
        assert!((metrics[&Method::KfAuto].coverage - 28.0 / 30.0).abs() < 1e-12);
    }

    #[test]
    fn every_actor_gets_its_own_oracle_estimate_and_every_wanted_cluster_an_auto_one() {
        let mut trackers = BaselineTrackers::new("s", &BaselineParams::default()).unwrap();
        let mut last = None;
        for scan in situation(8) {
            // Only the slow car's cluster is wanted for ICP-AUTO.
            let slow = scan.actor_cluster(9).unwrap();
            let wanted: Vec<bool> = (0..3).map(|c| c == slow).collect();
            last = Some((trackers.step(scan.clone(), &wanted).unwrap(), scan));
        }
        let (step, scan) = last.unwrap();
        let slow = step.actor_estimate(Method::Icp, 9, &scan).unwrap();
        assert!((slow.velocity_xy_mps[1] - 1.0).abs() < 1e-6, "{slow:?}");
        let target = step.actor_estimate(Method::Icp, 7, &scan).unwrap();
        assert!(velocity_error(&target) < 1e-6);
        // KF-AUTO has every cluster (the parked car too, standing still); ICP-AUTO only the wanted one.
        let kf_auto = &step.clusters[&Method::KfAuto];
        assert!(kf_auto.iter().all(Option::is_some));
        let icp_auto = &step.clusters[&Method::IcpAuto];
        let slow_cluster = scan.actor_cluster(9).unwrap();
        for (c, flow) in icp_auto.iter().enumerate() {
            assert_eq!(flow.is_some(), c == slow_cluster, "cluster {c}");
        }
        // The oracle flow of a cluster is its actor's.
        let parked = (0..3)
            .find(|c| !scan.actors.values().any(|a| a.cluster == *c))
            .unwrap();
        assert!(step.cluster_flow(Method::Kf, parked).is_none());
        assert!(step.cluster_flow(Method::Kf, slow_cluster).is_some());
    }
}
