//! The motion estimator of thesis 3.1: three GPs learned from importance-sampled map patches
//! (training here; the per-scan step, thesis Algorithm 3.1, in `scan_motion.rs`).

use nalgebra::DVector;
use patchflow_dataset::Dataset;

use super::feature_matrix::rows_to_matrix;
use super::params::{EstimatorParams, EstimatorValidParams};
use crate::{
    FeatureKind, FeatureParams, FeatureValidParams, GpKind, GpModel, GpParams, LearnError, Result,
    SampleSet, SweepFeatures,
};

/// A trained motion estimator: GPs for sin and cos of the heading relative to the bearing, and
/// for the speed on heading-aligned patches (thesis 3.1.1).
#[derive(Debug, Clone)]
pub struct MotionEstimator {
    pub(crate) gp: GpKind,
    pub(crate) feature: FeatureKind,
    pub(crate) features: FeatureValidParams,
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
        let params = params.check()?;
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
        let mut estimator = Self::fit_checked(&set, &params)?.with_sequences(dataset);
        estimator.training.seconds = start.elapsed().as_secs_f64();
        Ok(estimator)
    }

    /// Fits the three GPs to an already drawn sample set (thesis 3.1.1, 3.1.3): its first
    /// `params.samples` samples (they are in dataset order, so these are a sample too). A set
    /// drawn with another feature kind or other feature parameters than `params` holds is an
    /// error: the model carries `params.features` and its GPs must have seen such features.
    pub fn fit_samples(set: &SampleSet, params: &EstimatorParams) -> Result<Self> {
        Self::fit_checked(set, &params.check()?)
    }

    /// [`Self::fit_samples`] with parameters checked beforehand.
    pub fn fit_checked(set: &SampleSet, params: &EstimatorValidParams) -> Result<Self> {
        let start = std::time::Instant::now();
        if set.kind != params.feature {
            return Err(LearnError::InvalidParams(format!(
                "the samples carry {:?} features but the estimator parameters ask for {:?}",
                set.kind, params.feature
            )));
        }
        if set.features != params.features {
            return Err(LearnError::InvalidParams(format!(
                "the samples were drawn with feature parameters {:?} but the estimator parameters hold {:?}; draw them with EstimatorParams::features",
                set.features, params.features
            )));
        }
        let first;
        let set = if set.samples.len() > params.samples {
            first = SampleSet {
                samples: set.samples[..params.samples].to_vec(),
                ..set.clone()
            };
            &first
        } else {
            set
        };
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
        let heading_sin = gp(1)
            .check()?
            .fit_named(&heading_x, &sin_y, &names, "sin_rel")?;
        let heading_cos = gp(2)
            .check()?
            .fit_named(&heading_x, &cos_y, &names, "cos_rel")?;
        let speed = gp(3)
            .check()?
            .fit_named(&speed_x, &speed_y, &names, "speed")?;
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
            features: params.features().clone(),
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

    /// Refuses features computed with other map, slice or cluster parameters than this model
    /// was trained with (the training-only `speed_jitter_deg` aside): its GPs never saw them.
    pub(super) fn check_features(&self, features: &SweepFeatures) -> Result<()> {
        let run_time = FeatureParams {
            speed_jitter_deg: self.features.speed_jitter_deg,
            ..features.params().clone()
        };
        if run_time == *self.features.params() {
            Ok(())
        } else {
            Err(LearnError::InvalidParams(format!(
                "features computed with {:?}, but the model was trained with {:?}; compute them with MotionEstimator::feature_params",
                features.params(),
                self.features.params()
            )))
        }
    }

    /// What the training saw.
    pub fn training(&self) -> &TrainingRecord {
        &self.training
    }

    /// The three GPs: sin and cos of the relative heading, and the speed.
    pub fn gps(&self) -> [&GpModel; 3] {
        [&self.heading_sin, &self.heading_cos, &self.speed]
    }
}

#[cfg(test)]
#[path = "motion_estimator_tests.rs"]
mod tests;
