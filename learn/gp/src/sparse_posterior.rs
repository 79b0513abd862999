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
use super::kernel::{Kernel, OwnedPoints};
use super::linalg::{colsum_product, mul, t_view};
use super::train_data::TrainData;
use crate::Result;

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
