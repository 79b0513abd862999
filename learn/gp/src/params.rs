//! Fit parameters in the linfa/egobox shape: [`GpParams`] (builder with thesis defaults) →
//! [`GpValidParams`] (checked) → [`GpModel`](super::GpModel) (fitted). The kernel is a type
//! parameter, SE-ARD ([`Stationary::se_ard`]) unless [`GpParams::kernel`] picks another.

use std::fmt;
use std::str::FromStr;

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use super::hyper::Hyper;
use super::kernel::Kernel;
use super::stationary::Stationary;
use crate::{GpError, Result};

/// Which Gaussian process to fit (thesis 3.1.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum GpKind {
    /// Exact GP, O(N³): small problems and reference.
    Full,
    /// Sparse GP with learned pseudo-inputs (SPGP / FITC, Snelson & Ghahramani 2006).
    Spgp,
    /// SPGP with one learned noise term per pseudo-input, K_M + diag(h) (thesis eq. 3.34).
    SpgpHet,
}

impl GpKind {
    /// The name used on the command line and in model files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Full => "full",
            Self::Spgp => "spgp",
            Self::SpgpHet => "spgp-het",
        }
    }
}

impl fmt::Display for GpKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for GpKind {
    type Err = GpError;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "full" => Ok(Self::Full),
            "spgp" => Ok(Self::Spgp),
            "spgp-het" => Ok(Self::SpgpHet),
            other => Err(GpError::InvalidParams(format!(
                "unknown GP kind '{other}' (expected full, spgp or spgp-het)"
            ))),
        }
    }
}

/// Parameters of a GP fit. Defaults follow the thesis (M = 100, §4.3) and gp.md §5.
#[derive(Debug, Clone, PartialEq)]
pub struct GpParams<K = Stationary> {
    kind: GpKind,
    kernel: K,
    pseudo_inputs: usize,
    max_iters: usize,
    max_evals: Option<usize>,
    seed: u64,
    jitter: f64,
    noise_floor: f64,
    grad_tol: f64,
    rel_tol: f64,
    optimise_pseudo_inputs: bool,
    zero_mean: bool,
    start_pseudo_inputs: Option<DMatrix<f64>>,
    start_hyper: Option<Hyper<K>>,
    noise_weights: Option<DVector<f64>>,
}

impl Default for GpParams {
    fn default() -> Self {
        Self::new(GpKind::SpgpHet)
    }
}

impl GpParams {
    /// Defaults for `kind`: SE-ARD, 100 pseudo-inputs, 200 L-BFGS iterations, seed 0, jitter
    /// 1e-6·s, noise floor 1e-6·var(y).
    pub fn new(kind: GpKind) -> Self {
        Self {
            kind,
            kernel: Stationary::se_ard(),
            pseudo_inputs: 100,
            max_iters: 200,
            max_evals: None,
            seed: 0,
            jitter: 1e-6,
            noise_floor: 1e-6,
            grad_tol: 1e-5,
            rel_tol: 1e-9,
            optimise_pseudo_inputs: true,
            zero_mean: false,
            start_pseudo_inputs: None,
            start_hyper: None,
            noise_weights: None,
        }
    }
}

