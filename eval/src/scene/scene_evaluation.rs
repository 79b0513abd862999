//! Replays one sequence scan by scan, in order, as a car would run it: thesis Algorithm 3.1 on
//! every scan for every trained estimator, the baselines of thesis 3.2 on every cluster, and the
//! scores: per-target tables after thesis 4.4, scene flow and every actor for the whole scene.

use std::collections::BTreeMap;
use std::time::Instant;

use patchflow_dataset::SequenceReader;
use patchflow_learn::{
    ChangeEvidence, ClusterEstimate, FeatureParams, FeaturedSweep, MotionEstimator, MovingBelief,
    MovingClassifier, RangeProfile, ScanStream,
};

use crate::error::EvalError;
use crate::methods::baselines::baseline_params::BaselineParams;
use crate::methods::baselines::baseline_step::BaselineTrackers;
use crate::methods::baselines::velocity_measurement::GpVelocityNoise;
use crate::methods::estimate::to_estimate;
use crate::methods::learned::learned_step::{LearnedCluster, LearnedTrackers};
use crate::methods::learned::learned_target::{LearnedTargetTrackers, tracked_estimator};
use crate::methods::learned::plausible_motion::{implausible_estimate, implausible_motion};
use crate::methods::method::Method;
use crate::scene::cpu_time::process_cpu_secs;
use crate::scene::method_flows::{hypothesis_flags, method_flows};
use crate::scene::objects::ObjectScan;
use crate::scene::oracle::{observe, target_at, target_cluster};
use crate::scene::perception_timing::{ScanTiming, StepTiming};
use crate::scene::result::{SceneResult, SituationResult};
use crate::scene::scan_scoring::{object_scans, score_points};
use crate::scene::scene_flow::SceneFlowTally;
use crate::scene::scene_point::ScenePoints;
use crate::scene::target_columns::{TargetColumns, push_target_estimates};
use crate::scene::truth_at_scan::TruthAtScan;

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
    target_estimates: TargetColumns,
}

/// The trackers of a sequence: the baselines and the GP-informed ones.
struct Trackers {
    baselines: BaselineTrackers,
    learned: LearnedTrackers,
    /// GP-KF and GP-ICP on the target under the per-target protocol (no moving decision).
    target: LearnedTargetTrackers,
    /// The moving classifier's probabilities smoothed along the clusters' own tracks.
    belief: MovingBelief,
}

/// Evaluates every estimator and baseline on one sequence. Scan `k` of the result is sweep
/// `k + 1`: the first sweep has no predecessor, so no difference map and no estimate. With a
/// moving classifier, the `+MOS` readouts, GP-KF and GP-ICP take its moving/static decision.
/// GP-KF and GP-ICP read the merged (ALL) estimates of the SPGP-HET estimator among those sharing
/// the first one's maps, else of the first ([`tracked_estimator`]).
///
/// The whole-scene scores use the estimators trained with the first estimator's feature
/// parameters (they share its maps and clusters); an estimator trained with other parameters
/// computes its own maps and appears in the per-target tables only.
pub fn evaluate_sequence(
    sequence: &SequenceReader,
    estimators: &[MotionEstimator],
    baselines: &BaselineParams,
    moving: Option<&MovingClassifier>,
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
    // GP-KF's and GP-ICP's estimator, among those sharing the first one's maps.
    let shared: Vec<usize> = (0..estimators.len())
        .filter(|&k| group_of[k] == 0)
        .collect();
    let tracked = shared
        .get(tracked_estimator(
            shared.iter().map(|&k| estimators[k].gp_kind()),
        ))
        .copied()
        .unwrap_or(0);
    let has_target = sequence.len() >= 2 && sequence.read_sweep(0)?.target().is_some();
    let mut trackers = Trackers {
        baselines: BaselineTrackers::new(&name, baselines)?,
        learned: LearnedTrackers::new(baselines, GpVelocityNoise::default())?,
        target: LearnedTargetTrackers::new(baselines)?,
        belief: MovingBelief::default(),
    };
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
        let scan = FeaturedSweep {
            index,
            sweep,
            features,
        };
        let dt = scan.sweep.stamp_secs - sequence.stamps_secs()[scan.index - 1];
        // The moving classifier reads the change observed over the last half second as well
        // (timed as part of the segmentation).
        let change_start = Instant::now();
        let change = moving.and_then(|_| ChangeEvidence::of_stream(&stream));
        let change_secs = change_start.elapsed().as_secs_f64();
        let moving_now = moving.zip(change.as_ref());
        evaluate_scan(
            &scan,
            (cpu_start, change_secs),
            dt,
            &ScanModels {
                estimators,
                group_of: &group_of,
                tracked,
                moving: moving_now,
            },
            has_target.then_some(&name),
            &mut trackers,
            &mut scores,
        )
        .map_err(|err| match err {
            // A scan without a situation is named by its sequence.
            EvalError::BadObservation {
                situation,
                scan,
                reason,
            } if situation == "-" => EvalError::BadObservation {
                situation: name.clone(),
                scan,
                reason,
            },
            other => other,
        })?;
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

/// What evaluates a scan: the estimators, each one's feature group (0: the first estimator's
/// maps, which the whole scene uses), the one GP-KF and GP-ICP read, and the moving classifier
/// with the change it reads.
#[derive(Clone, Copy)]
struct ScanModels<'a> {
    estimators: &'a [MotionEstimator],
    group_of: &'a [usize],
    tracked: usize,
    moving: Option<(&'a MovingClassifier, &'a ChangeEvidence)>,
}

