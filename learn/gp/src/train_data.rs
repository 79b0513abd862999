//! Training inputs laid out for the blocked O(NM²) passes: samples as contiguous columns of a D×N
//! matrix (with the kernel's per-point data, if any) and the targets; fixed-size row blocks so
//! parallel sums are deterministic.

use nalgebra::{DMatrix, DVector};

use super::kernel::{Kernel, Points};

/// Rows per block of the blocked passes; fixed so the reduction order never depends on threads.
pub(crate) const BLOCK_ROWS: usize = 200;

/// The (standardised) training data of one fit.
#[derive(Debug, Clone)]
pub(crate) struct TrainData {
    /// Inputs, one sample per column (D×N).
    pub xt: DMatrix<f64>,
    /// The same inputs one sample per row (N×D), read in place by the gradient's E·X products.
    x: DMatrix<f64>,
    /// The kernel's per-point data (E×N), if it has any.
    pub extra: Option<DMatrix<f64>>,
    /// Targets (N).
    pub y: DVector<f64>,
    /// Relative noise level per sample (noise σ²·w_n), or σ² for all.
    pub noise_weights: Option<DVector<f64>>,
}

impl TrainData {
    /// Lays out `x` (N×D, one sample per row) and `y` (N).
    pub fn new(x: &DMatrix<f64>, y: &DVector<f64>) -> Self {
        Self {
            xt: x.transpose(),
            x: x.clone(),
            extra: None,
            y: y.clone(),
            noise_weights: None,
        }
    }

    /// Attaches the per-point data `kernel` derives from the inputs.
    pub fn with_point_data<K: Kernel>(mut self, kernel: &K) -> Self {
        self.extra = kernel.point_data(&self.xt);
        self
    }

    /// Noise variance of sample `n` for a global noise variance `noise`.
    #[inline(always)]
    pub fn noise_at(&self, n: usize, noise: f64) -> f64 {
        self.noise_weights.as_ref().map_or(noise, |w| noise * w[n])
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

    /// All samples as kernel points.
    pub fn points(&self) -> Points<'_> {
        Points::new(&self.xt, self.extra.as_ref()).with_by_dim(&self.x)
    }

    /// `(start, len)` of each row block, in order.
    pub fn blocks(&self) -> Vec<(usize, usize)> {
        let n = self.len();
        (0..n.div_ceil(BLOCK_ROWS))
            .map(|b| (b * BLOCK_ROWS, BLOCK_ROWS.min(n - b * BLOCK_ROWS)))
            .collect()
    }
}
