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
use super::model::{GpModel, GpPrediction, MAX_STANDARDISED_INPUT, Posterior};
use super::sparse_posterior::SparsePosterior;
use crate::{GpError, Result};

/// Most test points per block: K_MB (M×B) and the block's inputs (D×B) stay in the
/// second-level cache, and a scan's few thousand points make dozens of blocks for the cores.
pub(crate) const BLOCK_POINTS: usize = 128;

/// One block of rows: where it starts, how many, and which of them take nalgebra's
/// small-product loop for W K_MB.
pub(crate) struct Block {
    pub start: usize,
    pub len: usize,
    pub small: Vec<bool>,
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
        let t = self.grouped_rows(rows, d, group_rows)?;
        let (mean, var) = match &self.posterior {
            Posterior::Sparse(p) => {
                let z = OwnedPoints::of_rows(&self.hyper.pseudo_inputs, &self.hyper.kernel);
                let m = p.weights.len();
                let small = small_product_rows(m, group_rows);
                let blocks = blocks(&small)
                    .into_par_iter()
                    .map(|b| {
                        let rows = &rows[b.start * d..(b.start + b.len) * d];
                        let coords = self
                            .standardised_columns(rows, d)
                            .map_err(|bad| bad.offset(b.start * d))?;
                        Ok(self.sparse_block(p, z.points(), &coords, Some(&b.small)))
                    })
                    .collect::<Vec<_>>();
                let blocks = self.without_bad_inputs(rows, blocks)?;
                let mean = blocks.iter().flat_map(|(mu, _)| mu.iter().copied());
                let var = blocks.iter().flat_map(|(_, v)| v.iter().copied());
                (
                    DVector::from_iterator(t, mean),
                    DVector::from_iterator(t, var),
                )
            }
            Posterior::Full(p) => {
                self.check_rows(rows, d)?;
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

    /// The predictive mean alone (target units) at the rows of `rows` (row-major, as in
    /// [`GpModel::predict_rows`]): bit for bit the `mean` of [`GpModel::predict_row_groups`],
    /// without the O(M²) variance per row, for a GP whose variance is not used (the noise GP of
    /// a most-likely heteroscedastic regression).
    ///
    /// ```
    /// use nalgebra::{DMatrix, DVector};
    /// use patchflow_gp::{GpKind, GpParams};
    ///
    /// let x = DMatrix::from_fn(40, 2, |i, j| (i as f64 / 8.0) * (1.0 + j as f64));
    /// let y = DVector::from_fn(40, |i, _| (i as f64 / 8.0).sin());
    /// let model = GpParams::new(GpKind::Spgp).pseudo_inputs(8).max_iters(30).fit(&x, &y)?;
    /// let rows = [2.0, 4.0, 0.5, 1.0];
    /// assert_eq!(model.predict_mean_rows(&rows)?, model.predict_rows(&rows)?.mean);
    /// # Ok::<(), patchflow_gp::GpError>(())
    /// ```
    pub fn predict_mean_rows(&self, rows: &[f64]) -> Result<DVector<f64>> {
        let d = self.input_names.len();
        let t = self.whole_rows(rows, d)?;
        let Posterior::Sparse(p) = &self.posterior else {
            return Ok(self.predict_row_groups(rows, &[t])?.mean);
        };
        let z = OwnedPoints::of_rows(&self.hyper.pseudo_inputs, &self.hyper.kernel);
        let blocks = (0..t)
            .step_by(BLOCK_POINTS)
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|start| {
                let end = (start + BLOCK_POINTS).min(t);
                let rows = &rows[start * d..end * d];
                let coords = self
                    .standardised_columns(rows, d)
                    .map_err(|bad| bad.offset(start * d))?;
                Ok(self.sparse_block(p, z.points(), &coords, None))
            })
            .collect::<Vec<_>>();
        let blocks = self.without_bad_inputs(rows, blocks)?;
        let mean = DVector::from_iterator(t, blocks.iter().flat_map(|(mu, _)| mu.iter().copied()));
        self.mean_in_target_units(&mean)
    }

    /// A standardised predictive mean in the target's units; a value that is not finite there
    /// is an error (as [`GpModel::prediction`] says).
    pub(crate) fn mean_in_target_units(&self, mean: &DVector<f64>) -> Result<DVector<f64>> {
        let mean = self.target.invert_vector(mean);
        if let Some(row) = mean.iter().position(|v| !v.is_finite()) {
            return Err(GpError::DegenerateData(format!(
                "the prediction at test input row {row} is not finite (mean {:e}): the model's \
                 target transform is broken",
                mean[row]
            )));
        }
        Ok(mean)
    }

    /// The number of rows in `rows`; errors if it is not whole rows of `d` values.
    pub(crate) fn whole_rows(&self, rows: &[f64], d: usize) -> Result<usize> {
        if d == 0 || !rows.len().is_multiple_of(d) {
            return Err(GpError::InvalidParams(format!(
                "{} test values are not whole rows of the model's {d} input columns",
                rows.len()
            )));
        }
        Ok(rows.len() / d)
    }

    /// The number of rows in `rows`, checked to be whole rows of `d` columns that `group_rows`
    /// splits exactly.
    pub(crate) fn grouped_rows(
        &self,
        rows: &[f64],
        d: usize,
        group_rows: &[usize],
    ) -> Result<usize> {
        let t = self.whole_rows(rows, d)?;
        let grouped = group_rows.iter().sum::<usize>();
        if grouped != t {
            return Err(GpError::InvalidParams(format!(
                "groups of {grouped} rows in all, but {t} rows were given"
            )));
        }
        Ok(t)
    }

    /// Errors if a value of `rows` is not finite or lies too far from the training data (one
    /// pass in order, for the full GP's path).
    fn check_rows(&self, rows: &[f64], d: usize) -> Result<()> {
        let bad = BadInputs::find(rows, &self.inputs.mean, &self.inputs.scale, d);
        match bad {
            Some(bad) => Err(self.bad_input_error(rows, d, bad)),
            None => Ok(()),
        }
    }

    /// The blocks' results, or the error for the first bad value over all blocks: the first
    /// value that is not finite if there is one, else the first out of range (what one pass over
    /// all rows in order finds).
    pub(crate) fn without_bad_inputs<T>(
        &self,
        rows: &[f64],
        blocks: Vec<std::result::Result<T, BadInputs>>,
    ) -> Result<Vec<T>> {
        let bad: Vec<BadInputs> = blocks
            .iter()
            .filter_map(|b| b.as_ref().err())
            .copied()
            .collect();
        if bad.is_empty() {
            return Ok(blocks.into_iter().filter_map(|b| b.ok()).collect());
        }
        let first = bad
            .iter()
            .find(|b| b.non_finite.is_some())
            .or(bad.first())
            .copied()
            .unwrap_or_default();
        Err(self.bad_input_error(rows, self.input_names.len(), first))
    }

    /// The error for the first bad value `bad` found in `rows` (positions index `rows`).
    fn bad_input_error(&self, rows: &[f64], d: usize, bad: BadInputs) -> GpError {
        if let Some(pos) = bad.non_finite {
            return GpError::DegenerateData(format!(
                "test input row {}, column '{}' is not finite",
                pos / d,
                self.input_names[pos % d]
            ));
        }
        let pos = bad.out_of_range.unwrap_or_default();
        let cell = rows.get(pos).map(|&v| (pos / d, pos % d, v));
        match self.check_input_range(cell.into_iter()) {
            Err(e) => e,
            Ok(()) => GpError::DegenerateData(format!("test input row {} is bad", pos / d)),
        }
    }

    /// Standardised mean and latent variance at the standardised points `coords` of one block
    /// (D×B, as `SparsePosterior::predict` computes them), `small` saying which rows take
    /// nalgebra's small-product loop; without `small`, the mean alone (the variance comes back
    /// empty).
    pub(crate) fn sparse_block(
        &self,
        posterior: &SparsePosterior,
        z: Points<'_>,
        coords: &DMatrix<f64>,
        small: Option<&[bool]>,
    ) -> (DVector<f64>, DVector<f64>) {
        let h = &self.hyper;
        let extra = h.kernel.point_data(coords);
        let test = Points::new(coords, extra.as_ref());
        let k_star = h.kernel.cross(z, test); // M×B
        let mean = k_star.tr_mul(&posterior.weights);
        let Some(small) = small else {
            return (mean, DVector::zeros(0));
        };
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
    /// point per column (D×B); the first bad value (not finite, or standardised beyond
    /// [`MAX_STANDARDISED_INPUT`], as [`GpModel::check_input_range`] tests it) is an error.
    pub(crate) fn standardised_columns(
        &self,
        block: &[f64],
        d: usize,
    ) -> std::result::Result<DMatrix<f64>, BadInputs> {
        let (mean, scale) = (&self.inputs.mean, &self.inputs.scale);
        let mut out = Vec::with_capacity(block.len());
        let mut bad = false;
        for row in block.chunks_exact(d) {
            out.extend(
                row.iter()
                    .zip(mean)
                    .zip(scale)
                    .map(|((x, mu), s)| (x - mu) / s),
            );
            let standardised = &out[out.len() - row.len()..];
            bad |= row.iter().zip(standardised).fold(false, |b, (x, z)| {
                b | !x.is_finite() | z.is_nan() | (z.abs() > MAX_STANDARDISED_INPUT)
            });
        }
        if bad && let Some(found) = BadInputs::find(block, mean.as_slice(), scale.as_slice(), d) {
            return Err(found);
        }
        Ok(DMatrix::from_vec(d, block.len() / d, out))
    }
}

/// Where a run of test rows first holds a value that is not finite, and where one first lies
/// too far from the training data (positions in the row-major values).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct BadInputs {
    non_finite: Option<usize>,
    out_of_range: Option<usize>,
}

impl BadInputs {
    /// The bad values of `rows` (row-major, `d` columns) standardised by `mean` and `scale`, if
    /// any.
    fn find(rows: &[f64], mean: &[f64], scale: &[f64], d: usize) -> Option<Self> {
        let non_finite = rows.iter().position(|v| !v.is_finite());
        let out_of_range = rows.iter().enumerate().position(|(i, &v)| {
            let standardised = (v - mean[i % d]) / scale[i % d];
            standardised.is_nan() || standardised.abs() > MAX_STANDARDISED_INPUT
        });
        (non_finite.is_some() || out_of_range.is_some()).then_some(Self {
            non_finite,
            out_of_range,
        })
    }

    /// The same positions counted from `start` values earlier.
    pub(crate) fn offset(self, start: usize) -> Self {
        Self {
            non_finite: self.non_finite.map(|p| p + start),
            out_of_range: self.out_of_range.map(|p| p + start),
        }
    }
}

/// Per row of groups of `group_rows` rows: whether W K_MB takes nalgebra's small-product loop
/// for it (its group or the `m` pseudo-inputs at most SMALL_DIM), as a call on the group alone
/// would.
pub(crate) fn small_product_rows(m: usize, group_rows: &[usize]) -> Vec<bool> {
    group_rows
        .iter()
        .flat_map(|&n| std::iter::repeat_n(m.min(n) <= SMALL_DIM, n))
        .collect()
}

/// Blocks of at most [`BLOCK_POINTS`] rows; every row in one.
pub(crate) fn blocks(small: &[bool]) -> Vec<Block> {
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
