//! The kernel abstraction end to end: every kernel's NLML gradient (full GP, SPGP, SPGP-HET)
//! against central differences, including a non-stationary kernel that reads per-point data the
//! way DGPOM's motion-adapted kernel will.

use nalgebra::{DMatrix, DVector};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::*;
use crate::hyper::{Hyper, Layout};
use crate::params::GpKind;
use crate::shape::Shape;
use crate::stationary::Stationary;
use crate::train_data::TrainData;
use crate::{GpError, GpParams, fitc, full};

/// k(x, x') = s · w(x) w(x') · exp(−‖x − x'‖²/2ℓ²) with w(x) = exp(0.3 x₀) derived per point:
/// non-stationary, with a diagonal that varies, and data that is not a coordinate.
#[derive(Debug, Clone, PartialEq)]
struct Amplitude {
    lengthscale: f64,
    signal_variance: f64,
}

impl Amplitude {
    fn weights(p: Points<'_>) -> DVector<f64> {
        let extra = p.extra().expect("point data attached");
        DVector::from_iterator(p.len(), extra.row(0).iter().copied())
    }
}

impl Kernel for Amplitude {
    fn n_params(&self) -> usize {
        2
    }
    fn params(&self) -> Vec<f64> {
        vec![self.lengthscale.ln(), self.signal_variance.ln()]
    }
    fn set_params(&mut self, theta: &[f64]) {
        self.lengthscale = theta[0].exp();
        self.signal_variance = theta[1].exp();
    }
    fn initialise(&mut self, _xt: &DMatrix<f64>, target_variance: f64) -> crate::Result<()> {
        self.lengthscale = 1.0;
        self.signal_variance = target_variance.max(0.01);
        Ok(())
    }
    fn signal_variance(&self) -> f64 {
        self.signal_variance
    }
    fn log_signal_variance_index(&self) -> usize {
        1
    }
    fn cross(&self, a: Points<'_>, b: Points<'_>) -> DMatrix<f64> {
        let (wa, wb) = (Self::weights(a), Self::weights(b));
        let (ac, bc) = (a.coords(), b.coords());
        DMatrix::from_fn(a.len(), b.len(), |i, j| {
            let r2 = (ac.column(i) - bc.column(j)).norm_squared() / self.lengthscale.powi(2);
            self.signal_variance * wa[i] * wb[j] * (-0.5 * r2).exp()
        })
    }
    fn diag(&self, a: Points<'_>) -> DVector<f64> {
        Self::weights(a).map(|w| self.signal_variance * w * w)
    }
    fn cross_gradient(
        &self,
        a: Points<'_>,
        b: Points<'_>,
        k: &DMatrix<f64>,
        adjoint: &DMatrix<f64>,
        _d_a: Option<&mut DMatrix<f64>>,
    ) -> DVector<f64> {
        let (ac, bc) = (a.coords(), b.coords());
        let mut g = DVector::zeros(2);
        for i in 0..a.len() {
            for j in 0..b.len() {
                let r2 = (ac.column(i) - bc.column(j)).norm_squared() / self.lengthscale.powi(2);
                g[0] += adjoint[(i, j)] * k[(i, j)] * r2;
                g[1] += adjoint[(i, j)] * k[(i, j)];
            }
        }
        g
    }
    fn diag_gradient(&self, a: Points<'_>, adjoint: &DVector<f64>) -> DVector<f64> {
        DVector::from_vec(vec![0.0, self.diag(a).dot(adjoint)])
    }
    fn point_data(&self, xt: &DMatrix<f64>) -> Option<DMatrix<f64>> {
        Some(DMatrix::from_fn(1, xt.ncols(), |_, j| {
            (0.3 * xt[(0, j)]).exp()
        }))
    }
}

fn amplitude() -> Amplitude {
    Amplitude {
        lengthscale: 0.8,
        signal_variance: 1.3,
    }
}

/// Kernel values for the tests: Matérn 3/2, a space-time product and the amplitude kernel.
fn matern() -> Stationary {
    Stationary::with_values(
        Stationary::matern32_ard().factors().to_vec(),
        DVector::from_vec(vec![0.9, 1.4, 0.7]),
        1.2,
    )
    .expect("valid")
}

fn space_time() -> Stationary {
    Stationary::with_values(
        Stationary::space_time(2, Shape::SquaredExponential, Shape::Matern32)
            .factors()
            .to_vec(),
        DVector::from_vec(vec![0.9, 1.4, 0.6]),
        1.1,
    )
    .expect("valid")
}

