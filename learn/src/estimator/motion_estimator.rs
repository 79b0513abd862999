//! The motion estimator of thesis 3.1: three GPs learned from importance-sampled map patches
//! (training here; the per-scan step, thesis Algorithm 3.1, in `scan_motion.rs`).

use nalgebra::DVector;
use patchflow_dataset::Dataset;

use super::feature_matrix::rows_to_matrix;
use super::params::{EstimatorParams, EstimatorValidParams};
use super::regressor::Regressor;
use crate::{
    FeatureKind, FeatureParams, FeatureValidParams, GpKind, GpModel, LearnError, Result, SampleSet,
    SweepFeatures,
};

/// A trained motion estimator: GPs for sin and cos of the heading relative to the bearing, and
/// for the speed on heading-aligned patches (thesis 3.1.1).
#[derive(Debug, Clone)]
pub struct MotionEstimator {
    pub(crate) gp: GpKind,
    pub(crate) feature: FeatureKind,
    pub(crate) features: FeatureValidParams,
    pub(crate) heading_sin: Regressor,
    pub(crate) heading_cos: Regressor,
    pub(crate) speed: Regressor,
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
    /// GPs with a zero prior mean (the thesis); absent in older files (they centred).
    #[serde(default)]
    pub zero_mean: bool,
    /// PLS directions the patches were projected to (0: none).
    #[serde(default)]
    pub projection_dims: usize,
    /// Whether the most-likely heteroscedastic noise GPs were fitted.
    #[serde(default)]
    pub most_likely_noise: bool,
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
            return Err(LearnError::invalid_params(format!(
                "the samples carry {:?} features but the estimator parameters ask for {:?}",
                set.kind, params.feature
            )));
        }
        if set.features != params.features {
            return Err(LearnError::invalid_params(format!(
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
            return Err(LearnError::degenerate_data(format!(
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
        let seed = |offset: u64| params.seed.wrapping_add(offset);
        // 3.1.1: one GP for each of sin and cos of (heading − bearing), one for the speed.
        let heading_sin = Regressor::fit(&heading_x, &sin_y, &names, "sin_rel", params, seed(1))?;
        let heading_cos = Regressor::fit(&heading_x, &cos_y, &names, "cos_rel", params, seed(2))?;
        let speed = Regressor::fit(&speed_x, &speed_y, &names, "speed", params, seed(3))?;
        let training = TrainingRecord {
            sequences: Vec::new(),
            pool_size: drawn.pool_size,
            samples: drawn.samples.len(),
            mirror_images: params.mirror_images,
            pseudo_inputs: params.pseudo_inputs,
            zero_mean: params.zero_mean,
            projection_dims: params.projection_dims,
            most_likely_noise: params.most_likely_noise,
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
            Err(LearnError::invalid_params(format!(
                "features computed with {:?}, but the model was trained with {:?}; compute them with MotionEstimator::feature_params",
                features.params(),
                self.features.params()
            )))
        }
    }

    /// Whether the model was trained by the thesis' protocol exactly
    /// ([`EstimatorParams::thesis`]'s training fields, whatever its sample counts).
    pub fn is_thesis_preset(&self) -> bool {
        let thesis = EstimatorParams::thesis();
        let t = &self.training;
        !t.mirror_images
            && t.zero_mean == thesis.zero_mean
            && t.projection_dims == thesis.projection_dims
            && t.most_likely_noise == thesis.most_likely_noise
            && self.features.speed_jitter_deg == thesis.features.speed_jitter_deg
    }

    /// What the training saw.
    pub fn training(&self) -> &TrainingRecord {
        &self.training
    }

    /// The three GPs: sin and cos of the relative heading, and the speed.
    pub fn gps(&self) -> [&GpModel; 3] {
        [&self.heading_sin.gp, &self.heading_cos.gp, &self.speed.gp]
    }

    /// The three regressions with their projections and noise GPs, if any.
    pub fn regressors(&self) -> [&Regressor; 3] {
        [&self.heading_sin, &self.heading_cos, &self.speed]
    }
}

#[cfg(test)]
#[path = "motion_estimator_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "saved_model_tests.rs"]
mod saved_model_tests;

#[cfg(test)]
#[path = "training_data_tests.rs"]
mod training_data_tests;
