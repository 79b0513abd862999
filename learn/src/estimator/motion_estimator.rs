//! The motion estimator of thesis 3.1: three GPs learned from importance-sampled map patches,
//! applied per point and merged per cluster.

use nalgebra::{DMatrix, DVector};
use patchflow_dataset::Dataset;

use super::merge::{Gaussian, HeadingVote, MergeRule, merge_heading, merge_scalar};
use super::params::EstimatorParams;
use crate::{
    FeatureKind, FeatureParams, GpKind, GpModel, GpParams, LearnError, Result, SampleSet,
    SweepFeatures,
};

/// A merged motion estimate for one cluster.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClusterMotion {
    /// Heading, world frame, CCW from +x.
    pub heading_rad: f64,
    /// Approximate variance of the heading, rad².
    pub heading_var: f64,
    /// Speed, m/s.
    pub speed_mps: f64,
    /// Variance of the merged speed, (m/s)².
    pub speed_var: f64,
    /// Points whose heading predictions took part in the merge.
    pub heading_votes: usize,
}

/// What a cluster gets under both merge rules (thesis 3.1.4).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClusterEstimate {
    /// Product of all per-point predictions.
    pub all: Option<ClusterMotion>,
    /// Product of the low-variance predictions only.
    pub best: Option<ClusterMotion>,
}

/// A trained motion estimator: GPs for sin and cos of the heading relative to the bearing, and
/// for the speed on heading-aligned patches (thesis 3.1.1).
#[derive(Debug, Clone)]
pub struct MotionEstimator {
    pub(crate) gp: GpKind,
    pub(crate) feature: FeatureKind,
    pub(crate) features: FeatureParams,
    pub(crate) heading_sin: GpModel,
    pub(crate) heading_cos: GpModel,
    pub(crate) speed: GpModel,
    pub(crate) training: TrainingRecord,
}

/// What the training saw, kept in the model file for reproducibility.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TrainingRecord {
    /// Sequences the samples were drawn from.
    pub sequences: Vec<String>,
    /// Candidate points in the pool.
    pub pool_size: usize,
    /// Samples drawn.
    pub samples: usize,
    /// Whether the GPs also saw each sample's mirror image (twice the rows).
    pub mirror_images: bool,
    /// Pseudo-inputs per sparse GP.
    pub pseudo_inputs: usize,
    /// Seed of sampling and initialisation.
    pub seed: u64,
    /// Wall time of the whole training, seconds. Not written to the model file, so that identical
    /// runs give byte-identical files; 0 in a loaded model.
    #[serde(skip)]
    pub seconds: f64,
}

impl MotionEstimator {
    /// Trains on every sequence of a dataset (thesis 3.1.1-3.1.3).
    pub fn train(dataset: &Dataset, params: &EstimatorParams) -> Result<Self> {
        Self::train_with_progress(dataset, params, &|_, _| {})
    }

