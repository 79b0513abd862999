//! The per-target tables alone (thesis 4.4's protocol: the target's cluster, predicted at every
//! one of its points, merged ALL and BEST) for the further training seeds of a benchmark: only
//! the GP methods depend on training, so a seed needs neither the baselines nor the whole scene.
//! With the baselines, the same serves the realism study, which scores the target only: no GP
//! runs on the rest of the scene and ICP-AUTO aligns the target's cluster alone. GP-KF and
//! GP-ICP then run too, with the GP's estimate of the target's cluster and no moving decision on
//! it (`LearnedTargetTrackers`, as in the whole evaluation's per-target tables); the moving
//! decision gives the `+MOS` read-outs.

use std::collections::BTreeMap;

use patchflow_dataset::{Dataset, SequenceReader};
use patchflow_learn::{
    ChangeEvidence, ClusterEstimate, FeatureParams, FeaturedSweep, MergeRule, MotionEstimator,
    MovingBelief, MovingClassifier, RangeProfile, ScanStream,
};
use rayon::prelude::*;

use crate::error::EvalError;
use crate::methods::baselines::baseline_method::run_all_baselines;
use crate::methods::baselines::baseline_params::BaselineParams;
use crate::methods::estimate::MotionEstimate;
use crate::methods::estimate::to_estimate;
use crate::methods::learned::learned_target::{LearnedTargetTrackers, tracked_estimator};
use crate::methods::method::Method;
use crate::methods::observation::ScanObservation;
use crate::pipeline::dataset_evaluation::sequences_to_evaluate;
use crate::report::benchmark_report::BenchmarkReport;
use crate::scene::oracle::{observe, target_at, target_cluster};
use crate::scene::result::SituationResult;

/// Every GP read-out's estimate of the target at every scan of every situation (sequences with a
/// target) of `dataset`, in dataset order, for each of several trained runs (`runs[k]` holds one
/// run's estimators, one per GP kind); the runs share each scan's maps. The estimates equal
/// those of the whole evaluation ([`crate::evaluate_dataset`]) for the same estimators.
pub fn evaluate_targets(
    dataset: &Dataset,
    runs: &[Vec<MotionEstimator>],
) -> Result<Vec<Vec<SituationResult>>, EvalError> {
    targets_of_runs(dataset, runs, None, None)
}

/// Every method's estimate of the target at every scan of every situation of `dataset` (the GP
/// read-outs of `estimators` and the four baselines with `baselines`), the situations in
/// parallel: the per-target tables of [`crate::evaluate_dataset`], equal to its, without the
/// whole scene (whose scores and timings are not wanted here).
pub fn evaluate_targets_with_baselines(
    dataset: &Dataset,
    estimators: &[MotionEstimator],
    baselines: &BaselineParams,
    moving: Option<&MovingClassifier>,
) -> Result<BenchmarkReport, EvalError> {
    let runs = [estimators.to_vec()];
    let situations = targets_of_runs(dataset, &runs, Some(baselines), moving)?
        .into_iter()
        .next()
        .unwrap_or_default();
    Ok(BenchmarkReport {
        situations,
        ..BenchmarkReport::default()
    })
}

/// [`evaluate_targets_with_baselines`] for several trained runs at once (`runs[k]` one run's
/// estimators, one per GP kind): the runs share each scan's maps and the baselines run once;
/// `result[k]` is what run `k` alone would give (its GP-KF and GP-ICP read its own estimator).
pub fn evaluate_runs_with_baselines(
    dataset: &Dataset,
    runs: &[Vec<MotionEstimator>],
    baselines: &BaselineParams,
) -> Result<Vec<Vec<SituationResult>>, EvalError> {
    targets_of_runs(dataset, runs, Some(baselines), None)
}

