//! Fitting a GP by maximising its marginal likelihood (thesis 3.1.3): standardise, initialise,
//! run L-BFGS on the NLML jointly in Θ, the pseudo-inputs and h, then cache the posterior.

use std::time::Instant;

use nalgebra::{DMatrix, DVector};

use super::full::FullPosterior;
use super::hyper::Hyper;
use super::kernel::Kernel;
use super::lbfgs::{LbfgsOptions, minimize};
use super::model::{FitReport, GpModel, Posterior};
use super::objective::GpObjective;
use super::params::{GpKind, GpParams, GpValidParams};
use super::sparse_posterior::SparsePosterior;
use super::train_data::TrainData;
use super::transform::Standardiser;
use crate::{GpError, Result};

/// Correction pairs kept by L-BFGS.
const LBFGS_MEMORY: usize = 10;

impl<K: Kernel> GpParams<K> {
    /// Checks the parameters and fits `x` (N×D, one sample per row) to `y` (N).
    pub fn fit(&self, x: &DMatrix<f64>, y: &DVector<f64>) -> Result<GpModel<K>> {
        self.check()?.fit(x, y)
    }

    /// Starts the optimiser at `model`'s fitted hyperparameters (kernel, σ², pseudo-inputs and,
    /// for SPGP-HET, h) instead of the seeded start: a warm start for refitting the same inputs,
    /// e.g. with new noise weights. The values are in the standardised units of `model`'s fit,
    /// which a fit on the same `x` and `y` reproduces. (The most-likely heteroscedastic refit
    /// does not use it: docs/speed.md, "Issue 24's time targets: stop 38".) The model's kind
    /// and input dimension must match; with
    /// [`Self::optimise_pseudo_inputs`]`(false)` its pseudo-inputs stay where it left them.
    pub fn start_from(self, model: &GpModel<K>) -> Self {
        self.start_hyper(model.hyper.clone())
    }
}

/// Caches what prediction needs (thesis eqs. 3.32-3.33, or 3.20-3.21 for the full GP).
fn condition<K: Kernel>(
    data: &TrainData,
    kind: GpKind,
    h: &Hyper<K>,
    jitter: f64,
) -> Result<(Posterior, f64)> {
    let eps = jitter * h.kernel.signal_variance();
    Ok(match kind {
        GpKind::Full => {
            let (p, used) = FullPosterior::new(data, h, eps)?;
            (Posterior::Full(p), used)
        }
        GpKind::Spgp | GpKind::SpgpHet => {
            let (p, used) = SparsePosterior::new(data, h, eps)?;
            (Posterior::Sparse(p), used)
        }
    })
}

fn check_data(x: &DMatrix<f64>, y: &DVector<f64>, names: &[String]) -> Result<()> {
    let bad = |why: String| Err(GpError::DegenerateData(why));
    if x.nrows() != y.len() {
        return bad(format!("{} input rows but {} targets", x.nrows(), y.len()));
    }
    if x.nrows() < 2 || x.ncols() == 0 {
        return bad(format!(
            "need at least 2 samples and 1 input, got {}×{}",
            x.nrows(),
            x.ncols()
        ));
    }
    if names.len() != x.ncols() {
        return bad(format!(
            "{} input names for {} input columns",
            names.len(),
            x.ncols()
        ));
    }
    if let Some(pos) = x.iter().position(|v| !v.is_finite()) {
        return bad(format!(
            "input row {}, column '{}' is not finite",
            pos % x.nrows(),
            names[pos / x.nrows()]
        ));
    }
    if let Some(row) = y.iter().position(|v| !v.is_finite()) {
        return bad(format!("target row {row} is not finite"));
    }
    Ok(())
}

/// Errors if a column's standardisation is not finite (values so large that their variance
/// overflows, e.g. a 1e300 cell): the fit would silently work on zeros.
fn check_transform(t: &Standardiser, names: &[&str]) -> Result<()> {
    for ((mean, scale), name) in t.mean.iter().zip(&t.scale).zip(names) {
        if !(mean.is_finite() && scale.is_finite()) {
            return Err(GpError::DegenerateData(format!(
                "column '{name}' has values too large to standardise (mean {mean:e}, spread \
                 {scale:e}); rescale it"
            )));
        }
    }
    Ok(())
}

impl<K: Kernel> GpValidParams<K> {
    /// Fits with input columns named `x0, x1, …` and target `y`.
    pub fn fit(&self, x: &DMatrix<f64>, y: &DVector<f64>) -> Result<GpModel<K>> {
        let names: Vec<String> = (0..x.ncols()).map(|d| format!("x{d}")).collect();
        self.fit_named(x, y, &names, "y")
    }

    /// Fits `x` (N×D) to `y` (N), recording column names for model files and CSV prediction.
    pub fn fit_named(
        &self,
        x: &DMatrix<f64>,
        y: &DVector<f64>,
        input_names: &[String],
        target_name: &str,
    ) -> Result<GpModel<K>> {
        let clock = Instant::now();
        check_data(x, y, input_names)?;
        let kind = self.kind();
        // Standardise inputs per column and the target (stored with the model).
        let inputs = Standardiser::for_kernel(x, self.kernel());
        let target = if self.zero_mean() {
            Standardiser::of_vector_uncentred(y)
        } else {
            Standardiser::of_vector(y)
        };
        let names: Vec<&str> = input_names.iter().map(String::as_str).collect();
        check_transform(&inputs, &names)?;
        check_transform(&target, &[target_name])?;
        // Seeded initialisation: random-subset pseudo-inputs, the kernel's start (gp.md §5.3).
        let mut data = TrainData::new(&inputs.apply(x), &target.apply_vector(y));
        if let Some(w) = self.noise_weights() {
            if w.len() != y.len() {
                return Err(GpError::InvalidParams(format!(
                    "{} noise weights for {} training samples",
                    w.len(),
                    y.len()
                )));
            }
            data.noise_weights = Some(w.clone());
        }
        let objective = GpObjective::standardised(self, data)?;
        // Maximise the marginal likelihood p(y | X, X̄, Θ) (eq. 3.30) jointly in Θ, the
        // pseudo-inputs X̄ and, for SPGP-HET, the pseudo-input noise h (eq. 3.34).
        let (grad_tol, rel_tol) = self.tolerances();
        let options = LbfgsOptions {
            max_iters: self.max_iters(),
            max_evals: self.max_evals(),
            memory: LBFGS_MEMORY,
            grad_tol,
            rel_tol,
        };
        let outcome = minimize(
            |t| objective.value_and_gradient(t),
            objective.start(),
            options,
        )?;
        let hyper = objective.layout.unpack(&outcome.x);
        // Condition on the data for predictions (eqs. 3.32-3.33).
        let data = &objective.data;
        let (posterior, used_jitter) = condition(data, kind, &hyper, self.jitter())?;
        let report = FitReport {
            n: data.len(),
            d: data.dims(),
            m: objective.layout.pseudo,
            evals: outcome.evals,
            iterations: outcome.iterations,
            seconds: clock.elapsed().as_secs_f64(),
            // NLML of the standardised targets plus N·log(scale): the NLML in target units.
            nlml: outcome.f + data.len() as f64 * target.scale[0].ln(),
            stop: format!("{:?}", outcome.stop),
        };
        Ok(GpModel {
            kind,
            input_names: input_names.to_vec(),
            target_name: target_name.to_string(),
            inputs,
            target,
            hyper,
            jitter: used_jitter,
            posterior,
            report,
        })
    }
}

#[cfg(test)]
#[path = "fit_tests.rs"]
mod tests;
