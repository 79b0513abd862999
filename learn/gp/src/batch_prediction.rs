//! Predictions at thousands of test inputs per call, given one after another in a flat slice
//! (the whole-scan step predicts every hypothesis cell of a scan this way), with the bits of
//! [`GpModel::predict`].
//!
//! The sparse posterior (thesis eqs. 3.32-3.33) is evaluated in blocks of at most
//! [`BLOCK_POINTS`] test points spread over the rayon pool, with the arithmetic of `predict`:
//! K_MB through the crate's packing-free products, the mean K_MBᵀw and the latent variance
//! s − colsum(K_MB ∘ W K_MB) through nalgebra. Every step but one computes each point's values
//! from its own column alone, so the block a point falls in does not matter. The exception is
//! W K_MB: nalgebra hands it to matrixmultiply when the product has more than five columns and
//! runs its own loop otherwise, which rounds differently. So each group of rows keeps the path
//! a call on the group alone takes (`predict` on more than five rows: matrixmultiply, padded to
//! six columns where a block holds fewer of them; on five or fewer: nalgebra's loop, five columns
//! at most at a time), and a row's prediction is the same whatever else is in the call and
//! however many threads run it.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use super::gemm::{SMALL_DIM, mul};
use super::kernel::{Kernel, OwnedPoints, Points};
use super::linalg::colsum_product;
use super::model::{GpModel, GpPrediction, Posterior};
use super::sparse_posterior::SparsePosterior;
use crate::{GpError, Result};

/// Most test points per block: K_MB (M×B) and the block's inputs (D×B) stay in the
/// second-level cache, and a scan's few thousand points make dozens of blocks for the cores.
const BLOCK_POINTS: usize = 128;

/// One block of rows: where it starts, how many, and which of them take nalgebra's
/// small-product loop for W K_MB.
struct Block {
    start: usize,
    len: usize,
    small: Vec<bool>,
}

impl<K: Kernel> GpModel<K> {
    /// Predicts at the test inputs in `rows`, given one after another (row-major, T×D for the
    /// model's D input columns), on the rayon pool: bit for bit what [`GpModel::predict`] gives
    /// on the same rows.
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
    /// assert_eq!(p, model.predict(&DMatrix::from_row_slice(2, 2, &rows))?);
    /// # Ok::<(), patchflow_gp::GpError>(())
    /// ```
    pub fn predict_rows(&self, rows: &[f64]) -> Result<GpPrediction> {
        let t = rows.len() / self.input_names.len().max(1);
        self.predict_row_groups(rows, &[t])
    }

    /// Predicts at consecutive groups of rows (`group_rows` rows each, in order, together all
    /// of `rows`; row-major as in [`GpModel::predict_rows`]) in one call: every group gets the
    /// bits [`GpModel::predict`] gives on that group alone, e.g. each cluster of a scan the
    /// prediction a call on the cluster would give.
    pub fn predict_row_groups(&self, rows: &[f64], group_rows: &[usize]) -> Result<GpPrediction> {
        let d = self.input_names.len();
        let t = self.checked_row_count(rows, d)?;
        if group_rows.iter().sum::<usize>() != t {
            return Err(GpError::InvalidParams(format!(
                "groups of {} rows in all, but {t} rows were given",
                group_rows.iter().sum::<usize>()
            )));
        }
        let (mean, var) = match &self.posterior {
            Posterior::Sparse(p) => {
                let z = OwnedPoints::of_rows(&self.hyper.pseudo_inputs, &self.hyper.kernel);
                let m = p.weights.len();
                let small: Vec<bool> = group_rows
                    .iter()
                    .flat_map(|&n| std::iter::repeat_n(m.min(n) <= SMALL_DIM, n))
                    .collect();
                let blocks: Vec<(DVector<f64>, DVector<f64>)> = blocks(&small)
                    .into_par_iter()
                    .map(|b| {
                        let rows = &rows[b.start * d..(b.start + b.len) * d];
                        self.sparse_block(p, z.points(), rows, &b.small, d)
                    })
                    .collect();
                let mean = blocks.iter().flat_map(|(mu, _)| mu.iter().copied());
                let var = blocks.iter().flat_map(|(_, v)| v.iter().copied());
                (
                    DVector::from_iterator(t, mean),
                    DVector::from_iterator(t, var),
                )
            }
            Posterior::Full(p) => {
                let (mut mean, mut var) = (Vec::with_capacity(t), Vec::with_capacity(t));
                let mut start = 0;
                for &n in group_rows {
                    let x = DMatrix::from_row_slice(n, d, &rows[start * d..(start + n) * d]);
                    let (mu, v) = p.predict(&self.hyper, &self.inputs.apply(&x))?;
                    mean.extend(mu.iter());
                    var.extend(v.iter());
                    start += n;
                }
                (DVector::from_vec(mean), DVector::from_vec(var))
            }
        };
        self.prediction(&mean, &var)
    }