/// The targets of `dataset` for each run, with the baselines' estimates in every run if asked.
fn targets_of_runs(
    dataset: &Dataset,
    runs: &[Vec<MotionEstimator>],
    baselines: Option<&BaselineParams>,
    moving: Option<&MovingClassifier>,
) -> Result<Vec<Vec<SituationResult>>, EvalError> {
    let names = sequences_to_evaluate(dataset)?;
    let sequences = names
        .par_iter()
        .map(|name| evaluate_target(&dataset.sequence(name)?, runs, baselines, moving))
        .collect::<Result<Vec<_>, EvalError>>()?;
    let mut per_run = vec![Vec::new(); runs.len()];
    for results in sequences.into_iter().flatten() {
        for (run, result) in per_run.iter_mut().zip(results) {
            run.push(result);
        }
    }
    Ok(per_run)
}

/// One sequence's target for every run, or `None` when the sequence marks no target.
fn evaluate_target(
    sequence: &SequenceReader,
    runs: &[Vec<MotionEstimator>],
    baselines: Option<&BaselineParams>,
    moving: Option<&MovingClassifier>,
) -> Result<Option<Vec<SituationResult>>, EvalError> {
    let name = sequence.info().name.clone();
    if sequence.len() < 2 || sequence.read_sweep(0)?.target().is_none() {
        return Ok(None);
    }
    // Each distinct set of feature parameters gets its maps once per scan.
    let mut params: Vec<FeatureParams> = Vec::new();
    let mut group_of: Vec<Vec<usize>> = Vec::with_capacity(runs.len());
    for run in runs {
        let mut groups = Vec::with_capacity(run.len());
        for e in run {
            // The training-only speed jitter does not change the run-time maps.
            let own = FeatureParams {
                speed_jitter_deg: 0.0,
                ..e.feature_params().clone()
            };
            match params.iter().position(|p| *p == own) {
                Some(g) => groups.push(g),
                None => {
                    params.push(own);
                    groups.push(params.len() - 1);
                }
            }
        }
        group_of.push(groups);
    }
    let mut truth = Vec::new();
    let mut methods: Vec<BTreeMap<Method, Vec<Option<MotionEstimate>>>> =
        vec![BTreeMap::new(); runs.len()];
    let mut observations: Vec<ScanObservation> = Vec::new();
    // Per scan: the target's moving decision; per run and scan: its tracked GP's ALL estimate.
    let mut target_moving: Vec<Option<bool>> = Vec::new();
    let mut target_all: Vec<Vec<Option<MotionEstimate>>> = vec![Vec::new(); runs.len()];
    let mut belief = MovingBelief::default();
    let mut stream = ScanStream::new(sequence, params)?;
    while let Some((index, sweep)) = stream.read_next()? {
        let features = stream.features_of(&sweep)?;
        let scan = FeaturedSweep {
            index,
            sweep,
            features,
        };
        // One range profile per scan serves the target's truth and the baselines' clusters.
        let profile = RangeProfile::of(&scan.features[0]);
        truth.push(target_at(&scan, &scan.features[0], &profile, &name)?);
        if baselines.is_some() {
            // What the baselines see (the first estimator's clusters, as the whole evaluation);
            // the oracle association kept for the target alone, which only its estimates read.
            let mut observation = observe(&scan, &scan.features[0], &profile);
            let target = observation.target_actor;
            observation.actors.retain(|&actor, _| Some(actor) == target);
            let change = moving.and_then(|_| ChangeEvidence::of_stream(&stream));
            // Every cluster's decision, so that the belief follows every track.
            let decisions = match (moving, change) {
                (Some(classifier), Some(change)) => classifier.tracked_decisions(
                    &mut belief,
                    &scan.features[0],
                    &change,
                    scan.sweep.stamp_secs,
                )?,
                _ => Vec::new(),
            };
            let decision = observation
                .target_cluster()
                .and_then(|c| decisions.get(c).copied().flatten());
            target_moving.push(decision);
            observations.push(observation);
        }
        let runs_and_columns = runs.iter().zip(&group_of).zip(&mut methods);
        for (((run, groups), columns), tracked_all) in runs_and_columns.zip(&mut target_all) {
            // GP-KF and GP-ICP read the estimator the whole evaluation gives them.
            let tracked = tracked_estimator(run.iter().map(MotionEstimator::gp_kind));
            for (i, (estimator, &group)) in run.iter().zip(groups).enumerate() {
                let own = &scan.features[group];
                let estimate = match target_cluster(own, &scan.sweep) {
                    Some(c) => estimator.estimate_cluster(own, own.clusters().members(c))?,
                    None => ClusterEstimate::default(),
                };
                if i == tracked {
                    tracked_all.push(estimate.all.map(to_estimate));
                }
                for (rule, motion) in [
                    (MergeRule::All, estimate.all),
                    (MergeRule::Best, estimate.best),
                ] {
                    let Some(method) = Method::of_target_readout(estimator, rule) else {
                        continue;
                    };
                    let column = columns.entry(method).or_default();
                    column.push(motion.map(to_estimate));
                }
                if baselines.is_some() && moving.is_some() {
                    let all = estimate.all.map(to_estimate);
                    let decided = match target_moving.last().copied().flatten() {
                        Some(false) => {
                            Some(MotionEstimate::at_rest(all.map_or(0.0, |e| e.heading_rad)))
                        }
                        _ => all,
                    };
                    let column = columns.entry(Method::gp_decided(estimator.gp_kind()));
                    column.or_default().push(decided);
                }
            }
        }
    }
    // Thesis 3.2: the baselines, run once; they do not learn, so every run gets the same.
    if let Some(params) = baselines {
        let estimates = run_all_baselines(&name, &observations, params)?;
        for (columns, tracked_all) in methods.iter_mut().zip(&target_all) {
            columns.extend(estimates.clone());
            columns.extend(learned_targets(&observations, tracked_all, params)?);
        }
    }
    let results = methods
        .into_iter()
        .map(|methods| {
            let result = SituationResult {
                name: name.clone(),
                scans: truth.len(),
                truth: truth.clone(),
                methods,
            };
            result.validate().map(|()| result)
        })
        .collect::<Result<Vec<_>, EvalError>>()?;
    Ok(Some(results))
}

