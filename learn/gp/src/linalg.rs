//! Small dense linear-algebra helpers: transposed views for gemm, a jittered Cholesky (gp.md §5.1)
//! and triangular inverses, so the O(NM²) products run as matrix-matrix products.

use nalgebra::{DMatrix, DVector, Dyn, MatrixView};

/// A dense matrix view with arbitrary strides (e.g. a transpose).
pub(crate) type StridedView<'a> = MatrixView<'a, f64, Dyn, Dyn, Dyn, Dyn>;

use super::blocked::{cholesky, lower_inverse_of};
use crate::{GpError, Result};

/// How many times the jitter is multiplied by 10 before a factorisation is declared failed.
const JITTER_RETRIES: usize = 5;

pub(crate) use super::gemm::mul;

/// A view of the transpose of the column-major `rows × cols` matrix stored in `data`.
///
/// nalgebra's `gemm` hands the strides to matrixmultiply, so multiplying by this view costs no copy.
pub(crate) fn transposed(data: &[f64], rows: usize, cols: usize) -> StridedView<'_> {
    StridedView::from_slice_with_strides(data, cols, rows, rows, 1)
}

/// The transpose of `a` as a view (see [`transposed`]).
pub(crate) fn t_view(a: &DMatrix<f64>) -> StridedView<'_> {
    transposed(a.as_slice(), a.nrows(), a.ncols())
}

/// `a`ᵀ, written column after column into a fresh buffer (no zero-fill). Each destination column
/// reads one row of `a` across its columns; the cache lines it touches serve the next seven rows,
/// so for the M×D matrices here every line is read from memory once.
pub(crate) fn transpose(a: &DMatrix<f64>) -> DMatrix<f64> {
    let (rows, cols) = a.shape();
    let src = a.as_slice();
    let mut out = Vec::with_capacity(rows * cols);
    for i in 0..rows {
        out.extend(src[i..].iter().step_by(rows).take(cols));
    }
    DMatrix::from_vec(cols, rows, out)
}

/// A lower Cholesky factor and the diagonal jitter that made the factorisation succeed.
pub(crate) struct JitteredCholesky {
    /// Lower-triangular factor of `a + jitter·I`.
    pub l: DMatrix<f64>,
    /// The jitter finally added to the diagonal.
    pub jitter: f64,
}

/// Factors `a + jitter·I`; on failure retries with 10× the jitter up to five times (GPy's `jitchol`,
/// gp.md §5.1), then returns [`GpError::Numerical`] naming `what`.
pub(crate) fn cholesky_with_jitter(
    a: &DMatrix<f64>,
    jitter: f64,
    what: &str,
) -> Result<JitteredCholesky> {
    if a.iter().any(|v| !v.is_finite()) {
        return Err(GpError::Numerical(format!("{what} has non-finite entries")));
    }
    let n = a.nrows();
    let mean_diag = if n == 0 {
        1.0
    } else {
        a.diagonal().mean().abs().max(f64::MIN_POSITIVE)
    };
    let mut eps = jitter.max(0.0);
    for attempt in 0..=JITTER_RETRIES {
        let mut m = a.clone();
        for i in 0..n {
            m[(i, i)] += eps;
        }
        if let Some(l) = cholesky(&m) {
            return Ok(JitteredCholesky { l, jitter: eps });
        }
        if attempt < JITTER_RETRIES {
            eps = (eps * 10.0).max(1e-10 * mean_diag);
        }
    }
    Err(GpError::Numerical(format!(
        "{what} ({n}×{n}) is not positive definite even with jitter {eps:.3e}"
    )))
}

/// The inverse of a lower-triangular matrix with a non-zero diagonal.
pub(crate) fn lower_inverse(l: &DMatrix<f64>, what: &str) -> Result<DMatrix<f64>> {
    let inv = lower_inverse_of(l);
    if inv.iter().all(|v| v.is_finite()) {
        Ok(inv)
    } else {
        Err(GpError::Numerical(format!("{what} has a zero pivot")))
    }
}

/// Sum of the logs of the diagonal of a triangular factor (half the log-determinant).
pub(crate) fn log_diag_sum(l: &DMatrix<f64>) -> f64 {
    l.diagonal().iter().map(|v| v.ln()).sum()
}

/// Σ values in four interleaved partial sums: vectorised and, for a given length, always added in
/// the same order.
#[inline(always)]
pub(crate) fn sum(values: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let chunks = values.chunks_exact(4);
    let tail: f64 = chunks.remainder().iter().sum();
    for c in chunks {
        for (a, v) in acc.iter_mut().zip(c) {
            *a += v;
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// Σ a_i b_i in four interleaved partial sums (vectorised, fixed order for a given length).
#[inline(always)]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (ac, bc) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ac
        .remainder()
        .iter()
        .zip(bc.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ac.zip(bc) {
        for l in 0..4 {
            acc[l] += x[l] * y[l];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// Column sums of the elementwise product `a ∘ b` (same shapes).
pub(crate) fn colsum_product(a: &DMatrix<f64>, b: &DMatrix<f64>) -> DVector<f64> {
    DVector::from_iterator(
        a.ncols(),
        a.column_iter()
            .zip(b.column_iter())
            .map(|(ca, cb)| ca.dot(&cb)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_transposed_view_multiplies_like_a_transpose() {
        let a = DMatrix::from_fn(7, 9, |i, j| (i * 3 + j) as f64 * 0.1 - 1.0);
        let b = DMatrix::from_fn(7, 8, |i, j| (i + 2 * j) as f64 * 0.05);
        let got = mul(&t_view(&a), &b);
        let want = a.transpose() * &b;
        assert!((got - want).amax() < 1e-12);
    }

    #[test]
    fn the_transpose_equals_nalgebras() {
        for (r, c) in [(1, 1), (3, 7), (100, 242), (9, 1)] {
            let a = DMatrix::from_fn(r, c, |i, j| (i * 31 + j) as f64);
            assert_eq!(transpose(&a), a.transpose(), "{r}×{c}");
        }
    }

    #[test]
    fn small_strided_products_are_computed_without_overrunning() {
        let a = DMatrix::from_fn(3, 2, |i, j| (i + 4 * j) as f64);
        let b = DMatrix::from_fn(3, 4, |i, j| (2 * i + j) as f64);
        assert_eq!(mul(&t_view(&a), &b), a.transpose() * &b);
    }

    #[test]
    fn a_singular_matrix_factors_after_jitter_and_nan_is_an_error() {
        let a = DMatrix::from_element(3, 3, 1.0);
        let chol = cholesky_with_jitter(&a, 0.0, "K").expect("jitter rescues a rank-one matrix");
        assert!(chol.jitter > 0.0);
        let mut bad = DMatrix::identity(2, 2);
        bad[(0, 1)] = f64::NAN;
        assert!(matches!(
            cholesky_with_jitter(&bad, 1e-6, "K"),
            Err(GpError::Numerical(_))
        ));
    }
}
