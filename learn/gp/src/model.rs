//! A fitted GP: its transforms, hyperparameters and cached posterior, and batch predictions.

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use super::full::FullPosterior;
use super::hyper::Hyper;
use super::kernel::Kernel;
use super::params::GpKind;
use super::sparse_posterior::SparsePosterior;
use super::stationary::Stationary;
use super::transform::Standardiser;
use crate::{GpError, Result};

/// Largest distance of a test input from the training mean, in the fit's standardised units (or
/// the inputs' own units for kernels that take them unscaled): squared distances stay finite,
/// and every decaying kernel is exactly 0 long before it.
pub(crate) const MAX_STANDARDISED_INPUT: f64 = 1e100;

/// Predictive distribution at many test inputs, in the target's units.
#[derive(Debug, Clone, PartialEq)]
pub struct GpPrediction {
    /// Predictive mean.
    pub mean: DVector<f64>,
    /// Latent variance (of f; for SPGP-HET this includes the local noise learned through h).
    pub var_latent: DVector<f64>,
    /// Variance of a new observation: latent variance plus the noise variance σ².
    pub var_y: DVector<f64>,
}

impl GpPrediction {
    /// The prediction as CSV with header `mean,var,var_y` (SPEC §7), one line per test point.
    pub fn to_csv(&self) -> String {
        let mut out = String::from("mean,var,var_y\n");
        for ((m, v), vy) in self
            .mean
            .iter()
            .zip(self.var_latent.iter())
            .zip(self.var_y.iter())
        {
            out.push_str(&format!("{m},{v},{vy}\n"));
        }
        out
    }
}

/// How the fit went.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FitReport {
    /// Training samples N.
    pub n: usize,
    /// Input dimension D.
    pub d: usize,
    /// Pseudo-inputs M (0 for the full GP).
    pub m: usize,
    /// Objective evaluations.
    pub evals: usize,
    /// Optimiser iterations.
    pub iterations: usize,
    /// Wall time of the fit. Not stored in model files, so identical fits give identical files;
    /// 0 for a model read from a file.
    #[serde(skip)]
    pub seconds: f64,
    /// Final negative log marginal likelihood, in the units of the original targets.
    pub nlml: f64,
    /// Why the optimiser stopped.
    pub stop: String,
}

/// What a model keeps from its training data for prediction.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Posterior {
    /// SPGP / SPGP-HET: weights and variance matrix over the pseudo-inputs.
    Sparse(SparsePosterior),
    /// Exact GP: training inputs, C⁻¹y and chol(C).
    Full(FullPosterior),
}

/// A fitted Gaussian process (see [`GpParams`](super::GpParams) for how to get one).
#[derive(Debug, Clone, PartialEq)]
pub struct GpModel<K = Stationary> {
    pub(crate) kind: GpKind,
    pub(crate) input_names: Vec<String>,
    pub(crate) target_name: String,
    pub(crate) inputs: Standardiser,
    pub(crate) target: Standardiser,
    pub(crate) hyper: Hyper<K>,
    pub(crate) jitter: f64,
    pub(crate) posterior: Posterior,
    pub(crate) report: FitReport,
}

impl GpModel<Stationary> {
    /// Lengthscales ℓ_d (not squared), in standardised input units.
    pub fn lengthscales(&self) -> &DVector<f64> {
        self.hyper.kernel.lengthscales()
    }
}

impl<K: Kernel> GpModel<K> {
    /// The model kind.
    pub fn kind(&self) -> GpKind {
        self.kind
    }
    /// Names of the input columns, in order.
    pub fn input_names(&self) -> &[String] {
        &self.input_names
    }
    /// Name of the target column.
    pub fn target_name(&self) -> &str {
        &self.target_name
    }
    /// The fit report.
    pub fn fit_report(&self) -> &FitReport {
        &self.report
    }
    /// The fitted kernel, in the standardised units of the fit.
    pub fn kernel(&self) -> &K {
        &self.hyper.kernel
    }
    /// Noise variance σ² in target units².
    pub fn noise_variance(&self) -> f64 {
        self.hyper.noise_variance * self.target.scale[0].powi(2)
    }
    /// Per-pseudo-input noise h (SPGP-HET), in standardised target units².
    pub fn pseudo_noise(&self) -> Option<&DVector<f64>> {
        self.hyper.pseudo_noise.as_ref()
    }
    /// Pseudo-inputs (M×D), in standardised input units.
    pub fn pseudo_inputs(&self) -> &DMatrix<f64> {
        &self.hyper.pseudo_inputs
    }

