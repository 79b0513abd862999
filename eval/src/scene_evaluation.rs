//! Replays one sequence scan by scan, in order, as a car would run it: thesis Algorithm 3.1 on
//! every scan for every trained estimator, the baselines of thesis 3.2 on every cluster, and the
//! scores: per-target tables after thesis 4.4, scene flow and every actor for the whole scene.

use std::collections::BTreeMap;
use std::time::Instant;

use patchflow_dataset::SequenceReader;
use patchflow_learn::{
    ClusterEstimate, ClusterMotion, FeatureParams, MotionEstimator, Scan, ScanMotion, ScanStream,
    SweepFeatures,
};

use crate::baseline_params::BaselineParams;
use crate::baseline_step::{BaselineScan, BaselineTrackers, ClusterFlow};
use crate::baselines::BaselineMethod;
use crate::cpu_time::process_cpu_secs;
use crate::error::EvalError;
use crate::estimate::MotionEstimate;
use crate::method::{GpReadout, Method};
use crate::objects::ObjectScan;
use crate::oracle::{observe, target_at, target_cluster};
use crate::perception_timing::{ScanTiming, StepTiming};
use crate::result::{SceneResult, SituationResult};
use crate::scan_scoring::{MethodFlow, object_scans, score_points};
use crate::scene_flow::SceneFlowTally;
use crate::scene_point::ScenePoints;
use crate::truth_at_scan::TruthAtScan;

/// What one sequence yields.
#[derive(Debug, Clone)]
pub struct SequenceRun {
    /// The per-target tables' data, when the sequence marks a target.
    pub target: Option<SituationResult>,
    /// The whole scene.
    pub scene: SceneResult,
}

/// The running scores of a sequence.
struct Scores {
    tallies: BTreeMap<Method, SceneFlowTally>,
    objects: Vec<ObjectScan>,
    timing: Vec<ScanTiming>,
    target_truth: Vec<TruthAtScan>,
    target_estimates: BTreeMap<Method, Vec<Option<MotionEstimate>>>,
}

/// Evaluates every estimator and baseline on one sequence. Scan `k` of the result is sweep
/// `k + 1`: the first sweep has no predecessor, so no difference map and no estimate.
///
/// The whole-scene scores use the estimators trained with the first estimator's feature
/// parameters (they share its maps and clusters); an estimator trained with other parameters
/// computes its own maps and appears in the per-target tables only.
pub fn evaluate_sequence(
    sequence: &SequenceReader,
    estimators: &[MotionEstimator],
    baselines: &BaselineParams,
    on_scan: &(dyn Fn() + Sync),
) -> Result<SequenceRun, EvalError> {
    let name = sequence.info().name.clone();
    let Some(first) = estimators.first() else {
        return Err(EvalError::BadParameter {
            name: "estimators",
            reason: "no trained estimator given".into(),
        });
    };
    // Each distinct set of feature parameters gets its features once per scan.
    let mut params: Vec<FeatureParams> = vec![first.feature_params().clone()];
    let mut group_of = Vec::with_capacity(estimators.len());
    for e in estimators {
        let group = match params.iter().position(|p| p == e.feature_params()) {
            Some(g) => g,
            None => {
                params.push(e.feature_params().clone());
                params.len() - 1
            }
        };
        group_of.push(group);
    }
    let has_target = sequence.len() >= 2 && sequence.read_sweep(0)?.target().is_some();
    let mut trackers = BaselineTrackers::new(&name, baselines)?;
    let mut scores = Scores {
        tallies: BTreeMap::new(),
        objects: Vec::new(),
        timing: Vec::new(),
        target_truth: Vec::new(),
        target_estimates: BTreeMap::new(),
    };
    let mut stream = ScanStream::new(sequence, params)?;
    while let Some((index, sweep)) = stream.read_next()? {
        let cpu_start = process_cpu_secs();
        let features = stream.features_of(&sweep)?;
        let scan = Scan {
            index,
            sweep,
            features,
        };
        let dt = scan.sweep.stamp_secs - sequence.stamps_secs()[scan.index - 1];
        evaluate_scan(
            &scan,
            cpu_start,
            dt,
            (estimators, &group_of),
            has_target.then_some(&name),
            &mut trackers,
            &mut scores,
        )?;
        on_scan();
    }
    let scans = scores.timing.len();
    let target = has_target
        .then(|| SituationResult {
            name: name.clone(),
            scans,
            truth: scores.target_truth,
            methods: scores.target_estimates,
        })
        .map(|result| result.validate().map(|()| result))
        .transpose()?;
    Ok(SequenceRun {
        target,
        scene: SceneResult {
            name,
            scans,
            scene_flow: scores.tallies,
            objects: scores.objects,
            timing: scores.timing,
        },
    })
}