/// GP-KF's and GP-ICP's estimates of the target at every scan under the per-target protocol
/// (no moving decision on the target, as the baselines have none), given the GP's estimate of
/// the target's cluster at every scan.
fn learned_targets(
    observations: &[ScanObservation],
    target_all: &[Option<MotionEstimate>],
    params: &BaselineParams,
) -> Result<BTreeMap<Method, Vec<Option<MotionEstimate>>>, EvalError> {
    let mut trackers = LearnedTargetTrackers::new(params)?;
    let mut out: BTreeMap<Method, Vec<Option<MotionEstimate>>> = BTreeMap::new();
    for (k, observation) in observations.iter().enumerate() {
        let target_gp = target_all.get(k).copied().flatten();
        for (method, estimate) in trackers.step(observation, target_gp)? {
            out.entry(method).or_default().push(estimate);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use patchflow_learn::{EstimatorParams, GpKind};
    use patchflow_sim::{GenerateOptions, ScenarioSource, Shard, generate_dataset};

    use crate::methods::baselines::baseline_params::BaselineParams;
    use crate::pipeline::dataset_evaluation::evaluate_dataset;

    /// `scenarios/tiny.toml` with `sweeps` sweeps, generated (seed 5) under `dir`.
    fn tiny_dataset(dir: &std::path::Path, sweeps: u32) -> Dataset {
        let text = include_str!("../../../scenarios/tiny.toml")
            .replace("sweeps = 3", &format!("sweeps = {sweeps}"));
        let scenario = dir.join("tiny.toml");
        std::fs::write(&scenario, text).unwrap();
        let options = GenerateOptions {
            out: dir.join("data"),
            seed: 5,
            shard: Shard::ALL,
            overwrite: false,
            realism: None,
        };
        generate_dataset(&[ScenarioSource::File(scenario)], &options, &|_| {}).unwrap();
        Dataset::open(&dir.join("data")).unwrap()
    }

    /// A GP of kind `gp` trained at the smallest sizes on `dataset`.
    fn tiny_estimator(dataset: &Dataset, gp: GpKind) -> MotionEstimator {
        let params = EstimatorParams {
            gp,
            samples: 40,
            pseudo_inputs: 5,
            max_iters: 10,
            ..EstimatorParams::default()
        };
        MotionEstimator::train(dataset, &params).unwrap()
    }

    #[test]
    fn the_target_alone_gets_the_same_gp_estimates_as_the_whole_evaluation() {
        let dir = tempfile::tempdir().unwrap();
        let dataset = tiny_dataset(dir.path(), 3);
        let estimators = [tiny_estimator(&dataset, GpKind::Spgp)];
        let whole = evaluate_dataset(
            &dataset,
            &estimators,
            &BaselineParams::default(),
            None,
            &|| {},
        )
        .unwrap();
        let runs = [estimators.to_vec(), estimators.to_vec()];
        let targets = evaluate_targets(&dataset, &runs).unwrap();
        assert_eq!(targets.len(), 2, "one result per run");
        assert_eq!(targets[0], targets[1], "the same estimators twice");
        assert_eq!(targets[0].len(), 1);
        let (alone, full) = (&targets[0][0], &whole.situations[0]);
        assert_eq!((&alone.name, alone.scans), (&full.name, full.scans));
        assert_eq!(alone.truth, full.truth);
        assert_eq!(alone.methods.len(), 2, "SPGP-ALL and SPGP-BEST");
        for (method, estimates) in &alone.methods {
            assert_eq!(Some(estimates), full.methods.get(method), "{method}");
        }
        assert!(alone.methods[&Method::SpgpAll].iter().any(Option::is_some));
        // With the baselines: every method of the whole evaluation's per-target table, equal,
        // GP-KF and GP-ICP included (both run the per-target protocol's trackers).
        let with = evaluate_targets_with_baselines(
            &dataset,
            &estimators,
            &BaselineParams::default(),
            None,
        )
        .unwrap();
        assert_eq!(with.situations, whole.situations);
        // Two scored scans are too few for a track to report: GP-KF, like KF-AUTO, ran on
        // each scan and stays silent.
        assert_eq!(with.situations[0].methods[&Method::GpKf].len(), full.scans);
        assert!(
            with.situations[0].methods[&Method::IcpAuto]
                .iter()
                .any(Option::is_some)
        );
    }

    #[test]
    fn gp_kf_and_gp_icp_read_the_spgp_het_estimator_when_spgp_is_listed_first() {
        let dir = tempfile::tempdir().unwrap();
        // The tiny scene for a second: long enough for GP-KF's track to report.
        let dataset = tiny_dataset(dir.path(), 10);
        let (spgp, het) = (
            tiny_estimator(&dataset, GpKind::Spgp),
            tiny_estimator(&dataset, GpKind::SpgpHet),
        );
        let trackers = |estimators: &[MotionEstimator]| {
            let whole = evaluate_dataset(
                &dataset,
                estimators,
                &BaselineParams::default(),
                None,
                &|| {},
            )
            .unwrap();
            let alone = evaluate_targets_with_baselines(
                &dataset,
                estimators,
                &BaselineParams::default(),
                None,
            )
            .unwrap();
            assert_eq!(alone.situations, whole.situations);
            let column = |m: Method| whole.situations[0].methods[&m].clone();
            (column(Method::GpKf), column(Method::GpIcp))
        };
        let both = trackers(&[spgp.clone(), het.clone()]);
        assert!(both.0.iter().any(Option::is_some), "GP-KF reports");
        assert_eq!(both, trackers(&[het]));
        assert_ne!(both, trackers(&[spgp]), "the two GPs read the target alike");
    }
}
