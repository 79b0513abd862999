//! Replays one situation (thesis 4.4): per scan, the maps, clusters and the target's cluster are
//! computed once and handed to every method: the GP estimators (ALL and BEST merging) and the
//! ICP and Kalman baselines (oracle and own association).

use std::collections::BTreeMap;

use patchflow_dataset::{SequenceReader, Sweep};
use patchflow_learn::{
    ClusterEstimate, ClusterMotion, GpKind, MergeRule, MotionEstimator, SweepFeatures,
};
use rayon::prelude::*;

use crate::baselines::{BaselineParams, run_all_baselines};
use crate::error::EvalError;
use crate::estimate::MotionEstimate;
use crate::method::{GpReadout, Method};
use crate::observation::{ClusterObservation, ScanObservation};
use crate::perception_timing::PerceptionTiming;
use crate::result::{SituationResult, TruthAtScan};

/// A trained estimator under the method prefix it reports as (`SPGP`, `SPGP-HET`, `FULL-GP`).
#[derive(Debug, Clone, Copy)]
pub struct GpMethod<'a> {
    /// Method-name prefix; `-ALL` and `-BEST` are appended.
    pub prefix: &'a str,
    /// The trained estimator.
    pub estimator: &'a MotionEstimator,
}

/// The method-name prefix of an estimator's GP kind.
pub fn method_prefix(kind: GpKind) -> &'static str {
    match kind {
        GpKind::Spgp => "SPGP",
        GpKind::SpgpHet => "SPGP-HET",
        GpKind::Full => "FULL-GP",
    }
}

/// A situation's result plus how long the per-scan perception took.
#[derive(Debug, Clone)]
pub struct SituationRun {
    /// Truth and every method's estimates.
    pub result: SituationResult,
    /// Per-scan perception cost of every scan (maps and clusters; prediction per estimator).
    pub perception: Vec<PerceptionTiming>,
}

/// What one scan yields before the baselines run over the whole sequence.
struct ScanOutcome {
    observation: ScanObservation,
    truth: TruthAtScan,
    gp: Vec<ClusterEstimate>,
    perception: PerceptionTiming,
}