/// One scan: the estimators' whole-scan step, the target's estimate, the baselines, the scores.
fn evaluate_scan(
    scan: &FeaturedSweep,
    (cpu_start, change_secs): (Option<f64>, f64),
    dt_secs: f64,
    models: &ScanModels,
    situation: Option<&String>,
    trackers: &mut Trackers,
    scores: &mut Scores,
) -> Result<(), EvalError> {
    let ScanModels {
        estimators,
        group_of,
        tracked,
        moving,
    } = *models;
    let features = &scan.features[0];
    let mut timing = ScanTiming::with_features(features.timing());
    // Thesis Algorithm 3.1, steps 3 and 4, on the whole scan, per estimator sharing these maps.
    let mut motions = Vec::new();
    let mut learned_cpu = None; // features and the first estimator's step, then issue 27's stages
    // GP-KF's and GP-ICP's estimator among these: those before it in the list share its maps.
    let tracked_motion = group_of[..tracked].iter().filter(|g| **g == 0).count();
    for (estimator, _) in estimators.iter().zip(group_of).filter(|(_, g)| **g == 0) {
        let motion = estimator.estimate_features(features)?;
        learned_cpu = learned_cpu.or(cpu_start.zip(process_cpu_secs()).map(|(a, b)| b - a));
        if let Some(reason) = implausible_motion(&motion) {
            return Err(EvalError::BadObservation {
                situation: situation.map_or_else(|| "-".to_owned(), String::clone),
                scan: scan.index,
                reason,
            });
        }
        timing.estimators.push(StepTiming::from(motion.timing));
        motions.push((estimator.gp_kind(), motion));
    }
    timing.whole_scan_cpu_secs = cpu_start
        .zip(process_cpu_secs())
        .map(|(start, end)| end - start);
    // Moving or static, per object hypothesis (issue 27).
    let (start, cpu) = (Instant::now(), process_cpu_secs());
    let decisions: Vec<Option<bool>> = match moving {
        Some((classifier, change)) => classifier.tracked_decisions(
            &mut trackers.belief,
            features,
            change,
            scan.sweep.stamp_secs,
        )?,
        None => vec![None; features.clusters().len()],
    };
    timing.segmentation_secs = start.elapsed().as_secs_f64() + change_secs;
    let mut learned_cpu = learned_cpu
        .zip(cpu.zip(process_cpu_secs()))
        .map(|(l, (a, b))| l + b - a);
    // The oracle association (thesis 4.4): every actor's cluster.
    // One range profile per scan serves the oracle's clusters and the target's truth.
    let profile = RangeProfile::of(features);
    let observation = observe(scan, features, &profile);
    let hypotheses = hypothesis_flags(features);
    // Thesis 4.4's protocol for the target: its cluster, predicted at every one of its points.
    let target = match situation {
        Some(situation) => Some(target_at(scan, features, &profile, situation)?),
        None => None,
    };
    let start = Instant::now();
    let mut target_gp = Vec::new();
    if target.is_some() {
        for (k, (estimator, &group)) in estimators.iter().zip(group_of).enumerate() {
            let own = &scan.features[group];
            let estimate = match target_cluster(own, &scan.sweep) {
                Some(c) => estimator.estimate_cluster(own, own.clusters().members(c))?,
                None => ClusterEstimate::default(),
            };
            // Estimators of other feature parameters predict only here: checked here too.
            let what = format!("the target (model {} of {})", k + 1, estimators.len());
            if let Some(reason) = implausible_estimate(&estimate, &what) {
                return Err(EvalError::BadObservation {
                    situation: situation.map_or_else(|| "-".to_owned(), String::clone),
                    scan: scan.index,
                    reason,
                });
            }
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
    let baseline = trackers.baselines.step(observation.clone(), &wanted)?;
    timing.baselines_secs = start.elapsed().as_secs_f64();
    // GP-KF on every cluster, GP-ICP where ICP-AUTO runs, from the tracked estimator's ALL.
    let learned: Vec<LearnedCluster> = (0..features.clusters().len())
        .map(|c| LearnedCluster {
            gp: motions
                .get(tracked_motion)
                .and_then(|(_, m)| m.clusters[c].and_then(|e| e.all))
                .map(to_estimate),
            moving: decisions[c],
        })
        .collect();
    let (start, cpu) = (Instant::now(), process_cpu_secs());
    let gp_kf = trackers.learned.step_kf(&observation, &learned)?;
    timing.gp_kf_secs = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let gp_icp = trackers.learned.step_icp(&observation, &learned, &wanted)?;
    timing.gp_icp_secs = start.elapsed().as_secs_f64();
    learned_cpu = learned_cpu
        .zip(cpu.zip(process_cpu_secs()))
        .map(|(l, (a, b))| l + b - a);
    timing.learned_scan_cpu_secs = learned_cpu;
    let learned_flows = BTreeMap::from([(Method::GpKf, gp_kf), (Method::GpIcp, gp_icp)]);
    // Scene flow of every method on every scored point, and every actor.
    let flows = method_flows(
        &motions,
        &baseline,
        &learned_flows,
        &hypotheses,
        moving.map(|_| &decisions[..]),
    );
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
        let target_moving = observation
            .target_cluster()
            .and_then(|c| decisions.get(c).copied().flatten());
        push_target_estimates(
            &mut scores.target_estimates,
            (target_gp, tracked),
            (moving.is_some(), target_moving),
            &mut trackers.target,
            &observation,
            &baseline,
        )?;
    }
    scores.timing.push(timing);
    Ok(())
}
