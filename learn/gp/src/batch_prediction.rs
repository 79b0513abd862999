//! Predictions at thousands of test inputs per call, given one after another in a flat slice
//! (the whole-scan step predicts every hypothesis cell of a scan this way).
//!
//! The sparse posterior (thesis eqs. 3.32-3.33) is evaluated in blocks of [`BLOCK_POINTS`] test
//! points, spread over the rayon pool: per block, the cross-covariances K_MB through the crate's
//! packing-free products (the fit's kernels), the mean K_MBᵀw, and the latent variance
//! s − diag(K_MBᵀ W K_MB) with W K_MB through the same products. Every value of a point comes
//! from sequential multiply-add chains over its own column, so a point's prediction does not
//! depend on the other points of the call, on the blocks or on the number of threads: a row
//! gets the same bits alone, in any batch, on one core or two.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use super::direct_gemm::{Lhs, Rhs, Structure, product};
use super::hyper::Hyper;
use super::kernel::{Kernel, OwnedPoints, Points};
use super::linalg::dot;
use super::model::{GpModel, GpPrediction, Posterior};
use super::simd::vectorised;
use super::sparse_posterior::SparsePosterior;
use crate::{GpError, Result};

/// Test points per block: K_MB (M×B) and the block's inputs (D×B) stay in the second-level
/// cache, the M×D pseudo-input work repeated per block is about 1 % of the block's product,
/// and a scan's few thousand points make dozens of blocks to balance over the cores.
const BLOCK_POINTS: usize = 128;

/// Mean and latent variance of one block, standardised.
struct BlockMoments {
    mean: Vec<f64>,
    var: Vec<f64>,
}

impl<K: Kernel> GpModel<K> {
    /// Predicts at the test inputs in `rows`, given one after another (row-major, T×D for the
    /// model's D input columns), on the rayon pool. Same predictive distribution as
    /// [`GpModel::predict`] (to rounding), with each row's result independent of the batch it
    /// comes in and of the number of threads.
    ///
    /// ```
    /// use nalgebra::{DMatrix, DVector};
    /// use patchflow_gp::{GpKind, GpParams};
    ///
    /// let x = DMatrix::from_fn(40, 2, |i, j| (i as f64 / 8.0) * (1.0 + j as f64));
    /// let y = DVector::from_fn(40, |i, _| (i as f64 / 8.0).sin());
    /// let model = GpParams::new(GpKind::Spgp).pseudo_inputs(8).max_iters(30).fit(&x, &y)?;
    /// let rows = [2.0, 4.0, 0.5, 1.0];
    /// let p = model.predict_rows(&rows)?;
    /// assert_eq!(p.mean.len(), 2);
    /// # Ok::<(), patchflow_gp::GpError>(())
    /// ```
    pub fn predict_rows(&self, rows: &[f64]) -> Result<GpPrediction> {
        let d = self.input_names.len();
        let t = self.checked_row_count(rows, d)?;
        let (mean, var) = match &self.posterior {
            Posterior::Sparse(p) => {
                let z = OwnedPoints::of_rows(&self.hyper.pseudo_inputs, &self.hyper.kernel);
                let blocks: Vec<BlockMoments> = rows
                    .par_chunks(BLOCK_POINTS * d.max(1))
                    .map(|block| self.sparse_block(p, z.points(), block, d))
                    .collect();
                let mut mean = Vec::with_capacity(t);
                let mut var = Vec::with_capacity(t);
                for b in blocks {
                    mean.extend(b.mean);
                    var.extend(b.var);
                }
                (DVector::from_vec(mean), DVector::from_vec(var))
            }
            Posterior::Full(p) => {
                let xs = self.inputs.apply(&DMatrix::from_row_slice(t, d, rows));
                p.predict(&self.hyper, &xs)?
            }
        };
        let noisy = var.map(|v| v + self.hyper.noise_variance);
        Ok(GpPrediction {
            mean: self.target.invert_vector(&mean),
            var_latent: self.target.invert_variance(&var),
            var_y: self.target.invert_variance(&noisy),
        })
    }

    /// The number of rows in `rows`; errors if it is not whole rows of `d` finite values.
    fn checked_row_count(&self, rows: &[f64], d: usize) -> Result<usize> {
        if d == 0 || rows.len() % d != 0 {
            return Err(GpError::InvalidParams(format!(
                "{} test values are not whole rows of the model's {d} input columns",
                rows.len()
            )));
        }
        if let Some(pos) = rows.iter().position(|v| !v.is_finite()) {
            return Err(GpError::DegenerateData(format!(
                "test input row {}, column '{}' is not finite",
                pos / d,
                self.input_names[pos % d]
            )));
        }
        Ok(rows.len() / d)
    }

    /// Standardised mean and latent variance at the rows of one block.
    fn sparse_block(
        &self,
        posterior: &SparsePosterior,
        z: Points<'_>,
        block: &[f64],
        d: usize,
    ) -> BlockMoments {
        let h: &Hyper<K> = &self.hyper;
        let coords = self.standardised_columns(block, d);
        let extra = h.kernel.point_data(&coords);
        let test = Points::new(&coords, extra.as_ref());
        let k_star = h.kernel.cross(z, test); // M×B
        let m = k_star.nrows();
        let wk = product(
            Lhs::of(&posterior.var_matrix),
            Structure::General,
            Rhs::of(&k_star),
        );
        let prior = h.kernel.diag(test);
        let weights = posterior.weights.as_slice();
        let mut mean = Vec::with_capacity(coords.ncols());
        let mut var = Vec::with_capacity(coords.ncols());
        vectorised(
            #[inline(always)]
            || {
                for ((k_col, wk_col), k_prior) in k_star
                    .as_slice()
                    .chunks_exact(m.max(1))
                    .zip(wk.as_slice().chunks_exact(m.max(1)))
                    .zip(prior.iter())
                {
                    mean.push(dot(k_col, weights));
                    var.push((k_prior - dot(k_col, wk_col)).max(0.0));
                }
            },
        );
        BlockMoments { mean, var }
    }

    /// The rows of `block` (row-major, D values each) standardised as the fit's inputs, one
    /// point per column (D×B).
    fn standardised_columns(&self, block: &[f64], d: usize) -> DMatrix<f64> {
        let (mean, scale) = (&self.inputs.mean, &self.inputs.scale);
        let mut out = Vec::with_capacity(block.len());
        for row in block.chunks_exact(d) {
            out.extend(
                row.iter()
                    .zip(mean)
                    .zip(scale)
                    .map(|((x, mu), s)| (x - mu) / s),
            );
        }
        DMatrix::from_vec(d, block.len() / d, out)
    }
}

#[cfg(test)]
#[path = "batch_prediction_tests.rs"]
mod tests;