/// N samples in 3-D, M pseudo-inputs, the given kernel; Z held fixed when `fixed`.
fn problem<K: Kernel>(kind: GpKind, kernel: K, fixed: bool) -> (TrainData, Hyper<K>, Layout<K>) {
    let (n, m) = (40, 6);
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    let x: DMatrix<f64> = DMatrix::from_fn(n, 3, |_, _| rng.random_range(-2.0..2.0));
    let y = DVector::from_fn(n, |i, _| {
        x[(i, 0)].sin() + 0.4 * x[(i, 2)] + rng.random_range(-0.2..0.2)
    });
    let data = TrainData::new(&x, &y).with_point_data(&kernel);
    let sparse = kind != GpKind::Full;
    let z = if sparse {
        DMatrix::from_fn(m, 3, |_, _| rng.random_range(-2.0..2.0))
    } else {
        DMatrix::zeros(0, 3)
    };
    let h = Hyper {
        kernel: kernel.clone(),
        noise_variance: 0.06,
        pseudo_noise: (kind == GpKind::SpgpHet)
            .then(|| DVector::from_fn(z.nrows(), |_, _| rng.random_range(0.01..0.3))),
        pseudo_inputs: z.clone(),
    };
    let layout = Layout {
        kernel,
        dims: 3,
        pseudo: z.nrows(),
        het: kind == GpKind::SpgpHet,
        noise_floor: 0.0,
        fixed_pseudo_inputs: (fixed && sparse).then_some(z),
    };
    (data, h, layout)
}

fn nlml<K: Kernel>(kind: GpKind, data: &TrainData, h: &Hyper<K>) -> f64 {
    match kind {
        GpKind::Full => full::objective(data, h, 1e-8),
        _ => fitc::objective(data, h, 1e-8),
    }
    .expect("factors")
    .nlml
}

/// Central differences of 𝓛 over the whole packed vector against the analytic gradient.
fn check<K: Kernel>(name: &str, kind: GpKind, kernel: K, fixed: bool) {
    let (data, h, layout) = problem(kind, kernel, fixed);
    let e = match kind {
        GpKind::Full => full::objective(&data, &h, 1e-8),
        _ => fitc::objective(&data, &h, 1e-8),
    }
    .expect("factors");
    let analytic = layout.pack_grad(&h, &e.grad);
    let theta = layout.pack(&h);
    let step = 1e-5;
    for i in 0..theta.len() {
        let at = |d: f64| {
            let mut t = theta.clone();
            t[i] += d;
            nlml(kind, &data, &layout.unpack(&t))
        };
        let fd = (at(step) - at(-step)) / (2.0 * step);
        // Relative tolerance 1e-6 on max(|gradient|, 1) (central differences, h = 1e-5).
        assert!(
            (fd - analytic[i]).abs() < 1e-6 * analytic[i].abs().max(1.0),
            "{name} {kind} param {i}: fd {fd} vs analytic {}",
            analytic[i]
        );
    }
}

#[test]
fn matern_and_space_time_gradients_match_central_differences_for_every_gp() {
    for kind in [GpKind::Full, GpKind::Spgp, GpKind::SpgpHet] {
        check("matern32", kind, matern(), false);
        check("space-time", kind, space_time(), false);
    }
}

#[test]
fn a_kernel_with_per_point_data_has_exact_gradients_with_fixed_pseudo_inputs() {
    for kind in [GpKind::Full, GpKind::Spgp, GpKind::SpgpHet] {
        check("amplitude", kind, amplitude(), true);
    }
}

#[test]
fn a_kernel_with_per_point_data_fits_with_fixed_pseudo_inputs_and_refuses_moving_ones() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let x: DMatrix<f64> = DMatrix::from_fn(50, 2, |_, _| rng.random_range(-2.0..2.0));
    let y = DVector::from_fn(50, |i, _| (0.3 * x[(i, 0)]).exp() * x[(i, 1)].sin());
    let params = GpParams::new(GpKind::Spgp)
        .pseudo_inputs(8)
        .max_iters(30)
        .kernel(amplitude());
    let err = params.fit(&x, &y).expect_err("moving pseudo-inputs");
    assert!(matches!(err, GpError::InvalidParams(_)), "{err}");
    let model = params
        .optimise_pseudo_inputs(false)
        .fit(&x, &y)
        .expect("fits");
    let p = model.predict(&x.rows(0, 5).into_owned()).expect("predicts");
    assert!(p.mean.iter().chain(p.var_y.iter()).all(|v| v.is_finite()));
    assert!((p.mean - y.rows(0, 5)).amax() < 0.5);
}

#[test]
fn a_space_time_gp_learns_a_temporal_length_scale_of_its_own() {
    // y varies fast in x and slowly in t; the fitted temporal length-scale must come out longer.
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let x: DMatrix<f64> = DMatrix::from_fn(80, 3, |_, _| rng.random_range(-2.0..2.0));
    let y = DVector::from_fn(80, |i, _| (2.5 * x[(i, 0)]).sin() + 0.3 * x[(i, 2)]);
    let kernel = Stationary::space_time(2, Shape::Matern32, Shape::SquaredExponential);
    let model = GpParams::new(GpKind::Full)
        .max_iters(80)
        .kernel(kernel)
        .fit(&x, &y)
        .expect("fits");
    let ls = model.kernel().lengthscales();
    assert!(ls[2] > 2.0 * ls[0], "length-scales {ls}");
}
