//! Training parameters of the motion estimator, with the thesis defaults (4.3).

use crate::{FeatureKind, FeatureParams, FeatureValidParams, GpKind, LearnError, Result};

/// Everything that decides how a [`MotionEstimator`](super::MotionEstimator) is trained.
///
/// [`Self::thesis`] is the thesis' protocol (3.1, 4.3): SPGP-HET on 242-value map patches, prior
/// 0.5, 1,600 importance-sampled samples, 100 free pseudo-inputs, GPs with a zero mean function.
/// `Default` deviates from it in these fields only (docs/estimator.md has the measurements; the
/// run-time side — ground estimate under the slice, 10-point minimum of an object hypothesis, no
/// estimate for one that has just come into view, merge eqs. 3.35-3.37 — is the same for both):
///
/// | field | thesis | default |
/// |---|---|---|
/// | [`Self::mirror_images`] | no | yes |
/// | `features.speed_jitter_deg` | 0 | 25 |
/// | [`Self::zero_mean`] | yes | no (prior mean = training targets' mean) |
/// | [`Self::projection_dims`] | 0 (raw 242 values) | 0 |
/// | [`Self::most_likely_noise`] | no | yes |
/// | `features.slice_min_m` … `slice_max_m` | 0.5 … 1.0 m | [`BELOW_BELT_SLICE_M`]: 0.5 … 0.85 m |
/// | `features.patch_cell_m` | 0.10 m (the maps' own cells) | [`WIDE_PATCH_CELL_M`]: 0.20 m |
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

/// The default's height slice above the ground (metres, lower and upper edge): the thesis'
/// 0.5-1.0 m (2.1.1) with its top moved down so that it stays under the side glass of every
/// car. Real belt lines (where the side glass starts) run from about 0.88 m on small hatchbacks
/// to 1.25 m on large SUVs (docs/realism.md, "A fleet that varies as real fleets do"); a slice
/// that reaches 1.0 m crosses the glass of a third of the cars, whose beams there are lost or
/// return from behind the pane, so the same car leaves a different outline on the maps from
/// one body to the next. Below 0.85 m every car shows its solid body (doors, bumpers, wheel
/// arches) to the slice. Measured in docs/estimator.md, "The height slice under the belt line".
pub const BELOW_BELT_SLICE_M: (f64, f64) = (0.5, 0.85);

/// The default's patch cell (metres): the 11 × 11 patches sample maps of 0.20 m cells built
/// for them, so a patch reaches 2.2 m, while the clusters' cells and the moving classifier keep
/// the thesis' 0.10 m maps. By the thesis' rule (4.3) 0.10 m cells at 10 Hz detect 2-10 m/s: a
/// car at 10 m/s moves 1 m between sweeps, so a 1.1 m patch centred on its face holds the cells
/// it entered or the ones it left, rarely both; a 2.2 m patch holds both up to about 10 m/s and
/// one side up to 20 m/s. Measured in docs/estimator.md, "Stop 42: patches on maps of their own".
pub const WIDE_PATCH_CELL_M: f64 = 0.20;

impl Default for EstimatorParams {
    fn default() -> Self {
        Self {
            gp: GpKind::SpgpHet,
            feature: FeatureKind::Patch,
            features: FeatureParams {
                slice_min_m: BELOW_BELT_SLICE_M.0,
                slice_max_m: BELOW_BELT_SLICE_M.1,
                patch_cell_m: WIDE_PATCH_CELL_M,
                ..FeatureParams::default()
            },
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
    /// with a zero mean function on the raw patch values, the 0.5-1.0 m height slice (2.1.1).
    /// See the table above for the default.
    ///
    /// ```
    /// let p = patchflow_learn::EstimatorParams::thesis();
    /// assert!(!p.mirror_images && p.features.speed_jitter_deg == 0.0 && p.zero_mean);
    /// assert_eq!((p.features.slice_min_m, p.features.slice_max_m), (0.5, 1.0));
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
                ..FeatureParams::default()
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The lowest belt line the fleet draws (docs/realism.md: compact cars, 0.88 m).
    const LOWEST_BELT_M: f64 = 0.88;

    #[test]
    fn the_default_slice_stays_under_every_belt_line_and_keeps_the_thesis_lower_edge() {
        let p = EstimatorParams::default().features;
        assert!(
            p.slice_max_m <= LOWEST_BELT_M - 0.02,
            "top {} m",
            p.slice_max_m
        );
        assert_eq!(p.slice_min_m, 0.5, "the thesis' lower edge");
        assert!(EstimatorParams::default().check().is_ok());
    }

    #[test]
    fn the_thesis_preset_keeps_the_thesis_slice_and_patches_and_every_other_feature_setting() {
        let thesis = EstimatorParams::thesis().features;
        let default = EstimatorParams::default().features;
        assert_eq!((thesis.slice_min_m, thesis.slice_max_m), (0.5, 1.0));
        assert_eq!((thesis.cell_m, thesis.patch_cell_m), (0.10, 0.10));
        assert_eq!(default.patch_cell_m, WIDE_PATCH_CELL_M);
        assert_eq!(
            thesis,
            FeatureParams {
                slice_min_m: 0.5,
                slice_max_m: 1.0,
                speed_jitter_deg: 0.0,
                patch_cell_m: default.cell_m,
                ..default
            }
        );
    }
}