/// One scan: the estimators' whole-scan step, the target's estimate, the baselines, the scores.
fn evaluate_scan(
    scan: &Scan,
    cpu_start: Option<f64>,
    dt_secs: f64,
    (estimators, group_of): (&[MotionEstimator], &[usize]),
    situation: Option<&String>,
    trackers: &mut BaselineTrackers,
    scores: &mut Scores,
) -> Result<(), EvalError> {
    let features = &scan.features[0];
    let mut timing = ScanTiming::with_features(features.timing());
    // Thesis Algorithm 3.1, steps 3 and 4, on the whole scan, per estimator sharing these maps.
    let mut motions = Vec::new();
    for (estimator, _) in estimators.iter().zip(group_of).filter(|(_, g)| **g == 0) {
        let motion = estimator.estimate_features(features)?;
        timing.estimators.push(StepTiming::from(motion.timing));
        motions.push((estimator.gp_kind(), motion));
    }
    timing.whole_scan_cpu_secs = cpu_start
        .zip(process_cpu_secs())
        .map(|(start, end)| end - start);
    // The oracle association (thesis 4.4): every actor's cluster.
    let observation = observe(scan, features);
    let hypotheses = hypothesis_flags(features);
    // Thesis 4.4's protocol for the target: its cluster, predicted at every one of its points.
    let target = match situation {
        Some(situation) => Some(target_at(scan, features, situation)?),
        None => None,
    };
    let start = Instant::now();
    let mut target_gp = Vec::new();
    if target.is_some() {
        for (estimator, &group) in estimators.iter().zip(group_of) {
            let own = &scan.features[group];
            let estimate = match target_cluster(own, &scan.sweep) {
                Some(c) => estimator.estimate_cluster(own, own.clusters().members(c))?,
                None => ClusterEstimate::default(),
            };
            target_gp.push((estimator.gp_kind(), estimate));
        }
        timing.target_secs = start.elapsed().as_secs_f64() / estimators.len() as f64;
    }
    // Thesis 3.2: the baselines on every cluster (ICP-AUTO on the hypotheses and the target).
    let mut wanted = hypotheses.clone();
    if let Some(c) = observation.target_cluster() {
        wanted[c] = true;
    }
    let start = Instant::now();
    let baseline = trackers.step(observation.clone(), &wanted)?;
    timing.baselines_secs = start.elapsed().as_secs_f64();
    // Scene flow of every method on every scored point, and every actor.
    let flows = method_flows(&motions, &baseline, &hypotheses);
    let points = ScenePoints::new(features, &scan.sweep, dt_secs);
    let errors = score_points(
        &points,
        features.clusters().ids(),
        &flows,
        &mut scores.tallies,
    );
    scores.objects.extend(object_scans(
        &scan.sweep,
        &points,
        &observation,
        &flows,
        &baseline,
        &errors,
    ));
    // The per-target tables.
    if let Some(truth) = target {
        timing.target_points = truth.target_points.unwrap_or(0);
        scores.target_truth.push(truth);
        for (kind, estimate) in target_gp {
            for (rule, motion) in [
                (patchflow_learn::MergeRule::All, estimate.all),
                (patchflow_learn::MergeRule::Best, estimate.best),
            ] {
                let method = Method::gp(kind, GpReadout::Merged(rule));
                let column = scores.target_estimates.entry(method).or_default();
                column.push(motion.map(to_estimate));
            }
        }
        for baseline_method in BaselineMethod::ALL {
            let method = baseline_method.method();
            let estimate = observation
                .target_actor
                .and_then(|t| baseline.actor_estimate(method, t, &observation));
            scores
                .target_estimates
                .entry(method)
                .or_default()
                .push(estimate);
        }
    }
    scores.timing.push(timing);
    Ok(())
}

/// Which clusters of the scan are object hypotheses.
fn hypothesis_flags(features: &SweepFeatures) -> Vec<bool> {
    let mut flags = vec![false; features.clusters().len()];
    for c in features.object_hypotheses() {
        flags[c] = true;
    }
    flags
}

/// How each method moves the scan's points.
fn method_flows(
    motions: &[(patchflow_learn::GpKind, ScanMotion)],
    baseline: &BaselineScan,
    hypotheses: &[bool],
) -> BTreeMap<Method, MethodFlow> {
    let mut flows = BTreeMap::new();
    for (kind, motion) in motions {
        let [all, best, point] = Method::of_estimator(*kind);
        let merged = |pick: fn(&ClusterEstimate) -> Option<ClusterMotion>| {
            let clusters = motion.clusters.iter();
            let flows = clusters.map(|e| e.as_ref().and_then(pick));
            MethodFlow::Clusters(
                flows
                    .map(|m| m.map(|m| ClusterFlow::Uniform(to_estimate(m))))
                    .collect(),
            )
        };
        flows.insert(all, merged(|e| e.all));
        flows.insert(best, merged(|e| e.best));
        let velocities = motion.points.iter().map(|p| p.map(|p| p.velocity_xy_mps()));
        flows.insert(point, MethodFlow::Points(velocities.collect()));
    }
    for (&method, clusters) in &baseline.clusters {
        let kept = clusters
            .iter()
            .zip(hypotheses)
            .map(|(flow, &hypothesis)| flow.filter(|_| hypothesis))
            .collect();
        flows.insert(method, MethodFlow::Clusters(kept));
    }
    flows.insert(Method::ZeroFlow, MethodFlow::Zero);
    flows
}

/// A merged cluster motion as the estimate the tables score.
pub(crate) fn to_estimate(motion: ClusterMotion) -> MotionEstimate {
    let (s, c) = motion.heading_rad.sin_cos();
    MotionEstimate {
        heading_rad: motion.heading_rad,
        speed_mps: motion.speed_mps,
        velocity_xy_mps: [motion.speed_mps * c, motion.speed_mps * s],
        heading_var: Some(motion.heading_var),
        speed_var: Some(motion.speed_var),
    }
}
