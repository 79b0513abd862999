//! The exact GP (thesis eqs. 3.13, 3.18, 3.20-3.21) with an SE-ARD kernel: O(N³) Cholesky of
//! C = K + σ²I, the NLML and its gradient through the adjoint G = ½(C⁻¹ − ααᵀ). Used for small
//! problems and as the reference the sparse models must reproduce.

use nalgebra::{DMatrix, DVector};

use super::blocked::{lower_gram, lower_solve};
use super::fitc::Evaluation;
use super::hyper::{Hyper, HyperGrad};
use super::kernel::{Kernel, OwnedPoints, self_covariance};
use super::linalg::{cholesky_with_jitter, colsum_product, log_diag_sum, lower_inverse};
use super::train_data::TrainData;
use crate::{GpError, Result};

/// The largest training set the exact GP accepts (its cost is O(N³) time and O(N²) memory).
pub const FULL_GP_MAX_SAMPLES: usize = 4000;

/// K (noise-free, exact diagonal) and the lower factor of K + σ²I with the jitter used.
fn factor<K: Kernel>(
    data: &TrainData,
    h: &Hyper<K>,
    jitter: f64,
) -> Result<(DMatrix<f64>, DMatrix<f64>, f64)> {
    if data.len() > FULL_GP_MAX_SAMPLES {
        return Err(GpError::InvalidParams(format!(
            "the full GP takes at most {FULL_GP_MAX_SAMPLES} samples, got {}; use SPGP",
            data.len()
        )));
    }
    let k = self_covariance(&h.kernel, data.points());
    let mut c = k.clone();
    for i in 0..c.nrows() {
        c[(i, i)] += h.noise_variance;
    }
    let chol = cholesky_with_jitter(&c, jitter, "training covariance K + σ²I")?;
    Ok((k, chol.l, chol.jitter))
}

/// 𝓛 = ½yᵀC⁻¹y + ½log|C| + (N/2)log 2π (eq. 3.18 negated) and its gradient.
pub(crate) fn objective<K: Kernel>(
    data: &TrainData,
    h: &Hyper<K>,
    jitter: f64,
) -> Result<Evaluation> {
    let (k, l, _) = factor(data, h, jitter)?;
    let l_inv = lower_inverse(&l, "chol(K + σ²I)")?;
    let c_inv = lower_gram(&l_inv); // C⁻¹ = L⁻ᵀL⁻¹
    let alpha = &c_inv * &data.y;
    let n = data.len() as f64;
    let nlml =
        0.5 * data.y.dot(&alpha) + log_diag_sum(&l) + 0.5 * n * (2.0 * std::f64::consts::PI).ln();
    let g = (c_inv - &alpha * alpha.transpose()) * 0.5; // ∂𝓛/∂C
    let x = data.points();
    let trace = g.trace();
    let grad = HyperGrad {
        kernel: h.kernel.cross_gradient(x, x, &k, &g, None),
        log_noise_variance: h.noise_variance * trace,
        pseudo_inputs: DMatrix::zeros(0, data.dims()),
        log_pseudo_noise: None,
    };
    Ok(Evaluation {
        nlml,
        grad,
        d_jitter: trace,
    })
}

/// What the exact GP keeps for prediction: the training inputs, C⁻¹y and chol(C).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct FullPosterior {
    /// Standardised training inputs (N×D).
    pub x: DMatrix<f64>,
    /// Standardised training targets (N), kept so model files can rebuild the posterior.
    pub y: DVector<f64>,
    /// α = C⁻¹y.
    pub alpha: DVector<f64>,
    /// Lower Cholesky factor of C.
    pub l: DMatrix<f64>,
}

impl FullPosterior {
    /// Conditions the GP at `h` on `data`; returns the posterior and the jitter used.
    pub fn new<K: Kernel>(data: &TrainData, h: &Hyper<K>, jitter: f64) -> Result<(Self, f64)> {
        let (_, l, used) = factor(data, h, jitter)?;
        let l_inv = lower_inverse(&l, "chol(K + σ²I)")?;
        let alpha = l_inv.tr_mul(&(&l_inv * &data.y));
        Ok((
            Self {
                x: data.x_rows(),
                y: data.y.clone(),
                alpha,
                l,
            },
            used,
        ))
    }

