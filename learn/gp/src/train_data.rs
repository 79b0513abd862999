//! Training inputs laid out for the blocked O(NM²) passes: samples as contiguous columns of a D×N
//! matrix, their squares, and the targets; fixed-size row blocks so parallel sums are deterministic.

use nalgebra::{DMatrix, DMatrixView, DVector};

use super::linalg::{StridedView, transposed};

/// Rows per block of the blocked passes; fixed so the reduction order never depends on threads.
pub(crate) const BLOCK_ROWS: usize = 256;

/// Standardised training data of one fit.
#[derive(Debug, Clone)]
pub(crate) struct TrainData {
    /// Inputs, one sample per column (D×N).
    pub xt: DMatrix<f64>,
    /// Elementwise squares of `xt`.
    pub xt_sq: DMatrix<f64>,
    /// Targets (N).
    pub y: DVector<f64>,
}

impl TrainData {
    /// Lays out `x` (N×D, one sample per row) and `y` (N).
    pub fn new(x: &DMatrix<f64>, y: &DVector<f64>) -> Self {
        let xt = x.transpose();
        let xt_sq = xt.map(|v| v * v);
        Self {
            xt,
            xt_sq,
            y: y.clone(),
        }
    }

    /// Number of samples N.
    pub fn len(&self) -> usize {
        self.xt.ncols()
    }

    /// Input dimension D.
    pub fn dims(&self) -> usize {
        self.xt.nrows()
    }

    /// The inputs as rows (N×D), e.g. for initialisation.
    pub fn x_rows(&self) -> DMatrix<f64> {
        self.xt.transpose()
    }

    /// `(start, len)` of each row block, in order.
    pub fn blocks(&self) -> Vec<(usize, usize)> {
        let n = self.len();
        (0..n.div_ceil(BLOCK_ROWS))
            .map(|b| (b * BLOCK_ROWS, BLOCK_ROWS.min(n - b * BLOCK_ROWS)))
            .collect()
    }

    /// The block's samples as columns (D×B).
    pub fn xt_block(&self, start: usize, len: usize) -> DMatrixView<'_, f64> {
        self.xt.columns(start, len)
    }

    /// The block's squared samples as columns (D×B).
    pub fn xt_sq_block(&self, start: usize, len: usize) -> DMatrixView<'_, f64> {
        self.xt_sq.columns(start, len)
    }

    /// The block's samples as rows (B×D), a strided view for gemm.
    pub fn x_block(&self, start: usize, len: usize) -> StridedView<'_> {
        let d = self.dims();
        transposed(&self.xt.as_slice()[start * d..(start + len) * d], d, len)
    }
}
