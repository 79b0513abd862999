//! One reading of a check: one method's errors on one check's target in one world with one
//! model, and whether they are within the bar (heading RMSE under 25°, speed RMSE under 1.5 m/s;
//! a method that gave no estimate, or none that could be scored, is a miss).

use serde::Serialize;

use crate::bench::{heading_under_bar, speed_under_bar};
use crate::error::EvalError;
use crate::methods::method::Method;
use crate::scene::metrics::score_method;
use crate::scene::result::SituationResult;

/// One method's errors on one check's target, one world, one model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TargetReading {
    /// The check (its scenario's and sequence's name).
    pub check: String,
    /// The world seed it was simulated with.
    pub world: u64,
    /// The model file read (as given on the command line).
    pub model: String,
    /// The method (`SPGP-HET-ALL`, `GP-KF`, …).
    pub method: String,
    /// Heading RMSE, degrees (absent: no scan could be scored).
    pub heading_rmse_deg: Option<f64>,
    /// Speed RMSE, m/s (absent: no estimate).
    pub speed_rmse_mps: Option<f64>,
    /// Share of the target's scans with an estimate.
    pub coverage: f64,
    /// Heading and speed both under the bar.
    pub within_bar: bool,
}

/// The methods a check reads for each model, with the names its readings carry: the model's own
/// ALL read-out (thesis eq. 3.35, the per-scan estimator), GP-KF (that GP through a track) and,
/// for reference, the two baselines that find the target's cluster themselves. GP-KF reading
/// another model than the default's SPGP-HET is named after it (`GP-KF (thesis)`,
/// `GP-KF (SPGP-ALL)`), so that a tally never pools two models' tracks under one name.
pub fn checked_methods(model_readout: Method) -> [(Method, String); 4] {
    let tracked = match model_readout {
        Method::SpgpHetAll => Method::GpKf.to_string(),
        Method::SpgpHetAllThesis => format!("{} (thesis)", Method::GpKf),
        other => format!("{} ({other})", Method::GpKf),
    };
    [
        (model_readout, model_readout.to_string()),
        (Method::GpKf, tracked),
        (Method::KfAuto, Method::KfAuto.to_string()),
        (Method::IcpAuto, Method::IcpAuto.to_string()),
    ]
}

/// The readings of one check's target-protocol result in one world with one model.
pub fn readings_of(
    result: &SituationResult,
    world: u64,
    model: &str,
    methods: &[(Method, String)],
) -> Result<Vec<TargetReading>, EvalError> {
    let mut readings = Vec::with_capacity(methods.len());
    for (method, name) in methods {
        let method = *method;
        let no_estimates;
        let estimates = match result.methods.get(&method) {
            Some(estimates) => estimates.as_slice(),
            None => {
                no_estimates = vec![None; result.truth.len()];
                no_estimates.as_slice()
            }
        };
        let metrics = score_method(&result.truth, estimates)?;
        let finite = |v: Option<f64>| v.filter(|v| v.is_finite());
        let (heading, speed) = (
            finite(metrics.heading_rmse_deg),
            finite(metrics.speed_rmse_mps),
        );
        readings.push(TargetReading {
            check: result.name.clone(),
            world,
            model: model.to_owned(),
            method: name.clone(),
            heading_rmse_deg: heading,
            speed_rmse_mps: speed,
            coverage: metrics.coverage,
            within_bar: heading_under_bar(heading) && speed_under_bar(speed),
        });
    }
    Ok(readings)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use std::collections::BTreeMap;

    use super::*;
    use crate::methods::estimate::MotionEstimate;
    use crate::scene::truth_at_scan::TruthAtScan;

    /// A target moving at 5 m/s along +x for four scans, read by GP-KF at `gp_kf`.
    fn result(gp_kf: Option<[f64; 2]>) -> SituationResult {
        let truth: Vec<TruthAtScan> = (0..4)
            .map(|k| TruthAtScan::from_velocity(k, [5.0, 0.0]))
            .collect();
        let mut methods = BTreeMap::new();
        let column = vec![gp_kf.map(MotionEstimate::from_velocity); 4];
        methods.insert(Method::GpKf, column);
        SituationResult {
            name: "check".into(),
            scans: 4,
            truth,
            methods,
        }
    }

    fn gp_kf() -> [(Method, String); 1] {
        [(Method::GpKf, "GP-KF".into())]
    }

    #[test]
    fn gp_kf_reading_another_model_than_the_default_is_named_after_it() {
        let name = |m: Method| checked_methods(m)[1].1.clone();
        assert_eq!(name(Method::SpgpHetAll), "GP-KF");
        assert_eq!(name(Method::SpgpHetAllThesis), "GP-KF (thesis)");
        assert_eq!(name(Method::SpgpAll), "GP-KF (SPGP-ALL)");
    }

    #[test]
    fn a_reading_within_both_bounds_is_within_the_bar() {
        let readings = readings_of(&result(Some([5.5, 0.0])), 7, "m", &gp_kf()).unwrap();
        assert!(readings[0].within_bar, "{readings:?}");
        assert!((readings[0].speed_rmse_mps.unwrap() - 0.5).abs() < 1e-9);
        assert!((readings[0].coverage - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_speed_off_by_the_bar_or_more_is_a_miss() {
        let readings = readings_of(&result(Some([6.5, 0.0])), 7, "m", &gp_kf()).unwrap();
        assert!(!readings[0].within_bar, "{readings:?}");
    }

    #[test]
    fn a_heading_off_by_the_bar_or_more_is_a_miss() {
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let velocity = [5.0 * c, 5.0 * s];
        let readings = readings_of(&result(Some(velocity)), 7, "m", &gp_kf()).unwrap();
        assert!((readings[0].heading_rmse_deg.unwrap() - 30.0).abs() < 1e-6);
        assert!(!readings[0].within_bar);
    }

    #[test]
    fn a_method_without_estimates_is_a_miss_with_no_errors() {
        let methods = checked_methods(Method::SpgpHetAll);
        let readings = readings_of(&result(None), 7, "m", &methods).unwrap();
        for reading in &readings {
            assert!(!reading.within_bar);
            assert_eq!(reading.heading_rmse_deg, None);
            assert_eq!(reading.speed_rmse_mps, None);
            assert_eq!(reading.coverage, 0.0);
        }
        assert_eq!(readings[2].method, "KF-AUTO");
    }
}
