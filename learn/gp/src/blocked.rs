//! Recursive blocked Cholesky factorisation and lower-triangular inverse whose O(n³) work runs in
//! gemm: the off-diagonal blocks are matrix products, only blocks of at most `LEAF` columns are
//! done column by column, in vectorised loops along contiguous columns. For M = 100 pseudo-inputs
//! (one leaf) and thousands of points in the full GP this is several times faster than
//! nalgebra's unblocked routines. The products with a triangular block and the symmetric updates
//! skip the zero and the mirrored halves (`triangular.rs`).

use nalgebra::{DMatrix, DMatrixView, DMatrixViewMut};

use rayon::prelude::*;

use super::gemm::mul;
use super::simd::vectorised;
use super::triangular::{add_lower_gram, lower_times, times_lower};

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
    // L21 = A21 L11⁻ᵀ = (L11⁻¹ A21ᵀ)ᵀ, then the lower triangle of A22 −= L21 L21ᵀ.
    let l11_inv = lower_inverse_of(&a.view((0, 0), (n1, n1)).into_owned());
    let a21_t = a.view((n1, 0), (n2, n1)).transpose();
    let l21 = lower_times(l11_inv.as_view(), a21_t.as_view()).transpose();
    a.view_mut((n1, 0), (n2, n1)).copy_from(&l21);
    let mut a22 = a.view_mut((n1, n1), (n2, n2));
    add_lower_gram(&mut a22, l21.as_view(), -1.0);
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
    let l21_x11 = times_lower(l.view((n1, 0), (n2, n1)), x11.as_view());
    let x21 = -lower_times(x22.as_view(), l21_x11.as_view());
    x.view_mut((0, 0), (n1, n1)).copy_from(&x11);
    x.view_mut((n1, 0), (n2, n1)).copy_from(&x21);
    x.view_mut((n1, n1), (n2, n2)).copy_from(&x22);
    x
}

/// L⁻¹B for a lower-triangular `l` with a non-zero diagonal (non-finite entries if not): the
/// forward substitution of every column of `b` at once, recursive on [L11 0; L21 L22] so the
/// bulk is the gemm B2 − L21·V1; column blocks of `b` run in parallel.
pub(crate) fn lower_solve(l: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    const COLUMNS_PER_TASK: usize = 128;
    let (n, m) = b.shape();
    if m <= COLUMNS_PER_TASK {
        return lower_solve_block(l.as_view(), b.clone());
    }
    let blocks: Vec<DMatrix<f64>> = (0..m)
        .step_by(COLUMNS_PER_TASK)
        .collect::<Vec<_>>()
        .into_par_iter()
        .map(|start| {
            let width = COLUMNS_PER_TASK.min(m - start);
            lower_solve_block(l.as_view(), b.columns(start, width).into_owned())
        })
        .collect();
    let mut out = DMatrix::zeros(n, m);
    for (k, block) in blocks.into_iter().enumerate() {
        out.columns_mut(k * COLUMNS_PER_TASK, block.ncols())
            .copy_from(&block);
    }
    out
}

/// L⁻¹B for one block of columns, overwriting `b`; `l` is read in place (only a leaf's small
/// diagonal block is copied).
fn lower_solve_block(l: DMatrixView<'_, f64>, mut b: DMatrix<f64>) -> DMatrix<f64> {
    let n = l.nrows();
    if n <= 2 * LEAF {
        let leaf = l.clone_owned();
        let ls = leaf.as_slice();
        for col in b.as_mut_slice().chunks_exact_mut(n) {
            for k in 0..n {
                let lk = &ls[k * n..(k + 1) * n];
                let xk = col[k] / lk[k];
                col[k] = xk;
                for (xi, li) in col[k + 1..].iter_mut().zip(&lk[k + 1..]) {
                    *xi -= xk * li;
                }
            }
        }
        return b;
    }
    let n1 = n / 2;
    let n2 = n - n1;
    let v1 = lower_solve_block(l.view((0, 0), (n1, n1)), b.rows(0, n1).into_owned());
    let mut b2 = b.rows(n1, n2).into_owned();
    b2 -= mul(&l.view((n1, 0), (n2, n1)), &v1);
    let v2 = lower_solve_block(l.view((n1, n1), (n2, n2)), b2);
    b.rows_mut(0, n1).copy_from(&v1);
    b.rows_mut(n1, n2).copy_from(&v2);
    b
}

/// XᵀX for a lower-triangular `x` (C⁻¹ = L⁻ᵀL⁻¹ from X = L⁻¹, LAPACK's `lauum`), exactly
/// symmetric. Recursive on [X11 0; X21 X22]: XᵀX = [X11ᵀX11 + X21ᵀX21, X21ᵀX22; X22ᵀX21,
/// X22ᵀX22], so the zero block is never multiplied: about ⅔n³ flops against 2n³ for the dense
/// product (the diagonal blocks run side by side).
pub(crate) fn lower_gram(x: &DMatrix<f64>) -> DMatrix<f64> {
    let mut out = lower_gram_part(x);
    let n = out.nrows();
    for j in 0..n {
        for i in j + 1..n {
            out[(j, i)] = out[(i, j)];
        }
    }
    out
}

/// XᵀX with its lower triangle exact (the strict upper one is left partly updated).
fn lower_gram_part(x: &DMatrix<f64>) -> DMatrix<f64> {
    let n = x.nrows();
    if n <= 2 * LEAF {
        return mul(&x.transpose(), x);
    }
    let n1 = n / 2;
    let n2 = n - n1;
    let x22 = x.view((n1, n1), (n2, n2)).into_owned();
    let (mut a11, a22) = rayon::join(
        || lower_gram_part(&x.view((0, 0), (n1, n1)).into_owned()),
        || lower_gram_part(&x22),
    );
    // A11 += X21ᵀX21 (its lower triangle), A21 = X22ᵀX21 = (X21ᵀX22)ᵀ; only X21ᵀ is needed.
    let x21t = x.view((n1, 0), (n2, n1)).transpose();
    add_lower_gram(&mut a11.as_view_mut(), x21t.as_view(), 1.0);
    let a21 = times_lower(x21t.as_view(), x22.as_view()).transpose();
    let mut out = DMatrix::zeros(n, n);
    out.view_mut((0, 0), (n1, n1)).copy_from(&a11);
    out.view_mut((n1, 0), (n2, n1)).copy_from(&a21);
    out.view_mut((n1, n1), (n2, n2)).copy_from(&a22);
    out
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
    fn the_blocked_triangular_solve_matches_nalgebras_forward_substitution() {
        for (n, m) in [(1, 3), (40, 1), (64, 200), (65, 129), (300, 260)] {
            let l = cholesky(&spd(n)).expect("positive definite");
            let b = DMatrix::from_fn(n, m, |i, j| ((i * 5 + j * 3) % 11) as f64 - 5.0);
            let want = l.solve_lower_triangular(&b).expect("non-singular");
            let got = lower_solve(&l, &b);
            assert!(
                (&got - &want).amax() < 1e-9 * want.amax().max(1.0),
                "n={n} m={m}"
            );
        }
    }

    #[test]
    fn the_gram_of_a_lower_triangular_matrix_equals_the_dense_product_and_is_symmetric() {
        for n in [1, 7, 64, 65, 130, 301] {
            let l = cholesky(&spd(n)).expect("positive definite");
            let x = lower_inverse_of(&l);
            let want = x.transpose() * &x;
            let got = lower_gram(&x);
            assert!((&got - &want).amax() < 1e-10 * want.amax(), "n={n}");
            assert_eq!(got, got.transpose(), "n={n}");
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