    /// Like [`Self::train`], reporting sample collection as `progress(done, total)` sweep pairs.
    pub fn train_with_progress(
        dataset: &Dataset,
        params: &EstimatorParams,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Self> {
        params.validate()?;
        let start = std::time::Instant::now();
        // 3.1.2: importance-sample points on moving actors by the motion their patch shows.
        let set = SampleSet::collect_with_progress(
            dataset,
            &params.features,
            params.feature,
            params.samples,
            params.seed,
            progress,
        )?;
        let mut estimator = Self::fit_samples(&set, params)?.with_sequences(dataset);
        estimator.training.seconds = start.elapsed().as_secs_f64();
        Ok(estimator)
    }

    /// Fits the three GPs to an already drawn sample set (thesis 3.1.1, 3.1.3).
    pub fn fit_samples(set: &SampleSet, params: &EstimatorParams) -> Result<Self> {
        params.validate()?;
        let start = std::time::Instant::now();
        if set.samples.len() < 2 {
            return Err(LearnError::DegenerateData(format!(
                "{} training samples on moving actors; the dataset needs moving actors in the height slice",
                set.samples.len()
            )));
        }
        let drawn = set;
        // Each sample and its mirror image across the line of sight (learn::features::mirror).
        let mirrored;
        let set = if params.mirror_images {
            mirrored = set.with_mirror_images();
            &mirrored
        } else {
            set
        };
        let names = set.kind.names();
        let heading_x = rows_to_matrix(
            set.samples.iter().map(|s| s.heading_features.as_slice()),
            names.len(),
        )?;
        let speed_x = rows_to_matrix(
            set.samples.iter().map(|s| s.speed_features.as_slice()),
            names.len(),
        )?;
        let sin_y =
            DVector::from_iterator(set.samples.len(), set.samples.iter().map(|s| s.sin_rel));
        let cos_y =
            DVector::from_iterator(set.samples.len(), set.samples.iter().map(|s| s.cos_rel));
        let speed_y =
            DVector::from_iterator(set.samples.len(), set.samples.iter().map(|s| s.speed_mps));
        let gp = |seed_offset: u64| {
            GpParams::new(params.gp)
                .pseudo_inputs(params.pseudo_inputs.min(set.samples.len()))
                .max_iters(params.max_iters)
                .seed(params.seed.wrapping_add(seed_offset))
        };
        // 3.1.1: one GP for each of sin and cos of (heading − bearing), one for the speed.
        let heading_sin = named(gp(1).fit(&heading_x, &sin_y)?, &names, "sin_rel");
        let heading_cos = named(gp(2).fit(&heading_x, &cos_y)?, &names, "cos_rel");
        let speed = named(gp(3).fit(&speed_x, &speed_y)?, &names, "speed");
        let training = TrainingRecord {
            sequences: Vec::new(),
            pool_size: drawn.pool_size,
            samples: drawn.samples.len(),
            mirror_images: params.mirror_images,
            pseudo_inputs: params.pseudo_inputs,
            seed: params.seed,
            seconds: start.elapsed().as_secs_f64(),
        };
        Ok(Self {
            gp: params.gp,
            feature: set.kind,
            features: FeatureParams {
                prior: set.prior,
                ..params.features.clone()
            },
            heading_sin,
            heading_cos,
            speed,
            training,
        })
    }

    /// Records the dataset's sequences as the training data (for models fitted with
    /// [`Self::fit_samples`] on samples drawn from it).
    pub fn with_sequences(mut self, dataset: &Dataset) -> Self {
        self.training.sequences = dataset.sequences().iter().map(|s| s.name.clone()).collect();
        self
    }

    /// GP kind of the three regressions.
    pub fn gp_kind(&self) -> GpKind {
        self.gp
    }

    /// Feature kind the GPs read.
    pub fn feature_kind(&self) -> FeatureKind {
        self.feature
    }

    /// Feature parameters the model was trained with; run-time maps must use the same.
    pub fn feature_params(&self) -> &FeatureParams {
        &self.features
    }

    /// What the training saw.
    pub fn training(&self) -> &TrainingRecord {
        &self.training
    }

    /// The three GPs: sin and cos of the relative heading, and the speed.
    pub fn gps(&self) -> [&GpModel; 3] {
        [&self.heading_sin, &self.heading_cos, &self.speed]
    }

    /// Estimates the motion of one cluster (thesis 3.1, steps 3 and 4), under both merge rules.
    /// `members` index `features.points()`.
    pub fn estimate_cluster(
        &self,
        features: &SweepFeatures,
        members: &[usize],
    ) -> Result<ClusterEstimate> {
        if members.is_empty() {
            return Ok(ClusterEstimate::default());
        }
        // 3a-b: heading patches aligned to each point's bearing; per-point sin and cos predictions.
        let patches = features.heading_patches(members);
        let x = self.feature_matrix(features, &patches)?;
        let sin = self.heading_sin.predict(&x)?;
        let cos = self.heading_cos.predict(&x)?;
        let votes: Vec<HeadingVote> = members
            .iter()
            .enumerate()
            .map(|(k, &i)| {
                let s = Gaussian {
                    mean: sin.mean[k],
                    var: sin.var_y[k],
                };
                let c = Gaussian {
                    mean: cos.mean[k],
                    var: cos.var_y[k],
                };
                HeadingVote::from_relative(features.bearing_rad(i), s, c)
            })
            .collect();
        // 3c and 4: merge the headings, then predict and merge the speed along each merged heading.
        let all = self.speed_along(features, members, &votes, MergeRule::All)?;
        let best = self.speed_along(features, members, &votes, MergeRule::Best)?;
        Ok(ClusterEstimate { all, best })
    }

    fn speed_along(
        &self,
        features: &SweepFeatures,
        members: &[usize],
        votes: &[HeadingVote],
        rule: MergeRule,
    ) -> Result<Option<ClusterMotion>> {
        let Some(heading) = merge_heading(votes, rule) else {
            return Ok(None);
        };
        // 4a-c: speed patches aligned to the merged heading, per-point speeds, merged the same way.
        let patches: Vec<_> = members
            .iter()
            .map(|&i| features.speed_patch(i, heading.heading_rad))
            .collect();
        let x = self.feature_matrix(features, &patches)?;
        let speed = self.speed.predict(&x)?;
        let predictions: Vec<Gaussian> = (0..members.len())
            .map(|k| Gaussian {
                mean: speed.mean[k],
                var: speed.var_y[k],
            })
            .collect();
        Ok(merge_scalar(&predictions, rule).map(|s| ClusterMotion {
            heading_rad: heading.heading_rad,
            heading_var: heading.var_rad2,
            speed_mps: s.mean.max(0.0),
            speed_var: s.var,
            heading_votes: heading.votes,
        }))
    }

    fn feature_matrix(
        &self,
        features: &SweepFeatures,
        patches: &[crate::Patch],
    ) -> Result<DMatrix<f64>> {
        let rows: Vec<Vec<f64>> = patches
            .iter()
            .map(|p| features.feature_of(p, self.feature))
            .collect();
        let d = self.feature.names().len();
        rows_to_matrix(rows.iter().map(Vec::as_slice), d)
    }
}

/// Records the feature and target names in a fitted GP, so its model file is self-describing.
fn named(mut model: GpModel, inputs: &[String], target: &str) -> GpModel {
    model.input_names = inputs.to_vec();
    model.target_name = target.to_owned();
    model
}

/// Stacks feature rows into an N × D matrix, checking every row's length.
fn rows_to_matrix<'a>(
    rows: impl ExactSizeIterator<Item = &'a [f64]>,
    d: usize,
) -> Result<DMatrix<f64>> {
    let n = rows.len();
    let mut x = DMatrix::zeros(n, d);
    for (r, row) in rows.enumerate() {
        if row.len() != d {
            return Err(LearnError::DegenerateData(format!(
                "feature row {r} has {} values, expected {d}",
                row.len()
            )));
        }
        for (c, v) in row.iter().enumerate() {
            x[(r, c)] = *v;
        }
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
    use patchflow_dataset::{Pose, SequenceWriter, Sweep};

    /// A car at `speed_mps` driving at `heading_rad` past a sensor at the origin; `sweeps` sweeps.
    fn car_sweeps(heading_rad: f64, speed_mps: f64, sweeps: u32) -> Vec<Sweep> {
        let lidar = SyntheticLidar::with_resolution(24, 900);
        let start = [
            12.0 - 6.0 * heading_rad.cos(),
            3.0 - 6.0 * heading_rad.sin(),
        ];
        let mut scene = SyntheticScene {
            boxes: vec![SceneBox::car(1, start, heading_rad, speed_mps)],
        };
        let mut out = Vec::new();
        for i in 0..sweeps {
            out.push(scene.scan(&lidar, [0.0, 0.0], 0.0, i));
            scene = scene.advanced(0.1);
        }
        out
    }

    fn write_dataset(root: &std::path::Path, tracks: &[(f64, f64)]) -> Dataset {
        for (k, &(heading, speed)) in tracks.iter().enumerate() {
            let writer = SequenceWriter::open(root, &format!("track{k:02}")).unwrap();
            let sweeps = car_sweeps(heading, speed, 8);
            for s in &sweeps {
                writer.write_sweep(s).unwrap();
            }
            let poses: Vec<Pose> = sweeps.iter().map(|s| s.world_from_sensor).collect();
            let stamps: Vec<f64> = sweeps.iter().map(|s| s.stamp_secs).collect();
            writer
                .finish("synthetic", 0, 10.0, &poses, &stamps, "test")
                .unwrap();
        }
        Dataset::open(root).unwrap()
    }

    fn small_params() -> EstimatorParams {
        EstimatorParams {
            gp: GpKind::Spgp,
            features: FeatureParams {
                half_extent_m: 20.0,
                ..FeatureParams::default()
            },
            samples: 300,
            pseudo_inputs: 15,
            max_iters: 60,
            ..EstimatorParams::default()
        }
    }

    fn estimate_for(
        estimator: &MotionEstimator,
        heading_rad: f64,
        speed_mps: f64,
    ) -> ClusterEstimate {
        let sweeps = car_sweeps(heading_rad, speed_mps, 4);
        let features =
            SweepFeatures::compute(&sweeps[2], &sweeps[3], estimator.feature_params()).unwrap();
        let biggest = (0..features.clusters().len())
            .max_by_key(|&c| features.clusters().members(c).len())
            .unwrap();
        estimator
            .estimate_cluster(&features, features.clusters().members(biggest))
            .unwrap()
    }

    #[test]
    fn a_trained_estimator_recovers_heading_and_speed_of_a_held_out_car() {
        let dir = tempfile::tempdir().unwrap();
        let tracks: Vec<(f64, f64)> = (0..8)
            .map(|k| (-3.0 + 0.8 * k as f64, 4.0 + (k % 3) as f64 * 2.0))
            .collect();
        let dataset = write_dataset(dir.path(), &tracks);
        let estimator = MotionEstimator::train(&dataset, &small_params()).unwrap();
        let (heading, speed) = (0.2, 6.0);
        let all = estimate_for(&estimator, heading, speed).all.unwrap();
        let heading_error_deg = (all.heading_rad - heading)
            .sin()
            .atan2((all.heading_rad - heading).cos())
            .to_degrees();
        assert!(
            heading_error_deg.abs() < 30.0,
            "heading error {heading_error_deg:.1} deg: {all:?}"
        );
        assert!((all.speed_mps - speed).abs() < 2.5, "speed {all:?}");
    }

    #[test]
    fn a_saved_model_loads_and_predicts_identically() {
        let dir = tempfile::tempdir().unwrap();
        let dataset = write_dataset(dir.path(), &[(0.5, 5.0), (-1.5, 7.0), (2.5, 4.0)]);
        let params = EstimatorParams {
            samples: 100,
            pseudo_inputs: 8,
            max_iters: 15,
            ..small_params()
        };
        let estimator = MotionEstimator::train(&dataset, &params).unwrap();
        let path = dir.path().join("model.json");
        estimator.save(&path).unwrap();
        let loaded = MotionEstimator::load(&path).unwrap();
        assert_eq!(loaded.feature_params(), estimator.feature_params());
        assert_eq!(
            estimate_for(&loaded, 0.5, 5.0),
            estimate_for(&estimator, 0.5, 5.0)
        );
    }

    #[test]
    fn a_model_file_of_another_version_is_refused_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("old.json");
        std::fs::write(
            &path,
            r#"{"format": "patchflow-motion-model", "version": 0}"#,
        )
        .unwrap();
        let err = MotionEstimator::load(&path).unwrap_err().to_string();
        assert!(
            err.contains("old.json") && err.contains("version 0"),
            "{err}"
        );
    }

    #[test]
    fn a_dataset_without_moving_actors_is_a_clear_error() {
        let dir = tempfile::tempdir().unwrap();
        let dataset = write_dataset(dir.path(), &[(0.0, 0.0)]);
        let err = MotionEstimator::train(&dataset, &small_params()).unwrap_err();
        assert!(
            matches!(
                err,
                LearnError::DegenerateData(_) | LearnError::InvalidParams(_)
            ),
            "{err}"
        );
    }

    #[test]
    fn mirror_images_double_the_rows_each_gp_is_fitted_to() {
        let dir = tempfile::tempdir().unwrap();
        let dataset = write_dataset(dir.path(), &[(0.4, 5.0)]);
        let params = EstimatorParams {
            max_iters: 5,
            ..small_params()
        };
        let set = SampleSet::collect(
            &dataset,
            &params.features,
            params.feature,
            params.samples,
            params.seed,
        )
        .unwrap();
        let n = set.samples.len();
        let with = MotionEstimator::fit_samples(&set, &params).unwrap();
        let thesis = EstimatorParams {
            mirror_images: false,
            ..params
        };
        let without = MotionEstimator::fit_samples(&set, &thesis).unwrap();
        assert!(with.gps().iter().all(|gp| gp.fit_report().n == 2 * n));
        assert!(without.gps().iter().all(|gp| gp.fit_report().n == n));
        assert_eq!(with.training().samples, n);
        assert!(with.training().mirror_images && !without.training().mirror_images);
    }
}