impl<K: Kernel> GpParams<K> {
    /// The covariance function (its starting values come from the data at fit time).
    pub fn kernel<K2: Kernel>(self, kernel: K2) -> GpParams<K2> {
        GpParams {
            kind: self.kind,
            kernel,
            pseudo_inputs: self.pseudo_inputs,
            max_iters: self.max_iters,
            max_evals: self.max_evals,
            seed: self.seed,
            jitter: self.jitter,
            noise_floor: self.noise_floor,
            grad_tol: self.grad_tol,
            rel_tol: self.rel_tol,
            optimise_pseudo_inputs: self.optimise_pseudo_inputs,
            zero_mean: self.zero_mean,
            start_pseudo_inputs: self.start_pseudo_inputs,
            // A start of another kernel type cannot carry over.
            start_hyper: None,
            noise_weights: self.noise_weights,
        }
    }
    /// Number of pseudo-inputs M (sparse kinds; capped at N during the fit).
    pub fn pseudo_inputs(mut self, m: usize) -> Self {
        self.pseudo_inputs = m;
        self
    }
    /// Iteration limit of the optimiser.
    pub fn max_iters(mut self, k: usize) -> Self {
        self.max_iters = k;
        self
    }
    /// Evaluation limit of the optimiser (default 2·iterations + 20).
    pub fn max_evals(mut self, k: usize) -> Self {
        self.max_evals = Some(k);
        self
    }
    /// Seed of the pseudo-input initialisation.
    pub fn seed(mut self, s: u64) -> Self {
        self.seed = s;
        self
    }
    /// Jitter on K_M's (or K's) diagonal, relative to the signal variance.
    pub fn jitter(mut self, j: f64) -> Self {
        self.jitter = j;
        self
    }
    /// Lower bound of the noise variance, relative to the target variance.
    pub fn noise_floor(mut self, f: f64) -> Self {
        self.noise_floor = f;
        self
    }
    /// Convergence tolerances: largest gradient component, and relative objective change.
    pub fn tolerances(mut self, grad_tol: f64, rel_tol: f64) -> Self {
        self.grad_tol = grad_tol;
        self.rel_tol = rel_tol;
        self
    }

    /// Whether the pseudo-inputs are optimised with the hyperparameters (default, thesis 3.1.3) or
    /// stay at their seeded random subset of the inputs (gp.md §5.5 item 7; egobox never moves
    /// them). Holding them fixed avoids FITC's collapse of σ² on step-like targets such as ±1
    /// labels, where moving pseudo-inputs let the diagonal correction absorb all noise.
    pub fn optimise_pseudo_inputs(mut self, optimise: bool) -> Self {
        self.optimise_pseudo_inputs = optimise;
        self
    }

    /// Whether the prior mean function is 0 in the target's own units (thesis 3.1.3: "the mean
    /// function is set to 0"): the target is then only scaled (by its root mean square), not
    /// centred. The default centres it, so far from the data a prediction returns to the
    /// training targets' mean instead of to 0.
    pub fn zero_mean(mut self, zero: bool) -> Self {
        self.zero_mean = zero;
        self
    }

    /// Starts the pseudo-inputs at these rows (M×D, in the *standardised* input units of the
    /// fit, e.g. k-means centres of standardised inputs) instead of a random subset of the
    /// inputs; with [`Self::optimise_pseudo_inputs`]`(false)` they stay there.
    pub fn start_pseudo_inputs(mut self, z: DMatrix<f64>) -> Self {
        self.start_pseudo_inputs = Some(z);
        self
    }

    /// Starts the optimiser at these hyperparameters (see [`GpParams::start_from`]).
    pub(crate) fn start_hyper(mut self, h: Hyper<K>) -> Self {
        self.start_hyper = Some(h);
        self
    }

    /// A fixed relative noise level per training sample (sparse kinds): sample n's noise
    /// variance is σ²·w_n, σ² still learned (Kersting et al. 2007's G3 with the noise shape of
    /// its noise GP; gp.md §7). Must hold one positive finite value per training row.
    pub fn noise_weights(mut self, w: DVector<f64>) -> Self {
        self.noise_weights = Some(w);
        self
    }

    /// Validates the parameters.
    pub fn check(&self) -> Result<GpValidParams<K>> {
        let bad = |what: &str| Err(GpError::InvalidParams(what.to_string()));
        if self.kind != GpKind::Full && self.pseudo_inputs == 0 {
            return bad("a sparse GP needs at least one pseudo-input");
        }
        if !(self.jitter.is_finite() && self.jitter > 0.0 && self.jitter < 1.0) {
            return bad("jitter must be in (0, 1)");
        }
        if !(self.noise_floor.is_finite() && self.noise_floor > 0.0 && self.noise_floor < 1.0) {
            return bad("noise floor must be in (0, 1)");
        }
        if !(self.grad_tol >= 0.0 && self.rel_tol >= 0.0) {
            return bad("tolerances must be non-negative");
        }
        if let Some(w) = &self.noise_weights {
            if self.kind == GpKind::Full {
                return bad("per-sample noise weights need a sparse GP kind");
            }
            if w.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
                return bad("noise weights must be positive and finite");
            }
        }
        if let Some(h) = &self.start_hyper
            && ((self.kind == GpKind::SpgpHet) != h.pseudo_noise.is_some()
                || (self.kind == GpKind::Full) != (h.pseudo_inputs.nrows() == 0))
        {
            return bad("a warm start needs a model of the same GP kind");
        }
        if let Some(z) = &self.start_pseudo_inputs
            && (self.kind == GpKind::Full || z.nrows() == 0 || z.iter().any(|v| !v.is_finite()))
        {
            return bad("starting pseudo-inputs need a sparse GP kind and finite rows");
        }
        Ok(GpValidParams(self.clone()))
    }
}

