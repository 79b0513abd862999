//! The general matrix product through matrixmultiply's gemm, strided views included; its own file
//! so that the blocked factorisations and the other helpers can both use it without importing
//! each other.

use nalgebra::{DMatrix, Dyn, Matrix, Storage};

/// nalgebra's threshold below which `gemm` does not call matrixmultiply.
pub(crate) const SMALL_DIM: usize = 5;

/// `a * b` through matrixmultiply's gemm (strided views included, no copies).
pub(crate) fn mul<S1, S2>(
    a: &Matrix<f64, Dyn, Dyn, S1>,
    b: &Matrix<f64, Dyn, Dyn, S2>,
) -> DMatrix<f64>
where
    S1: Storage<f64, Dyn, Dyn>,
    S2: Storage<f64, Dyn, Dyn>,
{
    // nalgebra's fallback for small dimensions (≤ 5) mis-handles strided views (its axcpy loops
    // over the view's slice length), so small products go through owned copies.
    if a.nrows().min(a.ncols()).min(b.ncols()) <= SMALL_DIM {
        return a.clone_owned() * b.clone_owned();
    }
    // Above the threshold nalgebra hands both views' strides to matrixmultiply and writes the
    // result without zeroing it first.
    a * b
}