    /// Mean (eq. 3.20) and latent variance (eq. 3.21) at the rows of `x_test` (standardised).
    pub fn predict<K: Kernel>(
        &self,
        h: &Hyper<K>,
        x_test: &DMatrix<f64>,
    ) -> Result<(DVector<f64>, DVector<f64>)> {
        let train = OwnedPoints::of_rows_kept(&self.x, &h.kernel);
        let test = OwnedPoints::of_rows(x_test, &h.kernel);
        let k_star = h.kernel.cross(train.points(), test.points());
        let mean = k_star.tr_mul(&self.alpha);
        let v = lower_solve(&self.l, &k_star);
        if !v.iter().all(|x| x.is_finite()) {
            return Err(GpError::Numerical("chol(K + σ²I) has a zero pivot".into()));
        }
        let prior = h.kernel.diag(test.points());
        let var = DVector::from_iterator(
            prior.len(),
            colsum_product(&v, &v)
                .iter()
                .zip(prior.iter())
                .map(|(q, k)| (k - q).max(0.0)),
        );
        Ok((mean, var))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fitc;
    use crate::hyper::Layout;
    use crate::sparse_posterior::SparsePosterior;
    use crate::stationary::Stationary;

    fn problem() -> (TrainData, Hyper<Stationary>) {
        let x = DMatrix::from_fn(15, 2, |n, d| ((n * (3 + d) + d) % 11) as f64 / 5.0 - 1.0);
        let y = DVector::from_fn(15, |n, _| (2.0 * x[(n, 0)]).sin() - 0.4 * x[(n, 1)]);
        let h = Hyper {
            kernel: Stationary::se(&[0.8, 1.4], 1.1),
            noise_variance: 0.05,
            pseudo_inputs: x.clone(),
            pseudo_noise: None,
        };
        (TrainData::new(&x, &y), h)
    }

    #[test]
    fn the_full_gp_gradient_matches_central_differences() {
        let (data, mut h) = problem();
        h.pseudo_inputs = DMatrix::zeros(0, 2);
        let layout = Layout {
            kernel: h.kernel.clone(),
            dims: 2,
            pseudo: 0,
            het: false,
            noise_floor: 0.0,
            fixed_pseudo_inputs: None,
        };
        let theta = layout.pack(&h);
        let e = objective(&data, &h, 0.0).expect("factors");
        let analytic = layout.pack_grad(&h, &e.grad);
        for i in 0..theta.len() {
            let (mut up, mut down) = (theta.clone(), theta.clone());
            up[i] += 1e-5;
            down[i] -= 1e-5;
            let fu = objective(&data, &layout.unpack(&up), 0.0)
                .expect("factors")
                .nlml;
            let fd = objective(&data, &layout.unpack(&down), 0.0)
                .expect("factors")
                .nlml;
            let numeric = (fu - fd) / 2e-5;
            // Relative tolerance 1e-6 on max(|gradient|, 1).
            assert!(
                (numeric - analytic[i]).abs() < 1e-6 * analytic[i].abs().max(1.0),
                "param {i}"
            );
        }
    }

    #[test]
    fn spgp_with_pseudo_inputs_at_the_training_inputs_matches_the_full_gp() {
        let (data, h) = problem();
        let full = objective(&data, &h, 0.0).expect("factors").nlml;
        let sparse = fitc::objective(&data, &h, 1e-10).expect("factors").nlml;
        assert!(
            (full - sparse).abs() < 1e-6 * full.abs(),
            "{full} vs {sparse}"
        );
        let test = DMatrix::from_row_slice(3, 2, &[0.1, 0.2, -0.7, 0.9, 1.5, -1.5]);
        let (fp, _) = FullPosterior::new(&data, &h, 0.0).expect("factors");
        let (sp, _) = SparsePosterior::new(&data, &h, 1e-10).expect("factors");
        let (fm, fv) = fp.predict(&h, &test).expect("predicts");
        let (sm, sv) = sp.predict(&h, &test);
        assert!((fm - sm).amax() < 1e-6, "means differ");
        assert!((fv - sv).amax() < 1e-6, "variances differ");
    }
}
