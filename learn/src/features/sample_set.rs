//! Training samples (thesis 3.1.1-3.1.2): sliced points on moving actors with heading and speed
//! targets, importance sampled by the motion their heading patch shows.

use std::sync::atomic::{AtomicUsize, Ordering};

use patchflow_dataset::Dataset;
use rayon::prelude::*;

use crate::features::feature_kind::FeatureKind;
use crate::features::gabor::GaborBank;
use crate::features::run_sampler::{Rank, Run, RunSampler, merge};
use crate::features::top_n::TopN;
use crate::features::training_sample::TrainingSample;
use crate::{FeatureParams, LearnError, Result};

/// A set of importance-sampled training samples drawn from a whole dataset.
#[derive(Debug, Clone, PartialEq)]
pub struct SampleSet {
    /// Feature kind of both feature vectors.
    pub kind: FeatureKind,
    /// The feature parameters the samples were drawn with (their map prior included); a model
    /// trained on the set carries them and refuses features computed otherwise.
    pub features: FeatureParams,
    /// Number of candidate points the samples were drawn from.
    pub pool_size: usize,
    /// The samples, in dataset order (sequence name, sweep, point).
    pub samples: Vec<TrainingSample>,
}

/// Sweep pairs per task.
const RUN_LEN: usize = 6;

impl SampleSet {
    /// Draws `n` samples (thesis: 1,600) from every sliced point on a moving actor in every
    /// sweep pair of the dataset; see [`Self::collect_with_progress`].
    pub fn collect(
        dataset: &Dataset,
        params: &FeatureParams,
        kind: FeatureKind,
        n: usize,
        seed: u64,
    ) -> Result<Self> {
        Self::collect_with_progress(dataset, params, kind, n, seed, &|_, _| {})
    }

