//! The fit's objective as a public value: the NLML and its gradient over the flat parameter vector
//! (log ℓ, log s, log(σ² − floor), Z unless held fixed, log h), at the seeded starting point or
//! any other. The fit
//! minimises exactly this; benches and diagnostics can call it directly.

use nalgebra::{DMatrix, DVector};

use super::fitc;
use super::full;
use super::hyper::{Hyper, Layout};
use super::init::initial_hyper;
use super::kernel::Kernel;
use super::params::{GpKind, GpValidParams, MAX_PSEUDO_INPUTS};
use super::stationary::Stationary;
use super::train_data::TrainData;
use super::transform::Standardiser;
use crate::{GpError, Result};

/// The negative log marginal likelihood of a GP on standardised data, as a function of θ.
#[derive(Debug, Clone)]
pub struct GpObjective<K = Stationary> {
    pub(crate) data: TrainData,
    pub(crate) kind: GpKind,
    pub(crate) layout: Layout<K>,
    pub(crate) jitter: f64,
    pub(crate) start: Hyper<K>,
}

impl<K: Kernel> GpObjective<K> {
    /// Standardises `x` (N×D) and `y` like a fit and sets up the seeded starting point.
    pub fn new(params: &GpValidParams<K>, x: &DMatrix<f64>, y: &DVector<f64>) -> Result<Self> {
        let inputs = Standardiser::for_kernel(x, params.kernel());
        let target = Standardiser::of_vector(y);
        Self::standardised(
            params,
            TrainData::new(&inputs.apply(x), &target.apply_vector(y)),
        )
    }

    /// The objective on already standardised data.
    pub(crate) fn standardised(params: &GpValidParams<K>, data: TrainData) -> Result<Self> {
        let kind = params.kind();
        let data = data.with_point_data(params.kernel());
        // Seeded initialisation: random-subset pseudo-inputs, the kernel's start (gp.md §5.3);
        // or a fitted model's values (a warm start).
        let seeded = initial_hyper(
            &data,
            kind,
            params.pseudo_inputs(),
            params.seed(),
            params.kernel().clone(),
            params.start_pseudo_inputs(),
        )?;
        let start = match params.start_hyper_values() {
            Some(h) => warm_start(h, &seeded)?,
            None => seeded,
        };
        if let Some(z) = params.start_pseudo_inputs()
            && z.ncols() != data.dims()
        {
            return Err(GpError::InvalidParams(format!(
                "starting pseudo-inputs have {} columns, the inputs {}",
                z.ncols(),
                data.dims()
            )));
        }
        let m = start.pseudo_inputs.nrows();
        if kind != GpKind::Full && m > MAX_PSEUDO_INPUTS {
            return Err(GpError::InvalidParams(format!(
                "{m} pseudo-inputs; a sparse GP takes at most {MAX_PSEUDO_INPUTS} (its M × M \
                 posterior is then as large as a full GP's)"
            )));
        }
        let moving = params.optimise_pseudo_inputs() && kind != GpKind::Full;
        if moving && data.extra.is_some() {
            return Err(GpError::InvalidParams(
                "a kernel with per-point data needs fixed pseudo-inputs \
                 (GpParams::optimise_pseudo_inputs(false))"
                    .into(),
            ));
        }
        let layout = Layout {
            kernel: start.kernel.clone(),
            dims: data.dims(),
            pseudo: start.pseudo_inputs.nrows(),
            het: kind == GpKind::SpgpHet,
            noise_floor: params.noise_floor(),
            fixed_pseudo_inputs: (!params.optimise_pseudo_inputs())
                .then(|| start.pseudo_inputs.clone()),
        };
        Ok(Self {
            data,
            kind,
            layout,
            jitter: params.jitter(),
            start,
        })
    }

    /// Length of θ.
    pub fn dims(&self) -> usize {
        self.layout.len()
    }

    /// The starting point θ₀.
    pub fn start(&self) -> DVector<f64> {
        self.layout.pack(&self.start)
    }

    /// 𝓛(θ) and ∂𝓛/∂θ (gp.md §1-2; the full GP: thesis eq. 3.18). Errors if a factorisation fails.
    pub fn value_and_gradient(&self, theta: &DVector<f64>) -> Result<(f64, DVector<f64>)> {
        let h = self.layout.unpack(theta);
        let eps = self.jitter * h.kernel.signal_variance();
        let e = match self.kind {
            GpKind::Full => full::objective(&self.data, &h, eps)?,
            GpKind::Spgp | GpKind::SpgpHet => fitc::objective(&self.data, &h, eps)?,
        };
        let mut grad = self.layout.pack_grad(&h, &e.grad);
        // ε = jitter·s, so ∂ε/∂log s = ε (gp.md §2.3)
        grad[h.kernel.log_signal_variance_index()] += eps * e.d_jitter;
        Ok((e.nlml, grad))
    }
}

