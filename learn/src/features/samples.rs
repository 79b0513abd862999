//! Training samples (thesis 3.1.1-3.1.2): sliced points on moving actors with heading and speed
//! targets, importance sampled by the motion their heading patch shows.

use std::sync::atomic::{AtomicUsize, Ordering};

use patchflow_dataset::{Dataset, SequenceReader, Sweep};
use rayon::prelude::*;

use crate::features::sampling::importance_sample;
use crate::features::sweep_features::{FeatureKind, SweepFeatures};
use crate::{FeatureParams, LearnError, Result};

/// One training sample: a sliced point on a moving actor at sweep `scan ≥ 1`.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// Sequence name.
    pub sequence: String,
    /// Sweep index within the sequence.
    pub scan: u32,
    /// Index of the point among the sweep's points.
    pub point: usize,
    /// Actor id (instance id of the point's label).
    pub actor: u16,
    /// Importance weight: mean absolute difference value of the heading patch (thesis Eq. 3.1).
    pub weight: f64,
    /// Bearing of sensor → point, world frame.
    pub bearing_rad: f64,
    /// sin(heading − bearing): the first heading target (thesis 3.1.1).
    pub sin_rel: f64,
    /// cos(heading − bearing): the second heading target.
    pub cos_rel: f64,
    /// The actor's true heading, world frame.
    pub heading_rad: f64,
    /// The actor's true speed: the speed target.
    pub speed_mps: f64,
    /// Features of the patch aligned to the bearing (input of the heading GPs).
    pub heading_features: Vec<f64>,
    /// Features of the patch aligned to the true heading (input of the speed GP).
    pub speed_features: Vec<f64>,
}

/// A set of importance-sampled training samples drawn from a whole dataset.
#[derive(Debug, Clone, PartialEq)]
pub struct SampleSet {
    /// Feature kind of both feature vectors.
    pub kind: FeatureKind,
    /// Map prior the features were computed with.
    pub prior: f64,
    /// Number of candidate points the samples were drawn from.
    pub pool_size: usize,
    /// The samples, in dataset order (sequence name, sweep, point).
    pub samples: Vec<Sample>,
}

