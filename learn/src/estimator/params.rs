//! Training parameters of the motion estimator, with the thesis defaults (4.3).

use crate::{FeatureKind, FeatureParams, FeatureValidParams, GpKind, LearnError, Result};

/// Everything that decides how a [`MotionEstimator`](super::MotionEstimator) is trained.
///
/// [`Self::thesis`] is the thesis' protocol (3.1, 4.3): SPGP-HET on 242-value map patches, prior
/// 0.5, 1,600 importance-sampled samples, 100 free pseudo-inputs, GPs with a zero mean function.
/// `Default` deviates from it in these fields only (docs/estimator.md has the measurements; the
/// run-time side — ground estimate under the slice, 10-point minimum of an object hypothesis,
/// merge eqs. 3.35-3.37 — is the same for both):
///
/// | field | thesis | default |
/// |---|---|---|
/// | [`Self::mirror_images`] | no | yes |
/// | `features.speed_jitter_deg` | 0 | 25 |
/// | [`Self::zero_mean`] | yes | no (prior mean = training targets' mean) |
/// | [`Self::projection_dims`] | 0 (raw 242 values) | 0 |
/// | [`Self::most_likely_noise`] | no | yes |
#[derive(Debug, Clone, PartialEq)]
pub struct EstimatorParams {
    /// GP used for all three regressions (sin, cos of the relative heading; speed).
    pub gp: GpKind,
    /// Patch values or Gabor responses.
    pub feature: FeatureKind,
    /// Map, cluster and patch parameters (the map prior lives here).
    pub features: FeatureParams,
    /// Importance-sampled training samples (thesis 3.1.2: 1,600).
    pub samples: usize,
    /// Also train on each sample's mirror image across its line of sight (2 × `samples` rows;
    /// see `TrainingSample::mirror_image`): balances the sides that right-hand traffic favours. `false`
    /// is the thesis' training set.
    pub mirror_images: bool,
    /// Pseudo-inputs per sparse GP (thesis 4.3: 100).
    pub pseudo_inputs: usize,
    /// GPs with a zero prior mean in the targets' units (thesis 3.1.3: "the mean function is set
    /// to 0"). `false` centres each target on its training mean, so far from the training inputs
    /// a GP predicts that mean (cos ≈ −0.1, "approaching"; the mean training speed).
    pub zero_mean: bool,
    /// Thesis Ch. 6, low-dimensional inputs: `k > 0` projects each GP's patch values to `k` PLS
    /// directions fitted on its own training targets, and holds its pseudo-inputs at k-means
    /// centres of the projected samples (only the kernel and noise are learned, instead of
    /// 242 × M free coordinates). `0`: the raw patch values, free pseudo-inputs (the thesis).
    pub projection_dims: usize,
    /// Thesis Ch. 6, Kersting et al. 2007's most-likely heteroscedastic GP (one round): a noise
    /// GP fitted to the log of the first fit's held-out (leave-one-out) squared residuals, then
    /// the GP refitted with that noise shape; a vote's variance then carries the noise GP's
    /// prediction at its patch. `false`: the thesis' GP alone.
    pub most_likely_noise: bool,
    /// Optimiser iteration limit per GP.
    pub max_iters: usize,
    /// Seed of sampling and GP initialisation.
    pub seed: u64,
}

impl Default for EstimatorParams {
    fn default() -> Self {
        Self {
            gp: GpKind::SpgpHet,
            feature: FeatureKind::Patch,
            features: FeatureParams::default(),
            samples: 1600,
            mirror_images: true,
            pseudo_inputs: 100,
            zero_mean: false,
            projection_dims: 0,
            most_likely_noise: true,
            max_iters: 300,
            seed: 0,
        }
    }
}

impl EstimatorParams {
    /// The thesis' protocol exactly (`train --preset thesis`): no mirror images, training speed
    /// patches aligned to the exact true heading (`FeatureParams::speed_jitter_deg = 0`), GPs
    /// with a zero mean function on the raw patch values. See the table above for the default.
    ///
    /// ```
    /// let p = patchflow_learn::EstimatorParams::thesis();
    /// assert!(!p.mirror_images && p.features.speed_jitter_deg == 0.0 && p.zero_mean);
    /// ```
    pub fn thesis() -> Self {
        let defaults = Self::default();
        Self {
            mirror_images: false,
            zero_mean: true,
            projection_dims: 0,
            most_likely_noise: false,
            features: FeatureParams {
                speed_jitter_deg: 0.0,
                ..defaults.features.clone()
            },
            ..defaults
        }
    }

    /// Checks the parameters once, before any work, and returns them as
    /// [`EstimatorValidParams`]: training takes those and checks nothing again.
    ///
    /// ```
    /// let p = patchflow_learn::EstimatorParams::default();
    /// assert_eq!(p.check().unwrap().samples, 1600);
    /// ```
    pub fn check(&self) -> Result<EstimatorValidParams> {
        self.validate()?;
        Ok(EstimatorValidParams {
            features: self.features.check()?,
            params: self.clone(),
        })
    }

    fn validate(&self) -> Result<()> {
        if self.samples < 10 {
            return Err(LearnError::invalid_params(format!(
                "samples must be at least 10, got {}",
                self.samples
            )));
        }
        if self.gp != GpKind::Full && self.pseudo_inputs == 0 {
            return Err(LearnError::invalid_params(
                "a sparse GP needs at least one pseudo-input".into(),
            ));
        }
        if self.max_iters == 0 {
            return Err(LearnError::invalid_params(
                "max_iters must be at least 1".into(),
            ));
        }
        Ok(())
    }
}

/// [`EstimatorParams`] that passed [`EstimatorParams::check`] (their feature parameters checked
/// too); reads as the parameters it wraps.
#[derive(Debug, Clone, PartialEq)]
pub struct EstimatorValidParams {
    params: EstimatorParams,
    features: FeatureValidParams,
}

impl EstimatorValidParams {
    /// The checked feature parameters.
    pub fn features(&self) -> &FeatureValidParams {
        &self.features
    }
}

impl std::ops::Deref for EstimatorValidParams {
    type Target = EstimatorParams;

    fn deref(&self) -> &EstimatorParams {
        &self.params
    }
}