    /// Like [`Self::collect`], calling `progress(done, total)` as sweep pairs finish; the
    /// prior is `params.prior`. See [`Self::collect_priors`].
    pub fn collect_with_progress(
        dataset: &Dataset,
        params: &FeatureParams,
        kind: FeatureKind,
        n: usize,
        seed: u64,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Self> {
        let sets = Self::collect_priors(dataset, params, &[params.prior], kind, n, seed, progress)?;
        sets.into_iter().next().ok_or_else(|| {
            LearnError::degenerate_data(format!("{}: no sample set", dataset.root().display()))
        })
    }

    /// One sample set per map prior, set `i` drawn with `params` but prior `priors[i]` (the
    /// set's [`features`](Self::features) record which), each drawing `n` samples from
    /// the same candidates, in one pass over the dataset: every sweep is read and sliced once,
    /// every sweep pair's beams traced once for all priors (the prior only fills unobserved
    /// cells), and `progress(done, total)` is called as sweep pairs finish.
    ///
    /// Importance sampling without replacement (thesis 3.1.2) streams: a candidate's key is
    /// `ln(u) / w` (Efraimidis and Spirakis), `w` the mean absolute difference of its heading
    /// patch and `u` hashed from the seed, the sequence name, the sweep and the point; each task
    /// keeps the `n` largest keys with their features, and the tasks' lists are merged. The kept
    /// set is the `n` largest keys of the whole dataset, so the result depends only on the data,
    /// the parameters and the seed, not on the threads. The same `u` serves every prior.
    pub fn collect_priors(
        dataset: &Dataset,
        params: &FeatureParams,
        priors: &[f64],
        kind: FeatureKind,
        n: usize,
        seed: u64,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Vec<Self>> {
        let draws: Vec<(f64, u64)> = priors.iter().map(|&prior| (prior, seed)).collect();
        Self::collect_draws(dataset, params, &draws, kind, n, progress)
    }

    /// One sample set per `(prior, seed)` draw, all in one pass over the dataset as in
    /// [`SampleSet::collect_priors`]: the maps of each distinct prior are built once per sweep
    /// pair and serve every seed, so further seeds cost only their own draws. A draw's set
    /// equals the one `collect_priors` gives for that prior and seed alone.
    pub fn collect_draws(
        dataset: &Dataset,
        params: &FeatureParams,
        draws: &[(f64, u64)],
        kind: FeatureKind,
        n: usize,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Vec<Self>> {
        if draws.is_empty() {
            return Ok(Vec::new());
        }
        let mut priors: Vec<f64> = Vec::new();
        let mut draw_of: Vec<(usize, u64)> = Vec::with_capacity(draws.len());
        for &(prior, seed) in draws {
            // Each draw's parameters checked once, here.
            FeatureParams {
                prior,
                ..params.clone()
            }
            .check()?;
            let p = match priors.iter().position(|q| q.to_bits() == prior.to_bits()) {
                Some(p) => p,
                None => {
                    priors.push(prior);
                    priors.len() - 1
                }
            };
            draw_of.push((p, seed));
        }
        let readers = dataset
            .sequences()
            .iter()
            .map(|s| dataset.sequence(&s.name))
            .collect::<patchflow_dataset::Result<Vec<_>>>()?;
        let runs: Vec<Run> = readers
            .iter()
            .enumerate()
            .flat_map(|(s, r)| {
                (1..r.len())
                    .step_by(RUN_LEN)
                    .map(move |t| (s, t..(t + RUN_LEN).min(r.len())))
            })
            .collect();
        let total: usize = runs.iter().map(|r| r.1.len()).sum();
        let done = AtomicUsize::new(0);
        let tick = || progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
        // Training reads patches only: its maps are the patches' ones.
        let patch_params = params.patch_only();
        let sampler = RunSampler {
            readers: &readers,
            params: &patch_params,
            priors: &priors,
            draws: &draw_of,
            kind,
            gabor: GaborBank::new(&params.gabor, params.patch_cell_m),
        };
        let empty = || (0, draws.iter().map(|_| TopN::new(n)).collect::<Vec<_>>());
        let (pool_size, kept_draws) = runs
            .par_iter()
            .try_fold(empty, |draws, run| sampler.run(run, draws, &tick))
            .try_reduce(empty, |a, b| Ok(merge(a, b)))?;
        if pool_size == 0 {
            return Err(LearnError::degenerate_data(format!(
                "{}: no sliced point on a moving actor",
                dataset.root().display()
            )));
        }
        Ok(kept_draws
            .into_iter()
            .zip(draws)
            .map(|(draw, &(prior, _))| {
                let mut kept: Vec<(Rank, TrainingSample)> = draw.into_items().collect();
                // Dataset order (sequence, sweep, point).
                kept.sort_unstable_by_key(|(rank, _)| (rank.1).0);
                Self {
                    kind,
                    features: FeatureParams {
                        prior,
                        ..params.clone()
                    },
                    pool_size,
                    samples: kept.into_iter().map(|(_, s)| s).collect(),
                }
            })
            .collect())
    }

    /// The map prior the features were computed with.
    pub fn prior(&self) -> f64 {
        self.features.prior
    }

    /// Names of the feature columns.
    pub fn feature_names(&self) -> Vec<String> {
        self.kind.names()
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::features::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
    use patchflow_dataset::{Pose, SequenceWriter};
    use std::path::Path;

    /// Writes a small dataset: one sequence of `sweeps` sweeps, a car crossing and one
    /// approaching, a wall, the ego driving along +x at 3 m/s.
    pub(crate) fn write_dataset(root: &Path, sweeps: u32) {
        let mut scene = SyntheticScene {
            boxes: vec![
                SceneBox::car(1, [6.0, 9.0], 0.0, 6.0),
                SceneBox::car(2, [22.0, -2.0], 3.0, 4.0),
                SceneBox::wall([5.0, -9.0], 0.0, [20.0, 0.5, 2.5]),
            ],
        };
        let lidar = SyntheticLidar::with_resolution(32, 900);
        let writer = SequenceWriter::open(root, "synthetic").unwrap();
        let mut poses: Vec<Pose> = Vec::new();
        for t in 0..sweeps {
            let sweep = scene.scan(&lidar, [0.3 * f64::from(t), 0.0], 0.0, t);
            writer.write_sweep(&sweep).unwrap();
            poses.push(sweep.world_from_sensor);
            scene = scene.advanced(0.1);
        }
        let stamps: Vec<f64> = (0..sweeps).map(|t| f64::from(t) * 0.1).collect();
        writer
            .finish("synthetic", 0, 10.0, &poses, &stamps, "test")
            .unwrap();
    }

    #[test]
    fn samples_carry_consistent_targets_and_both_feature_vectors() {
        let dir = tempfile::tempdir().unwrap();
        write_dataset(dir.path(), 3);
        let dataset = Dataset::open(dir.path()).unwrap();
        let params = FeatureParams::default();
        let set = SampleSet::collect(&dataset, &params, FeatureKind::Gabor, 60, 3).unwrap();
        assert_eq!(set.samples.len(), 60.min(set.pool_size));
        assert!(set.pool_size > 60, "pool {}", set.pool_size);
        for s in &set.samples {
            assert!(s.scan >= 1 && (s.actor == 1 || s.actor == 2));
            assert!((s.sin_rel.hypot(s.cos_rel) - 1.0).abs() < 1e-12);
            let expected = if s.actor == 1 { (0.0, 6.0) } else { (3.0, 4.0) };
            assert!(
                (s.heading_rad - expected.0).abs() < 1e-9
                    && (s.speed_mps - expected.1).abs() < 1e-9
            );
            assert_eq!((s.heading_features.len(), s.speed_features.len()), (16, 16));
            assert!(s.weight >= 0.0);
        }
        let again = SampleSet::collect(&dataset, &params, FeatureKind::Gabor, 60, 3).unwrap();
        assert_eq!(set, again, "the same seed gives the same samples");
    }

    #[test]
    fn sets_for_several_priors_equal_sets_collected_one_prior_at_a_time() {
        let dir = tempfile::tempdir().unwrap();
        write_dataset(dir.path(), 4);
        let dataset = Dataset::open(dir.path()).unwrap();
        let params = FeatureParams::default();
        let kind = FeatureKind::Gabor;
        let both =
            SampleSet::collect_priors(&dataset, &params, &[0.01, 0.5], kind, 50, 5, &|_, _| {})
                .unwrap();
        assert_eq!(both.len(), 2);
        for (set, prior) in both.iter().zip([0.01, 0.5]) {
            let one_params = FeatureParams::with_prior(prior);
            let one = SampleSet::collect(&dataset, &one_params, kind, 50, 5).unwrap();
            assert_eq!(set, &one, "prior {prior}");
        }
        assert_ne!(
            both[0].samples, both[1].samples,
            "the priors change the features"
        );
    }

    #[test]
    fn draws_of_several_seeds_equal_draws_collected_one_seed_at_a_time() {
        let dir = tempfile::tempdir().unwrap();
        write_dataset(dir.path(), 4);
        let dataset = Dataset::open(dir.path()).unwrap();
        let params = FeatureParams::default();
        let kind = FeatureKind::Gabor;
        let draws = [(0.5, 3), (0.01, 3), (0.5, 4)];
        let sets =
            SampleSet::collect_draws(&dataset, &params, &draws, kind, 40, &|_, _| {}).unwrap();
        assert_eq!(sets.len(), 3);
        for (set, &(prior, seed)) in sets.iter().zip(&draws) {
            let one =
                SampleSet::collect(&dataset, &FeatureParams::with_prior(prior), kind, 40, seed)
                    .unwrap();
            assert_eq!(set, &one, "prior {prior}, seed {seed}");
        }
        assert_ne!(
            sets[0].samples, sets[2].samples,
            "the seeds draw differently"
        );
    }

    #[test]
    fn the_draw_does_not_depend_on_the_number_of_threads() {
        let dir = tempfile::tempdir().unwrap();
        write_dataset(dir.path(), 8);
        let dataset = Dataset::open(dir.path()).unwrap();
        let params = FeatureParams::default();
        let on = |threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| SampleSet::collect(&dataset, &params, FeatureKind::Gabor, 30, 9))
                .unwrap()
        };
        assert_eq!(on(1), on(3));
    }

    #[test]
    fn selected_samples_have_higher_weights_than_the_pool_on_average() {
        let dir = tempfile::tempdir().unwrap();
        write_dataset(dir.path(), 3);
        let dataset = Dataset::open(dir.path()).unwrap();
        let params = FeatureParams::default();
        let all = SampleSet::collect(&dataset, &params, FeatureKind::Gabor, usize::MAX, 0).unwrap();
        let some = SampleSet::collect(&dataset, &params, FeatureKind::Patch, 40, 0).unwrap();
        let mean = |s: &SampleSet| {
            s.samples.iter().map(|x| x.weight).sum::<f64>() / s.samples.len() as f64
        };
        assert_eq!(all.samples.len(), all.pool_size);
        assert!(
            mean(&some) > 1.2 * mean(&all),
            "{} vs {}",
            mean(&some),
            mean(&all)
        );
        assert_eq!(some.samples[0].heading_features.len(), 242);
    }
}
