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
    S1: Storage<f64, Dyn, Dyn> + Sync,
    S2: Storage<f64, Dyn, Dyn> + Sync,
{
    // nalgebra's fallback for small dimensions (≤ 5) mis-handles strided views (its axcpy loops
    // over the view's slice length), so small products go through owned copies.
    if a.nrows().min(a.ncols()).min(b.ncols()) <= SMALL_DIM {
        return a.clone_owned() * b.clone_owned();
    }
    // A large product is split by columns of `b` into two halves computed side by side
    // (matrixmultiply runs on one thread): the exact GP's O(N³) factorisations are such
    // products, and each output entry is summed exactly as in one call.
    let (m, k, n) = (a.nrows(), a.ncols(), b.ncols());
    if n >= 2 * SPLIT_MIN_COLUMNS && (m * k).saturating_mul(n) >= SPLIT_MIN_FLOPS {
        let h = n / 2;
        let (left, right) =
            rayon::join(|| mul(a, &b.columns(0, h)), || mul(a, &b.columns(h, n - h)));
        let mut out = DMatrix::zeros(m, n);
        out.columns_mut(0, h).copy_from(&left);
        out.columns_mut(h, n - h).copy_from(&right);
        return out;
    }
    // Above the threshold nalgebra hands both views' strides to matrixmultiply and writes the
    // result without zeroing it first.
    a * b
}

/// Products of at least this many multiply-adds are split in two (about 4 ms of work each).
const SPLIT_MIN_FLOPS: usize = 16_000_000;
/// Each half of a split product keeps at least this many columns.
const SPLIT_MIN_COLUMNS: usize = 32;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_product_large_enough_to_be_split_equals_the_unsplit_one_bit_for_bit() {
        let a = DMatrix::from_fn(300, 280, |i, j| ((i * 7 + j * 3) % 19) as f64 * 0.1 - 0.9);
        let b = DMatrix::from_fn(280, 301, |i, j| ((i * 5 + j * 11) % 23) as f64 * 0.05 - 0.5);
        const { assert!(300 * 280 * 301 >= SPLIT_MIN_FLOPS) };
        assert_eq!(mul(&a, &b), &a * &b);
        // A strided (transposed) view of the right operand is split the same way.
        let bt = b.transpose();
        assert_eq!(mul(&a, &bt.transpose()), &a * &b);
    }
}
