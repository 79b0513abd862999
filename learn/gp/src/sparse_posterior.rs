//! SPGP / SPGP-HET predictions (thesis eqs. 3.32-3.33, gp.md §3): the cached weights
//! w = A⁻¹UΓ⁻¹y and the matrix W = B_u⁻¹ − A⁻¹ give, for test covariances k_*,
//! mean k_*ᵀw and latent variance k(x_*, x_*) − k_*ᵀWk_*.
//!
//! For SPGP-HET, B_u = K_M + diag(h) + εI, so the latent variance contains the input-dependent
//! term s − k_*ᵀB_u⁻¹k_*, which grows near pseudo-inputs with a large h_m: that is the learned
//! local noise. The variance with noise adds the global σ² on top (gp.md §3, "HET specifics").

use nalgebra::{DMatrix, DVector};

use super::fitc::factor;
use super::hyper::Hyper;
use super::kernel::{Kernel, OwnedPoints, self_covariance};
use super::linalg::{cholesky_with_jitter, colsum_product, mul, t_view};
use super::train_data::TrainData;
use crate::Result;

/// Largest asymmetry of a stored W, relative to its largest entry (a fit symmetrises W exactly).
const SYMMETRY_TOLERANCE: f64 = 1e-9;
/// How far outside [0, 1] the eigenvalues of LᵀWL may stray through rounding: at most this
/// fraction of the signal variance could go missing from a predictive variance.
const EIGEN_TOLERANCE: f64 = 1e-3;

/// What a sparse model keeps from its training data for prediction.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SparsePosterior {
    /// w = L⁻ᵀL_B⁻ᵀc (M).
    pub weights: DVector<f64>,
    /// W = B_u⁻¹ − A⁻¹ = L⁻ᵀ(I − B⁻¹)L⁻¹ (M×M).
    pub var_matrix: DMatrix<f64>,
}

impl SparsePosterior {
    /// Conditions the model at `h` on `data`; returns the posterior and the jitter used.
    pub fn new<K: Kernel>(data: &TrainData, h: &Hyper<K>, jitter: f64) -> Result<(Self, f64)> {
        let f = factor(data, h, jitter)?;
        let m = f.u.len();
        let weights = f.l_inv.tr_mul(&f.u);
        let middle = DMatrix::identity(m, m) - &f.b_inv;
        let var = mul(&mul(&t_view(&f.l_inv), &middle), &f.l_inv);
        let var_matrix = (&var + var.transpose()) * 0.5;
        Ok((
            Self {
                weights,
                var_matrix,
            },
            f.jitter,
        ))
    }

    /// Checks a posterior read from a file against its hyperparameters: W must be symmetric and
    /// lie between 0 and B_u⁻¹ = (K_M + diag(h) + εI)⁻¹, as every fit's does (W = B_u⁻¹ − A⁻¹ with
    /// A ⪰ B_u). Above B_u⁻¹ some input gets a negative latent variance k_** − k_*ᵀWk_*; below 0
    /// (a negative-definite W) the variance exceeds the prior's. Checked through the eigenvalues
    /// of LᵀWL (L = chol(B_u)), which lie in [0, 1) for a fitted model: two Cholesky factorings.
    pub fn check<K: Kernel>(&self, h: &Hyper<K>, jitter: f64) -> std::result::Result<(), String> {
        let w = &self.var_matrix;
        let scale = w
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()))
            .max(f64::MIN_POSITIVE);
        let asymmetry = w
            .iter()
            .zip(w.transpose().iter())
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        if asymmetry > SYMMETRY_TOLERANCE * scale {
            return Err(format!(
                "posterior var_matrix is not symmetric (entries differ from their mirror by up to \
                 {asymmetry:e}, of entries up to {scale:e})"
            ));
        }
        let z = OwnedPoints::of_rows_kept(&h.pseudo_inputs, &h.kernel);
        let mut b_u = self_covariance(&h.kernel, z.points());
        if let Some(p) = &h.pseudo_noise {
            for (i, hi) in p.iter().enumerate() {
                b_u[(i, i)] += hi;
            }
        }
        // As the fit factored it (the jitter it used, more only if rounding needs it). Every
        // M × M temporary is dropped as soon as it is used: at M = 4000 each is 128 MB.
        let what = "the pseudo-inputs' covariance K_M + diag(h)";
        let l = cholesky_with_jitter(&b_u, jitter, what)
            .map_err(|e| e.to_string())?
            .l;
        drop(b_u);
        let wl = w * &l;
        let mut c = l.tr_mul(&wl);
        drop((l, wl));
        let m = c.nrows();
        for i in 0..m {
            for j in 0..i {
                let mean = 0.5 * (c[(i, j)] + c[(j, i)]);
                c[(i, j)] = mean;
                c[(j, i)] = mean;
            }
        }
        let mut shifted = c.clone();
        for i in 0..m {
            shifted[(i, i)] += EIGEN_TOLERANCE;
        }
        if shifted.cholesky().is_none() {
            return Err(
                "posterior var_matrix is not positive semi-definite (a fit's never is): the \
                 predictive variance would exceed the prior's"
                    .into(),
            );
        }
        // (1 + tol) I − C, in place.
        c.neg_mut();
        for i in 0..m {
            c[(i, i)] += 1.0 + EIGEN_TOLERANCE;
        }
        if c.cholesky().is_none() {
            return Err(
                "posterior var_matrix is larger than the pseudo-inputs' inverse covariance allows \
                 (a fit's never is): some inputs would get a negative predictive variance"
                    .into(),
            );
        }
        Ok(())
    }

    /// Mean and latent variance at the rows of `x` (T×D, standardised).
    pub fn predict<K: Kernel>(
        &self,
        h: &Hyper<K>,
        x: &DMatrix<f64>,
    ) -> (DVector<f64>, DVector<f64>) {
        let z = OwnedPoints::of_rows_kept(&h.pseudo_inputs, &h.kernel);
        let test = OwnedPoints::of_rows(x, &h.kernel);
        let k_star = h.kernel.cross(z.points(), test.points());
        let mean = k_star.tr_mul(&self.weights);
        let wk = mul(&self.var_matrix, &k_star);
        let quad = colsum_product(&k_star, &wk);
        let prior = h.kernel.diag(test.points());
        let var = DVector::from_iterator(
            prior.len(),
            quad.iter().zip(prior.iter()).map(|(q, k)| (k - q).max(0.0)),
        );
        (mean, var)
    }
}
