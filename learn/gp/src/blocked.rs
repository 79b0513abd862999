//! Recursive blocked Cholesky factorisation and lower-triangular inverse whose O(n³) work runs in
//! gemm: the off-diagonal blocks are matrix products, only blocks of at most `LEAF` columns are
//! done column by column, in vectorised loops along contiguous columns. For M = 100 pseudo-inputs
//! (one leaf) and thousands of points in the full GP this is several times faster than
//! nalgebra's unblocked routines.

use nalgebra::{DMatrix, DMatrixViewMut};

use super::gemm::mul;
use super::simd::vectorised;

/// Largest block factored column by column: a whole M×M pseudo-input covariance (M ≤ 128) is
/// one leaf.
const LEAF: usize = 32;

/// Left-looking Cholesky of the lower triangle of the column-major n×n `a` in place; false if not
/// positive definite. Column j takes the updates of the finished columns k < j along its
/// contiguous tail (vectorised); the strict upper triangle is left untouched.
fn cholesky_columns(a: &mut [f64], n: usize) -> bool {
    vectorised(
        #[inline(always)]
        || {
            for j in 0..n {
                let (done, rest) = a.split_at_mut(j * n);
                let col = &mut rest[..n];
                for ck in done.chunks_exact(n) {
                    let f = ck[j];
                    for (x, l) in col[j..].iter_mut().zip(&ck[j..]) {
                        *x -= f * l;
                    }
                }
                let pivot = col[j];
                if !(pivot > 0.0 && pivot.is_finite()) {
                    return false;
                }
                let d = pivot.sqrt();
                col[j] = d;
                for x in &mut col[j + 1..] {
                    *x /= d;
                }
            }
            true
        },
    )
}

/// Cholesky of a leaf block in place (a copy when the view is not contiguous).
fn cholesky_leaf(a: &mut DMatrixViewMut<'_, f64>) -> bool {
    let n = a.nrows();
    let mut owned = a.clone_owned();
    let ok = cholesky_columns(owned.as_mut_slice(), n);
    a.copy_from(&owned);
    ok
}

/// Blocked Cholesky of the lower triangle of `a` in place (upper triangle untouched).
fn cholesky_view(a: &mut DMatrixViewMut<'_, f64>) -> bool {
    let n = a.nrows();
    if n <= LEAF {
        return cholesky_leaf(a);
    }
    let n1 = n / 2;
    let n2 = n - n1;
    if !cholesky_view(&mut a.view_mut((0, 0), (n1, n1))) {
        return false;
    }
    // L21 = A21 L11⁻ᵀ, then A22 −= L21 L21ᵀ.
    let l11_inv = lower_inverse_of(&a.view((0, 0), (n1, n1)).into_owned());
    let l21 = mul(&a.view((n1, 0), (n2, n1)), &l11_inv.transpose());
    a.view_mut((n1, 0), (n2, n1)).copy_from(&l21);
    let update = mul(&l21, &l21.transpose());
    let mut a22 = a.view_mut((n1, n1), (n2, n2));
    a22 -= update;
    cholesky_view(&mut a22)
}

/// The lower Cholesky factor of the symmetric positive definite `a` (zero upper triangle), or
/// `None` if a pivot is not positive.
pub(crate) fn cholesky(a: &DMatrix<f64>) -> Option<DMatrix<f64>> {
    let mut l = a.clone();
    if !cholesky_view(&mut l.view_mut((0, 0), a.shape())) {
        return None;
    }
    l.fill_upper_triangle(0.0, 1);
    Some(l)
}

/// L⁻¹ for a lower-triangular `l` with a non-zero diagonal (non-finite entries if not).
pub(crate) fn lower_inverse_of(l: &DMatrix<f64>) -> DMatrix<f64> {
    let n = l.nrows();
    let mut x = DMatrix::zeros(n, n);
    if n <= LEAF {
        // Column j solves L x = e_j by forward substitution along contiguous columns of L.
        vectorised(
            #[inline(always)]
            || {
                for (j, xc) in x.as_mut_slice().chunks_exact_mut(n).enumerate() {
                    xc[j] = 1.0;
                    for (k, lk) in l.as_slice().chunks_exact(n).enumerate().skip(j) {
                        let xk = xc[k] / lk[k];
                        xc[k] = xk;
                        for (xi, li) in xc[k + 1..].iter_mut().zip(&lk[k + 1..]) {
                            *xi -= xk * li;
                        }
                    }
                }
            },
        );
        return x;
    }
    // [L11 0; L21 L22]⁻¹ = [X11 0; −X22 L21 X11  X22].
    let n1 = n / 2;
    let n2 = n - n1;
    // The two diagonal blocks are independent: invert them side by side.
    let (x11, x22) = rayon::join(
        || lower_inverse_of(&l.view((0, 0), (n1, n1)).into_owned()),
        || lower_inverse_of(&l.view((n1, n1), (n2, n2)).into_owned()),
    );
    let x21 = -mul(&x22, &mul(&l.view((n1, 0), (n2, n1)), &x11));
    x.view_mut((0, 0), (n1, n1)).copy_from(&x11);
    x.view_mut((n1, 0), (n2, n1)).copy_from(&x21);
    x.view_mut((n1, n1), (n2, n2)).copy_from(&x22);
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spd(n: usize) -> DMatrix<f64> {
        let b = DMatrix::from_fn(n, n, |i, j| (((i * 7 + j * 13) % 17) as f64 - 8.0) * 0.1);
        &b * b.transpose() + DMatrix::identity(n, n) * 0.5
    }

    #[test]
    fn the_blocked_cholesky_and_inverse_match_nalgebra_across_block_sizes() {
        for n in [1, 5, 32, 33, 70, 128, 150, 260] {
            let a = spd(n);
            let l = cholesky(&a).expect("positive definite");
            let want = nalgebra::Cholesky::new(a.clone()).expect("spd").unpack();
            assert!((&l - &want).amax() < 1e-12 * want.amax(), "chol n={n}");
            let inv = lower_inverse_of(&l);
            assert!(
                (&inv * &l - DMatrix::identity(n, n)).amax() < 1e-10,
                "inv n={n}"
            );
            assert!(
                (0..n).all(|j| (0..j).all(|i| inv[(i, j)] == 0.0)),
                "upper n={n}"
            );
        }
    }

    #[test]
    fn an_indefinite_or_nan_matrix_does_not_factor() {
        let mut a = spd(40);
        a[(35, 35)] = -100.0;
        assert!(cholesky(&a).is_none());
        let mut b = spd(10);
        b[(3, 3)] = f64::NAN;
        assert!(cholesky(&b).is_none());
    }
}