/// Most pseudo-inputs a sparse GP has: its M × M posterior is checked at load in about 5 M³
/// operations (a Cholesky factoring, two products, two more factorings), so at 2000 a model loads
/// in about the time a full GP at its 4000-sample limit takes (one factoring). The thesis uses 100.
pub const MAX_PSEUDO_INPUTS: usize = 2000;

/// Checked [`GpParams`].
#[derive(Debug, Clone, PartialEq)]
pub struct GpValidParams<K = Stationary>(GpParams<K>);

impl<K: Kernel> GpValidParams<K> {
    /// The GP kind.
    pub fn kind(&self) -> GpKind {
        self.0.kind
    }
    /// The kernel (before its values are fitted).
    pub fn kernel(&self) -> &K {
        &self.0.kernel
    }
    /// Requested number of pseudo-inputs.
    pub fn pseudo_inputs(&self) -> usize {
        self.0.pseudo_inputs
    }
    /// Iteration limit.
    pub fn max_iters(&self) -> usize {
        self.0.max_iters
    }
    /// Evaluation limit.
    pub fn max_evals(&self) -> usize {
        self.0.max_evals.unwrap_or(2 * self.0.max_iters + 20)
    }
    /// Initialisation seed.
    pub fn seed(&self) -> u64 {
        self.0.seed
    }
    /// Relative jitter.
    pub fn jitter(&self) -> f64 {
        self.0.jitter
    }
    /// Relative noise floor.
    pub fn noise_floor(&self) -> f64 {
        self.0.noise_floor
    }
    /// (gradient tolerance, relative objective tolerance).
    pub fn tolerances(&self) -> (f64, f64) {
        (self.0.grad_tol, self.0.rel_tol)
    }
    /// Whether the pseudo-inputs are optimised.
    pub fn optimise_pseudo_inputs(&self) -> bool {
        self.0.optimise_pseudo_inputs
    }
    /// Whether the prior mean is 0 in target units ([`GpParams::zero_mean`]).
    pub fn zero_mean(&self) -> bool {
        self.0.zero_mean
    }
    /// Given starting pseudo-inputs, if any.
    pub fn start_pseudo_inputs(&self) -> Option<&DMatrix<f64>> {
        self.0.start_pseudo_inputs.as_ref()
    }
    /// The fitted hyperparameters to start from ([`GpParams::start_from`]), if any.
    pub(crate) fn start_hyper_values(&self) -> Option<&Hyper<K>> {
        self.0.start_hyper.as_ref()
    }
    /// Per-sample noise weights, if any.
    pub fn noise_weights(&self) -> Option<&DVector<f64>> {
        self.0.noise_weights.as_ref()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_parse_from_their_names_and_unknown_names_are_rejected() {
        for k in [GpKind::Full, GpKind::Spgp, GpKind::SpgpHet] {
            assert_eq!(k.name().parse::<GpKind>().expect("known"), k);
        }
        assert!("fitc".parse::<GpKind>().is_err());
    }

    #[test]
    fn zero_pseudo_inputs_fail_the_check() {
        assert!(
            GpParams::new(GpKind::Spgp)
                .pseudo_inputs(0)
                .check()
                .is_err()
        );
        assert!(GpParams::new(GpKind::Full).pseudo_inputs(0).check().is_ok());
    }
}
