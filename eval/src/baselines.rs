//! Runs a baseline method over one situation's scans and returns one optional estimate per scan
//! (thesis 3.2, SPEC §6).
//!
//! - `ICP`: ICP between the target's cluster at t−1 and at t (oracle association, as the thesis).
//! - `KF`: one constant-velocity Kalman filter on the target's cluster centroid (oracle
//!   association); it coasts through scans where the target is not seen and reports nothing there.
//! - `ICP-AUTO`: clusters are linked scan to scan by nearest predicted centroid with a gate
//!   ([`CentroidAssociator`]); ICP runs between the target cluster and the cluster it was linked to.
//! - `KF-AUTO`: the multi-target tracker over all clusters ([`MultiTargetTracker`]); the estimate is
//!   that of the confirmed track that took the target cluster.
//!
//! In the auto modes the target id is used only to read out the estimate, never to associate.

use std::collections::BTreeMap;

use crate::cluster_association::{CentroidAssociationParams, CentroidAssociator};
use crate::error::EvalError;
use crate::estimate::MotionEstimate;
use crate::icp::IcpParams;
use crate::kalman::{ConstantVelocityKalman, KalmanParams};
use crate::method::Method;
use crate::observation::ScanObservation;
use crate::rigid_motion::icp_motion_estimate;
use crate::tracker::{MultiTargetTracker, TrackStatus, TrackerParams};

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

/// Parameters of all baselines.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BaselineParams {
    /// ICP (both modes).
    pub icp: IcpParams,
    /// Kalman filter of `KF`.
    pub kalman: KalmanParams,
    /// Tracker of `KF-AUTO`.
    pub tracker: TrackerParams,
    /// Association of `ICP-AUTO`.
    pub association: CentroidAssociationParams,
}

/// Runs `method` over a situation's scans (in time order). `situation` labels errors.
pub fn run_baseline(
    method: BaselineMethod,
    situation: &str,
    scans: &[ScanObservation],
    params: &BaselineParams,
) -> Result<Vec<Option<MotionEstimate>>, EvalError> {
    check_stamps(situation, scans)?;
    let label = |err: EvalError| match err {
        EvalError::BadObservation { scan, reason, .. } => EvalError::BadObservation {
            situation: situation.to_owned(),
            scan,
            reason,
        },
        other => other,
    };
    match method {
        BaselineMethod::Icp => Ok(run_icp_oracle(scans, &params.icp)),
        BaselineMethod::Kf => run_kf_oracle(scans, params.kalman),
        BaselineMethod::IcpAuto => run_icp_auto(scans, params).map_err(label),
        BaselineMethod::KfAuto => run_kf_auto(scans, params.tracker).map_err(label),
    }
}

/// Runs all four baselines; method → per-scan estimates.
pub fn run_all_baselines(
    situation: &str,
    scans: &[ScanObservation],
    params: &BaselineParams,
) -> Result<BTreeMap<Method, Vec<Option<MotionEstimate>>>, EvalError> {
    BaselineMethod::ALL
        .iter()
        .map(|m| Ok((m.method(), run_baseline(*m, situation, scans, params)?)))
        .collect()
}

fn run_icp_oracle(scans: &[ScanObservation], params: &IcpParams) -> Vec<Option<MotionEstimate>> {
    let mut estimates = vec![None];
    for pair in scans.windows(2) {
        let (previous, current) = (&pair[0], &pair[1]);
        let estimate = match (previous.target(), current.target()) {
            (Some(p), Some(c)) => icp_motion_estimate(
                &p.points_xy_world,
                &c.points_xy_world,
                current.stamp_secs - previous.stamp_secs,
                params,
            ),
            _ => None,
        };
        estimates.push(estimate);
    }
    estimates.truncate(scans.len());
    estimates
}

fn run_kf_oracle(
    scans: &[ScanObservation],
    params: KalmanParams,
) -> Result<Vec<Option<MotionEstimate>>, EvalError> {
    let mut filter: Option<ConstantVelocityKalman> = None;
    let mut last_stamp = 0.0;
    let mut estimates = Vec::with_capacity(scans.len());
    for scan in scans {
        if let Some(kf) = filter.as_mut() {
            kf.predict(scan.stamp_secs - last_stamp);
        }
        last_stamp = scan.stamp_secs;
        let Some(target) = scan.target() else {
            estimates.push(None);
            continue;
        };
        match filter.as_mut() {
            Some(kf) => {
                kf.update(target.centroid_xy)?;
            }
            None => filter = Some(ConstantVelocityKalman::new(target.centroid_xy, params)?),
        }
        estimates.push(filter.as_ref().and_then(ConstantVelocityKalman::estimate));
    }
    Ok(estimates)
}

fn run_icp_auto(
    scans: &[ScanObservation],
    params: &BaselineParams,
) -> Result<Vec<Option<MotionEstimate>>, EvalError> {
    let mut associator = CentroidAssociator::new(params.association);
    let mut estimates = Vec::with_capacity(scans.len());
    let mut previous: Option<&ScanObservation> = None;
    for scan in scans {
        let links = associator.step(scan)?;
        let estimate = previous.and_then(|prev| {
            let target_index = scan.target_cluster?;
            let previous_index = (*links.get(target_index)?)?;
            icp_motion_estimate(
                &prev.clusters.get(previous_index)?.points_xy_world,
                &scan.clusters.get(target_index)?.points_xy_world,
                scan.stamp_secs - prev.stamp_secs,
                &params.icp,
            )
        });
        estimates.push(estimate);
        previous = Some(scan);
    }
    Ok(estimates)
}

fn run_kf_auto(
    scans: &[ScanObservation],
    params: TrackerParams,
) -> Result<Vec<Option<MotionEstimate>>, EvalError> {
    let mut tracker = MultiTargetTracker::new(params)?;
    let mut estimates = Vec::with_capacity(scans.len());
    for scan in scans {
        let centroids: Vec<[f64; 2]> = scan.clusters.iter().map(|c| c.centroid_xy).collect();
        let track_of_cluster = tracker.step(scan.scan, scan.stamp_secs, &centroids)?;
        let estimate = scan
            .target_cluster
            .and_then(|i| *track_of_cluster.get(i)?)
            .and_then(|id| tracker.track(id))
            .filter(|track| track.status == TrackStatus::Confirmed)
            .and_then(|track| track.filter.estimate());
        estimates.push(estimate);
    }
    Ok(estimates)
}

fn check_stamps(situation: &str, scans: &[ScanObservation]) -> Result<(), EvalError> {
    for pair in scans.windows(2) {
        let dt = pair[1].stamp_secs - pair[0].stamp_secs;
        if !(dt > 0.0 && dt.is_finite()) {
            return Err(EvalError::BadObservation {
                situation: situation.to_owned(),
                scan: pair[1].scan,
                reason: format!(
                    "time stamp {} s does not follow {} s",
                    pair[1].stamp_secs, pair[0].stamp_secs
                ),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::observation::ClusterObservation;

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
                ScanObservation {
                    scan: k,
                    stamp_secs: t,
                    sensor_xy_world: [0.0, 0.0],
                    clusters,
                    target_cluster: Some(target_cluster),
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
        scans[3].target_cluster = None;
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
        use crate::result::{SituationResult, TruthAtScan};
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
}
