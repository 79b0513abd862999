//! Training parameters of the motion estimator, with the thesis defaults (4.3).

use crate::{FeatureKind, FeatureParams, FeatureValidParams, GpKind, LearnError, Result};

/// Everything that decides how a [`MotionEstimator`](super::MotionEstimator) is trained.
///
/// `Default` gives the thesis' setup: SPGP-HET on 242-value map patches, prior 0.5, 1,600
/// importance-sampled training samples and 100 pseudo-inputs (thesis 4.3), plus the samples'
/// mirror images ([`Self::mirror_images`]) and training speed patches aligned with a heading
/// error (`FeatureParams::speed_jitter_deg`); [`Self::thesis`] leaves both out.
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
    /// see `Sample::mirror_image`): balances the sides that right-hand traffic favours. `false`
    /// is the thesis' training set.
    pub mirror_images: bool,
    /// Pseudo-inputs per sparse GP (thesis 4.3: 100).
    pub pseudo_inputs: usize,
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
            max_iters: 300,
            seed: 0,
        }
    }
}

impl EstimatorParams {
    /// The thesis' training set exactly: no mirror images, training speed patches aligned to the
    /// exact true heading (`FeatureParams::speed_jitter_deg = 0`). See ARCHITECTURE.md for why
    /// the defaults differ.
    ///
    /// ```
    /// let p = patchflow_learn::EstimatorParams::thesis();
    /// assert!(!p.mirror_images && p.features.speed_jitter_deg == 0.0);
    /// ```
    pub fn thesis() -> Self {
        let defaults = Self::default();
        Self {
            mirror_images: false,
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
            return Err(LearnError::InvalidParams(format!(
                "samples must be at least 10, got {}",
                self.samples
            )));
        }
        if self.gp != GpKind::Full && self.pseudo_inputs == 0 {
            return Err(LearnError::InvalidParams(
                "a sparse GP needs at least one pseudo-input".into(),
            ));
        }
        if self.max_iters == 0 {
            return Err(LearnError::InvalidParams(
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
