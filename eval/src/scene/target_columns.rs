//! The per-target tables' columns (thesis 4.4): at each scan, each method's estimate of the
//! situation's target. The GPs' merged readouts (and their `+MOS` form), GP-KF and GP-ICP run on
//! the target alone with no moving decision, and the baselines' estimates of the target actor.

use std::collections::BTreeMap;

use patchflow_learn::{ClusterEstimate, GpKind};

use crate::error::EvalError;
use crate::methods::baselines::baseline_method::BaselineMethod;
use crate::methods::baselines::baseline_step::BaselineScan;
use crate::methods::estimate::{MotionEstimate, to_estimate};
use crate::methods::learned::learned_target::LearnedTargetTrackers;
use crate::methods::method::{GpReadout, Method};
use crate::methods::observation::ScanObservation;

/// Per method, its estimate of the target at each scan so far.
pub(crate) type TargetColumns = BTreeMap<Method, Vec<Option<MotionEstimate>>>;

/// Appends one scan's estimates of the target to `columns`. `target_gp`: each estimator's estimate
/// of the target's cluster, GP-KF and GP-ICP reading the one at `tracked`; `target_moving`: the
/// moving classifier's decision on it, when `with_classifier`.
pub(crate) fn push_target_estimates(
    columns: &mut TargetColumns,
    (target_gp, tracked): (Vec<(GpKind, ClusterEstimate)>, usize),
    (with_classifier, target_moving): (bool, Option<bool>),
    target_trackers: &mut LearnedTargetTrackers,
    observation: &ScanObservation,
    baseline: &BaselineScan,
) -> Result<(), EvalError> {
    let target_gp_all = target_gp.get(tracked).and_then(|(_, e)| e.all);
    for (kind, estimate) in target_gp {
        for (rule, motion) in [
            (patchflow_learn::MergeRule::All, estimate.all),
            (patchflow_learn::MergeRule::Best, estimate.best),
        ] {
            let method = Method::gp(kind, GpReadout::Merged(rule));
            let column = columns.entry(method).or_default();
            column.push(motion.map(to_estimate));
        }
        if with_classifier {
            let all = estimate.all.map(to_estimate);
            let decided = match target_moving {
                Some(false) => Some(MotionEstimate::at_rest(all.map_or(0.0, |e| e.heading_rad))),
                _ => all,
            };
            let column = columns.entry(Method::gp_decided(kind)).or_default();
            column.push(decided);
        }
    }
    // GP-KF and GP-ICP on the target with no moving decision, as the baselines' rows.
    let gp = target_gp_all.map(to_estimate);
    for (method, estimate) in target_trackers.step(observation, gp)? {
        let column = columns.entry(method).or_default();
        column.push(estimate);
    }
    for baseline_method in BaselineMethod::ALL {
        let method = baseline_method.method();
        let estimate = observation
            .target_actor
            .and_then(|t| baseline.actor_estimate(method, t, observation));
        columns.entry(method).or_default().push(estimate);
    }
    Ok(())
}