/// A warm start's hyperparameters, checked against the seeded start's shape (the kernel's
/// parameter count and the pseudo-inputs' columns, both set by the data's input dimension).
fn warm_start<K: Kernel>(h: &Hyper<K>, seeded: &Hyper<K>) -> Result<Hyper<K>> {
    let (want, got) = (seeded.pseudo_inputs.ncols(), h.pseudo_inputs.ncols());
    if h.kernel.n_params() != seeded.kernel.n_params()
        || (h.pseudo_inputs.nrows() > 0 && got != want)
    {
        return Err(GpError::InvalidParams(format!(
            "the warm start's model has {} kernel parameters and {got}-dimensional pseudo-inputs, \
             the data need {} and {want}",
            h.kernel.n_params(),
            seeded.kernel.n_params()
        )));
    }
    Ok(h.clone())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::GpParams;

    #[test]
    fn the_relative_jitter_term_makes_the_signal_gradient_exact() {
        let x = DMatrix::from_fn(30, 2, |i, d| ((i * (d + 2)) % 7) as f64 - 3.0);
        let y = DVector::from_fn(30, |i, _| (i as f64 * 0.3).sin());
        let params = GpParams::new(GpKind::Spgp)
            .pseudo_inputs(4)
            .jitter(1e-3)
            .check()
            .expect("valid");
        let obj = GpObjective::new(&params, &x, &y).expect("sets up");
        let theta = obj.start();
        let (_, g) = obj.value_and_gradient(&theta).expect("evaluates");
        let i = obj.layout.dims; // log s
        let (mut up, mut down) = (theta.clone(), theta.clone());
        up[i] += 1e-5;
        down[i] -= 1e-5;
        let fd = (obj.value_and_gradient(&up).expect("ok").0
            - obj.value_and_gradient(&down).expect("ok").0)
            / 2e-5;
        assert!(
            (fd - g[i]).abs() < 1e-6 * g[i].abs().max(1.0),
            "fd {fd} vs {}",
            g[i]
        );
    }

    /// y = sin(x0) + 0.3·x1 on 60 points, x in [-3, 3]².
    fn plane_sine() -> (DMatrix<f64>, DVector<f64>) {
        let x = DMatrix::from_fn(60, 2, |i, d| ((i * (d + 3) * 7) % 61) as f64 / 10.0 - 3.0);
        let y = DVector::from_fn(60, |i, _| x[(i, 0)].sin() + 0.3 * x[(i, 1)]);
        (x, y)
    }

    #[test]
    fn a_warm_started_fit_starts_from_the_given_models_hyperparameters() {
        let (x, y) = plane_sine();
        for kind in [GpKind::Spgp, GpKind::SpgpHet, GpKind::Full] {
            let first = GpParams::new(kind)
                .pseudo_inputs(6)
                .max_iters(30)
                .fit(&x, &y)
                .expect("fits");
            let params = GpParams::new(kind)
                .pseudo_inputs(6)
                .seed(99)
                .start_from(&first)
                .check()
                .expect("valid");
            let obj = GpObjective::new(&params, &x, &y).expect("sets up");
            let want = obj.layout.pack(&first.hyper);
            assert_eq!(obj.start(), want, "{kind}: the start is the model's vector");
            // No iterations: the fit ends where it started, at the model's values (within the
            // round trip through the log and logit coordinates).
            let refit = GpParams::new(kind)
                .pseudo_inputs(6)
                .max_iters(0)
                .start_from(&first)
                .fit(&x, &y)
                .expect("refits");
            let got = obj.layout.pack(&refit.hyper);
            let gap = (&got - &want).amax();
            assert!(gap < 1e-9, "{kind}: moved {gap} in no iterations");
            assert!((refit.fit_report().nlml - first.fit_report().nlml).abs() < 1e-6);
        }
    }

    #[test]
    fn a_warm_start_from_a_fitted_model_needs_fewer_iterations_than_the_seeded_start() {
        let (x, y) = plane_sine();
        let params = || {
            GpParams::new(GpKind::SpgpHet)
                .pseudo_inputs(6)
                .max_iters(300)
        };
        let cold = params().fit(&x, &y).expect("fits");
        let warm = params().start_from(&cold).fit(&x, &y).expect("refits");
        assert!(
            warm.fit_report().iterations * 4 < cold.fit_report().iterations.max(4),
            "warm {} against cold {} iterations",
            warm.fit_report().iterations,
            cold.fit_report().iterations
        );
        assert!(warm.fit_report().nlml <= cold.fit_report().nlml + 1e-9);
    }

    #[test]
    fn a_warm_start_from_another_kind_or_input_dimension_is_an_error() {
        let (x, y) = plane_sine();
        let spgp = GpParams::new(GpKind::Spgp)
            .pseudo_inputs(6)
            .max_iters(5)
            .fit(&x, &y)
            .expect("fits");
        for kind in [GpKind::SpgpHet, GpKind::Full] {
            assert!(
                GpParams::new(kind).start_from(&spgp).check().is_err(),
                "{kind}"
            );
        }
        let wider = DMatrix::from_fn(60, 3, |i, d| x[(i, d.min(1))] + d as f64 * 0.1);
        let err = GpParams::new(GpKind::Spgp)
            .pseudo_inputs(6)
            .start_from(&spgp)
            .fit(&wider, &y)
            .expect_err("three inputs against a two-input model");
        assert!(err.to_string().contains("warm start"), "{err}");
    }
}