    /// Predicts at the rows of `x` (T×D, the model's input columns in order).
    ///
    /// The latent variance is k_** − k_*ᵀ(B_u⁻¹ − A⁻¹)k_* (thesis eq. 3.33 without σ²); for SPGP-HET,
    /// B_u = K_M + diag(h), so it grows near pseudo-inputs with a large noise term h_m.
    /// `var_y` adds the global noise σ².
    pub fn predict(&self, x: &DMatrix<f64>) -> Result<GpPrediction> {
        let d = self.input_names.len();
        if x.ncols() != d {
            return Err(GpError::InvalidParams(format!(
                "the model takes {d} input columns, got {}",
                x.ncols()
            )));
        }
        if let Some(pos) = x.iter().position(|v| !v.is_finite()) {
            let (row, col) = (pos % x.nrows(), pos / x.nrows());
            return Err(GpError::DegenerateData(format!(
                "test input row {row}, column '{}' is not finite",
                self.input_names[col]
            )));
        }
        let cells = (0..x.ncols()).flat_map(|c| (0..x.nrows()).map(move |r| (r, c)));
        self.check_input_range(cells.map(|(r, c)| (r, c, x[(r, c)])))?;
        let xs = self.inputs.apply(x);
        let (mean, var) = match &self.posterior {
            Posterior::Sparse(p) => p.predict(&self.hyper, &xs),
            Posterior::Full(p) => p.predict(&self.hyper, &xs)?,
        };
        self.prediction(&mean, &var)
    }

    /// Refuses a test input that lies more than [`MAX_STANDARDISED_INPUT`] of the fit's
    /// standardised units from the training mean: the kernel's squared distances would overflow
    /// (at ±1e308 a full GP predicted a variance of 0). Takes `(row, column, value)`.
    pub(crate) fn check_input_range(
        &self,
        values: impl Iterator<Item = (usize, usize, f64)>,
    ) -> Result<()> {
        let t = &self.inputs;
        for (row, col, v) in values {
            let standardised = (v - t.mean[col]) / t.scale[col];
            if standardised.is_nan() || standardised.abs() > MAX_STANDARDISED_INPUT {
                return Err(GpError::DegenerateData(format!(
                    "test input row {row}, column '{}' = {v:e} lies {:e} standard deviations from \
                     the training data (at most {MAX_STANDARDISED_INPUT:e})",
                    self.input_names[col],
                    standardised.abs()
                )));
            }
        }
        Ok(())
    }

    /// The prediction in the target's units from standardised mean and latent variance; a value
    /// that is not finite there (a broken target transform) is an error, never a result.
    pub(crate) fn prediction(
        &self,
        mean: &DVector<f64>,
        var: &DVector<f64>,
    ) -> Result<GpPrediction> {
        let noisy = var.map(|v| v + self.hyper.noise_variance);
        let p = GpPrediction {
            mean: self.target.invert_vector(mean),
            var_latent: self.target.invert_variance(var),
            var_y: self.target.invert_variance(&noisy),
        };
        let finite = |v: &DVector<f64>| v.iter().position(|x| !x.is_finite());
        if let Some(row) = finite(&p.mean)
            .or(finite(&p.var_y))
            .or(finite(&p.var_latent))
        {
            return Err(GpError::DegenerateData(format!(
                "the prediction at test input row {row} is not finite (mean {:e}, variance {:e}): \
                 the model's target transform is broken",
                p.mean[row], p.var_y[row]
            )));
        }
        Ok(p)
    }

    /// Predicts at rows given as `f32` slices (each of length D), e.g. feature patches, through
    /// [`GpModel::predict_rows`].
    pub fn predict_rows_f32(&self, rows: &[&[f32]]) -> Result<GpPrediction> {
        let d = self.input_names.len();
        if let Some(bad) = rows.iter().position(|r| r.len() != d) {
            return Err(GpError::InvalidParams(format!(
                "row {bad} has {} values, the model takes {d}",
                rows[bad].len()
            )));
        }
        let flat: Vec<f64> = rows
            .iter()
            .flat_map(|r| r.iter().map(|&v| f64::from(v)))
            .collect();
        self.predict_rows(&flat)
    }
}