    /// The number of rows in `rows`; errors if it is not whole rows of `d` finite values.
    fn checked_row_count(&self, rows: &[f64], d: usize) -> Result<usize> {
        if d == 0 || !rows.len().is_multiple_of(d) {
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
        let cells = rows.iter().enumerate().map(|(i, &v)| (i / d, i % d, v));
        self.check_input_range(cells)?;
        Ok(rows.len() / d)
    }

    /// Standardised mean and latent variance at the rows of one block (as `SparsePosterior::
    /// predict` computes them), `small` saying which rows take nalgebra's small-product loop.
    fn sparse_block(
        &self,
        posterior: &SparsePosterior,
        z: Points<'_>,
        rows: &[f64],
        small: &[bool],
        d: usize,
    ) -> (DVector<f64>, DVector<f64>) {
        let h = &self.hyper;
        let coords = self.standardised_columns(rows, d);
        let extra = h.kernel.point_data(&coords);
        let test = Points::new(&coords, extra.as_ref());
        let k_star = h.kernel.cross(z, test); // M×B
        let mean = k_star.tr_mul(&posterior.weights);
        let wk = variance_product(&posterior.var_matrix, &k_star, small);
        let quad = colsum_product(&k_star, &wk);
        let prior = h.kernel.diag(test);
        let var = DVector::from_iterator(
            prior.len(),
            quad.iter().zip(prior.iter()).map(|(q, k)| (k - q).max(0.0)),
        );
        (mean, var)
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

/// Blocks of at most [`BLOCK_POINTS`] rows; every row in one.
fn blocks(small: &[bool]) -> Vec<Block> {
    (0..small.len())
        .step_by(BLOCK_POINTS)
        .map(|start| {
            let len = BLOCK_POINTS.min(small.len() - start);
            Block {
                start,
                len,
                small: small[start..start + len].to_vec(),
            }
        })
        .collect()
}

/// W K_MB with each column computed on the path its group takes in `predict`: the columns of
/// large groups together through matrixmultiply (at least SMALL_DIM + 1 of them, zero-padded),
/// the others at most SMALL_DIM at a time through nalgebra's own loop.
fn variance_product(w: &DMatrix<f64>, k_star: &DMatrix<f64>, small: &[bool]) -> DMatrix<f64> {
    let m = k_star.nrows();
    let mut out = DMatrix::zeros(m, k_star.ncols());
    let (small_cols, large_cols): (Vec<usize>, Vec<usize>) =
        (0..k_star.ncols()).partition(|&j| small[j]);
    if !large_cols.is_empty() {
        let width = large_cols.len().max(SMALL_DIM + 1);
        let mut gathered = DMatrix::zeros(m, width);
        for (k, &j) in large_cols.iter().enumerate() {
            gathered.set_column(k, &k_star.column(j));
        }
        let product = mul(w, &gathered);
        for (k, &j) in large_cols.iter().enumerate() {
            out.set_column(j, &product.column(k));
        }
    }
    for cols in small_cols.chunks(SMALL_DIM) {
        let gathered = DMatrix::from_fn(m, cols.len(), |i, k| k_star[(i, cols[k])]);
        let product = mul(w, &gathered);
        for (k, &j) in cols.iter().enumerate() {
            out.set_column(j, &product.column(k));
        }
    }
    out
}

#[cfg(test)]
#[path = "batch_prediction_tests.rs"]
mod tests;