/// One pair of consecutive sweeps: sequence number and current sweep index.
type Unit = (usize, usize);

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

    /// Like [`Self::collect`], calling `progress(done, total)` as sweep pairs finish.
    ///
    /// Two passes keep memory small on large datasets: the first computes only each candidate's
    /// weight; after [`importance_sample`] the second recomputes the features of the sweep pairs
    /// holding a selected sample. Both passes run in parallel over sweep pairs and keep the
    /// dataset order, so the result depends only on the data, the parameters and the seed.
    pub fn collect_with_progress(
        dataset: &Dataset,
        params: &FeatureParams,
        kind: FeatureKind,
        n: usize,
        seed: u64,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Self> {
        params.validate()?;
        let readers = dataset
            .sequences()
            .iter()
            .map(|s| dataset.sequence(&s.name))
            .collect::<patchflow_dataset::Result<Vec<_>>>()?;
        let units: Vec<Unit> = readers
            .iter()
            .enumerate()
            .flat_map(|(s, r)| (1..r.len()).map(move |t| (s, t)))
            .collect();
        let done = AtomicUsize::new(0);
        let total = AtomicUsize::new(2 * units.len());
        let tick = || {
            let d = done.fetch_add(1, Ordering::Relaxed) + 1;
            progress(d, total.load(Ordering::Relaxed));
        };
        // Pass 1 (thesis 3.1.2): weight of every candidate.
        let per_unit = units
            .par_iter()
            .map(|&unit| {
                let (features, curr) = features_of(&readers, unit, params)?;
                let candidates = moving_points(&features, &curr)
                    .map(|(i, _)| (unit, i, features.heading_patch(i).mean_abs_difference()))
                    .collect::<Vec<_>>();
                tick();
                Ok(candidates)
            })
            .collect::<Result<Vec<_>>>()?;
        let pool: Vec<(Unit, usize, f64)> = per_unit.into_iter().flatten().collect();
        if pool.is_empty() {
            return Err(LearnError::DegenerateData(format!(
                "{}: no sliced point on a moving actor",
                dataset.root().display()
            )));
        }
        let weights: Vec<f64> = pool.iter().map(|c| c.2).collect();
        let picked = importance_sample(&weights, n, seed);
        // Pass 2: features of the selected candidates, grouped by sweep pair.
        let mut groups: Vec<(Unit, Vec<(usize, f64)>)> = Vec::new();
        for &k in &picked {
            let (unit, i, w) = pool[k];
            match groups.last_mut() {
                Some((u, members)) if *u == unit => members.push((i, w)),
                _ => groups.push((unit, vec![(i, w)])),
            }
        }
        total.store(units.len() + groups.len(), Ordering::Relaxed);
        let samples = groups
            .par_iter()
            .map(|(unit, members)| {
                let (features, curr) = features_of(&readers, *unit, params)?;
                let name = &readers[unit.0].info().name;
                let out = members
                    .iter()
                    .filter_map(|&(i, weight)| sample_at(&features, &curr, i, weight, kind, name))
                    .collect::<Vec<_>>();
                tick();
                Ok(out)
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(Self {
            kind,
            prior: params.prior,
            pool_size: pool.len(),
            samples: samples.into_iter().flatten().collect(),
        })
    }

    /// Names of the feature columns.
    pub fn feature_names(&self) -> Vec<String> {
        self.kind.names()
    }
}

/// Reads sweeps `t − 1` and `t` of a sequence and computes the features of `t`.
fn features_of(
    readers: &[SequenceReader],
    (seq, t): Unit,
    params: &FeatureParams,
) -> Result<(SweepFeatures, Sweep)> {
    let reader = &readers[seq];
    let prev = reader.read_sweep(t - 1)?;
    let curr = reader.read_sweep(t)?;
    let features = SweepFeatures::compute(&prev, &curr, params).map_err(|e| {
        let file = reader.dir().join("velodyne").join(format!("{t:06}.bin"));
        LearnError::DegenerateData(format!("{}: {e}", file.display()))
    })?;
    Ok((features, curr))
}

/// Sliced points on a moving actor whose truth is in the sweep: `(point, actor id)`.
fn moving_points<'a>(
    features: &'a SweepFeatures,
    curr: &'a Sweep,
) -> impl Iterator<Item = (usize, u16)> + 'a {
    features.points().iter().enumerate().filter_map(|(i, p)| {
        let label = curr.labels.get(p.index)?;
        let actor = label.instance();
        (label.is_moving() && curr.objects.iter().any(|o| o.id == actor)).then_some((i, actor))
    })
}

/// The sample of sliced point `i` (thesis 3.1.1 targets, 2.2.2 patches).
fn sample_at(
    features: &SweepFeatures,
    curr: &Sweep,
    i: usize,
    weight: f64,
    kind: FeatureKind,
    sequence: &str,
) -> Option<Sample> {
    let point = features.points()[i].index;
    let actor = curr.labels.get(point)?.instance();
    let truth = curr.objects.iter().find(|o| o.id == actor)?;
    let bearing_rad = features.bearing_rad(i);
    let relative = truth.heading_rad - bearing_rad;
    Some(Sample {
        sequence: sequence.to_owned(),
        scan: curr.index,
        point,
        actor,
        weight,
        bearing_rad,
        sin_rel: relative.sin(),
        cos_rel: relative.cos(),
        heading_rad: truth.heading_rad,
        speed_mps: truth.speed_mps,
        heading_features: features.feature_of(&features.heading_patch(i), kind),
        speed_features: features.feature_of(&features.speed_patch(i, truth.heading_rad), kind),
    })
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
