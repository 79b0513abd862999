//! Leave-one-out predictive moments in closed form (GPML eq. 5.12): for a GP whose training
//! covariance is C (noise included), the prediction of y_i from the other N − 1 targets has mean
//! y_i − [C⁻¹y]_i / [C⁻¹]_ii and variance 1 / [C⁻¹]_ii, with the hyperparameters held fixed; less
//! the noise σ², the latent variance of f_i (GPML's `infLOO`).
//!
//! SPGP and SPGP-HET are exact GPs with the prior covariance C = Q + Γ (gp.md §0), so the same
//! identity gives their exact leave-one-out moments from the O(NM²) factorisation: C⁻¹y = α and
//! [C⁻¹]_nn = (1 − ‖W1_{:,n}‖²)/g_n (gp.md §2.2).

use nalgebra::DVector;
use rayon::prelude::*;

use super::fitc::{Factors, Pass1, factor};
use super::full::FullPosterior;
use super::hyper::Hyper;
use super::kernel::Kernel;
use super::linalg::{colsum_product, lower_inverse, mul};
use super::params::GpKind;
use super::train_data::TrainData;
use crate::Result;

/// Leave-one-out predictive moments, one per training sample: what the model conditioned on the
/// other N − 1 samples (same hyperparameters) predicts at the sample's input.
#[derive(Debug, Clone, PartialEq)]
pub struct LooMoments {
    /// Predictive mean of y_i (and f_i).
    pub mean: DVector<f64>,
    /// Latent variance of f_i (for SPGP-HET including the local noise learned through h).
    pub var_latent: DVector<f64>,
    /// Variance of y_i: the latent variance plus the noise σ².
    pub var_y: DVector<f64>,
}

/// The moments from C⁻¹y and diag(C⁻¹) (GPML eq. 5.12), with noise variance `noise`.
fn from_inverse(
    y: &DVector<f64>,
    c_inv_y: &DVector<f64>,
    c_inv_diag: &DVector<f64>,
    noise: f64,
) -> LooMoments {
    let var_y = c_inv_diag.map(|d| 1.0 / d);
    LooMoments {
        mean: DVector::from_fn(y.len(), |i, _| y[i] - c_inv_y[i] / c_inv_diag[i]),
        var_latent: var_y.map(|v| (v - noise).max(0.0)),
        var_y,
    }
}

/// C⁻¹y and diag(C⁻¹) of one row block of a sparse model.
fn sparse_block(
    data: &TrainData,
    f: &Factors,
    p: &Pass1,
    (start, len): (usize, usize),
) -> (DVector<f64>, DVector<f64>) {
    let w1_sq = colsum_product(&p.vt, &mul(&f.b_inv, &p.vt)); // ‖L_B⁻¹Ṽ_{:,n}‖²
    let vtu = p.vt.tr_mul(&f.u); // Ṽᵀu = Γ^{-1/2}Vᵀu
    let y = data.y.rows(start, len);
    let alpha = DVector::from_fn(len, |n, _| (y[n] - p.g[n].sqrt() * vtu[n]) / p.g[n]);
    let diag = DVector::from_fn(len, |n, _| (1.0 - w1_sq[n]) / p.g[n]);
    (alpha, diag)
}

/// Leave-one-out moments of the model `kind` at `h` on standardised `data`, with the absolute
/// jitter `jitter` (the one the posterior was conditioned with).
pub(crate) fn loo_moments<K: Kernel>(
    data: &TrainData,
    kind: GpKind,
    h: &Hyper<K>,
    jitter: f64,
) -> Result<LooMoments> {
    let (c_inv_y, c_inv_diag) = match kind {
        GpKind::Full => {
            let (post, _) = FullPosterior::new(data, h, jitter)?;
            let l_inv = lower_inverse(&post.l, "chol(K + σ²I)")?;
            (post.alpha, colsum_product(&l_inv, &l_inv)) // [C⁻¹]_ii = ‖L⁻¹_{:,i}‖²
        }
        GpKind::Spgp | GpKind::SpgpHet => {
            let f = factor(data, h, jitter)?;
            let parts: Vec<_> = data
                .blocks()
                .par_iter()
                .zip(f.blocks.par_iter())
                .map(|(&blk, p)| sparse_block(data, &f, p, blk))
                .collect();
            let alpha = parts.iter().flat_map(|(a, _)| a.iter().copied());
            let diag = parts.iter().flat_map(|(_, d)| d.iter().copied());
            (
                DVector::from_iterator(data.len(), alpha),
                DVector::from_iterator(data.len(), diag),
            )
        }
    };
    Ok(from_inverse(
        &data.y,
        &c_inv_y,
        &c_inv_diag,
        h.noise_variance,
    ))
}

impl<K: Kernel> crate::GpModel<K> {
    /// Leave-one-out moments of this model's hyperparameters on training data `x` (N×D) and
    /// `y` (N), in the target's units: each sample predicted from the other N − 1 (GPML eq.
    /// 5.12). Kersting et al.'s noise GP reads its held-out residuals from these (gp.md §7).
    pub fn loo_moments(&self, x: &nalgebra::DMatrix<f64>, y: &DVector<f64>) -> Result<LooMoments> {
        if x.nrows() != y.len() || x.ncols() != self.input_names.len() {
            return Err(crate::GpError::InvalidParams(format!(
                "leave-one-out on {}×{} inputs and {} targets, the model takes {} columns",
                x.nrows(),
                x.ncols(),
                y.len(),
                self.input_names.len()
            )));
        }
        let data = TrainData::new(&self.inputs.apply(x), &self.target.apply_vector(y))
            .with_point_data(&self.hyper.kernel);
        let loo = loo_moments(&data, self.kind, &self.hyper, self.jitter)?;
        Ok(LooMoments {
            mean: self.target.invert_vector(&loo.mean),
            var_latent: self.target.invert_variance(&loo.var_latent),
            var_y: self.target.invert_variance(&loo.var_y),
        })
    }
}

#[cfg(test)]
#[path = "loo_tests.rs"]
mod tests;