/// Evaluates every method on one situation sequence. Scan `k` of the result is sweep `k + 1`:
/// the first sweep has no predecessor, so no difference map and no estimate.
pub fn evaluate_situation(
    sequence: &SequenceReader,
    methods: &[GpMethod<'_>],
    baselines: &BaselineParams,
    on_scan: &(dyn Fn() + Sync),
) -> Result<SituationRun, EvalError> {
    let name = sequence.info().name.clone();
    let Some(first) = methods.first() else {
        return Err(EvalError::BadParameter {
            name: "methods",
            reason: "no trained estimator given".into(),
        });
    };
    let params = first.estimator.feature_params().clone();
    let outcomes: Vec<ScanOutcome> = (1..sequence.len())
        .into_par_iter()
        .map(|index| {
            let outcome = evaluate_scan(sequence, index, methods, &params);
            on_scan();
            outcome
        })
        .collect::<Result<_, _>>()?;

    let observations: Vec<ScanObservation> =
        outcomes.iter().map(|o| o.observation.clone()).collect();
    let mut estimates = run_all_baselines(&name, &observations, baselines)?;
    for (m, method) in methods.iter().enumerate() {
        let all = outcomes
            .iter()
            .map(|o| o.gp[m].all.map(to_estimate))
            .collect();
        let best = outcomes
            .iter()
            .map(|o| o.gp[m].best.map(to_estimate))
            .collect();
        let kind = method.estimator.gp_kind();
        estimates.insert(Method::gp(kind, GpReadout::Merged(MergeRule::All)), all);
        estimates.insert(Method::gp(kind, GpReadout::Merged(MergeRule::Best)), best);
    }
    let scans = outcomes.len();
    let perception = outcomes.iter().map(|o| o.perception).collect();
    let result = SituationResult {
        name,
        scans,
        truth: outcomes.iter().map(|o| o.truth).collect(),
        methods: estimates.into_iter().collect::<BTreeMap<_, _>>(),
    };
    result.validate()?;
    Ok(SituationRun { result, perception })
}

/// One scan: maps and clusters (thesis 2.1-2.2), the oracle target cluster, GP estimates for it.
fn evaluate_scan(
    sequence: &SequenceReader,
    index: usize,
    methods: &[GpMethod<'_>],
    params: &patchflow_learn::FeatureParams,
) -> Result<ScanOutcome, EvalError> {
    let previous = sequence.read_sweep(index - 1)?;
    let current = sequence.read_sweep(index)?;
    let target = current.target().ok_or_else(|| EvalError::BadResult {
        situation: sequence.info().name.clone(),
        reason: format!("sweep {index} has no object marked target"),
    })?;
    let start = std::time::Instant::now();
    let features = SweepFeatures::compute(&previous, &current, params)?;
    let maps_secs = start.elapsed().as_secs_f64();
    let [sx, sy] = features.sensor_xy();
    let truth = TruthAtScan {
        range_m: Some((target.centre_m[0] - sx).hypot(target.centre_m[1] - sy)),
        ..TruthAtScan::from_velocity(index, [target.velocity_mps[0], target.velocity_mps[1]])
    };
    let target_cluster = cluster_with_most_points_of(&features, &current, target.id);
    let target_points = target_cluster.map_or(0, |c| features.clusters().members(c).len());
    let truth = TruthAtScan {
        target_points: Some(target_points),
        ..truth
    };
    let start = std::time::Instant::now();
    let mut gp = Vec::with_capacity(methods.len());
    for method in methods {
        let estimate = match target_cluster {
            Some(c) if method.estimator.feature_params() == params => method
                .estimator
                .estimate_cluster(&features, features.clusters().members(c))?,
            Some(_) => {
                // A model trained with other map parameters sees its own maps.
                let own =
                    SweepFeatures::compute(&previous, &current, method.estimator.feature_params())?;
                match cluster_with_most_points_of(&own, &current, target.id) {
                    Some(c) => method
                        .estimator
                        .estimate_cluster(&own, own.clusters().members(c))?,
                    None => ClusterEstimate::default(),
                }
            }
            None => ClusterEstimate::default(),
        };
        gp.push(estimate);
    }
    let perception = PerceptionTiming {
        maps_secs,
        estimate_secs: start.elapsed().as_secs_f64() / methods.len().max(1) as f64,
        target_points: target_points as f64,
    };
    let mut actors = std::collections::BTreeMap::new();
    if let Some(c) = target_cluster {
        actors.insert(
            target.id,
            crate::observation::ActorCluster {
                cluster: c,
                points: target_points,
            },
        );
    }
    let observation = ScanObservation {
        scan: index,
        stamp_secs: current.stamp_secs,
        sensor_xy_world: features.sensor_xy(),
        clusters: cluster_observations(&features),
        actors,
        target_actor: Some(target.id),
    };
    Ok(ScanOutcome {
        observation,
        truth,
        gp,
        perception,
    })
}

/// The oracle association (thesis 4.4): the cluster holding most of the target's sliced points.
fn cluster_with_most_points_of(
    features: &SweepFeatures,
    sweep: &Sweep,
    actor: u16,
) -> Option<usize> {
    let mut counts: BTreeMap<usize, usize> = BTreeMap::new();
    for (i, p) in features.points().iter().enumerate() {
        if sweep.labels[p.index].instance() == actor {
            *counts.entry(features.cluster_of(i)).or_default() += 1;
        }
    }
    // Ties go to the lowest cluster id, so the choice is deterministic.
    counts
        .into_iter()
        .max_by(|a, b| a.1.cmp(&b.1).then(b.0.cmp(&a.0)))
        .map(|(c, _)| c)
}

fn cluster_observations(features: &SweepFeatures) -> Vec<ClusterObservation> {
    features
        .clusters()
        .iter()
        .enumerate()
        .map(|(id, members)| {
            let points = members
                .iter()
                .map(|&i| [features.points()[i].x_m, features.points()[i].y_m])
                .collect();
            ClusterObservation::from_points(id, points)
        })
        .collect()
}

fn to_estimate(motion: ClusterMotion) -> MotionEstimate {
    let (s, c) = motion.heading_rad.sin_cos();
    MotionEstimate {
        heading_rad: motion.heading_rad,
        speed_mps: motion.speed_mps,
        velocity_xy_mps: [motion.speed_mps * c, motion.speed_mps * s],
        heading_var: Some(motion.heading_var),
        speed_var: Some(motion.speed_var),
    }
}

/// Every sequence of a dataset whose sweeps mark a `target` actor: the situations to evaluate.
pub fn situation_names(dataset: &patchflow_dataset::Dataset) -> Result<Vec<String>, EvalError> {
    let mut names = Vec::new();
    for info in dataset.sequences() {
        let sequence = dataset.sequence(&info.name)?;
        if sequence.len() >= 2 && sequence.read_sweep(0)?.target().is_some() {
            names.push(info.name.clone());
        }
    }
    if names.is_empty() {
        return Err(EvalError::BadResult {
            situation: dataset.root().display().to_string(),
            reason: "no sequence has an actor marked `target` and at least two sweeps".into(),
        });
    }
    Ok(names)
}

/// Evaluates every situation of a dataset (see [`situation_names`]) with the given estimators and
/// the four baselines. `on_scan` is called once per scan evaluated; `total_scans` tells how many.
pub fn evaluate_dataset(
    dataset: &patchflow_dataset::Dataset,
    methods: &[GpMethod<'_>],
    baselines: &BaselineParams,
    on_scan: &(dyn Fn() + Sync),
) -> Result<(crate::BenchmarkReport, PerceptionTiming), EvalError> {
    let mut report = crate::BenchmarkReport::default();
    let mut perception = Vec::new();
    for name in situation_names(dataset)? {
        let run = evaluate_situation(&dataset.sequence(&name)?, methods, baselines, on_scan)?;
        perception.extend(run.perception);
        report.situations.push(run.result);
    }
    Ok((report, PerceptionTiming::mean(&perception)))
}

/// Number of scans [`evaluate_dataset`] will evaluate (every sweep but the first of each situation).
pub fn scans_to_evaluate(dataset: &patchflow_dataset::Dataset) -> Result<u64, EvalError> {
    let mut total = 0;
    for name in situation_names(dataset)? {
        total += dataset.sequence(&name)?.len().saturating_sub(1) as u64;
    }
    Ok(total)
}
