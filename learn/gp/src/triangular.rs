//! Products with a lower-triangular factor (BLAS's `trmm`) and updates of a symmetric matrix's
//! lower triangle (`syrk`), recursive on halves so that the bulk runs in gemm while the zero half
//! of a triangle and the mirrored half of a symmetric result are never computed. The blocked
//! Cholesky, inverse and Gram of `blocked.rs` are built from them: with dense products in their
//! place each did about twice the multiply-adds the algorithm needs (10-13 GFLOP/s of useful work
//! at n = 800-1,055 against gemm's 27-32 on the project's machine; docs/speed.md "stop 65").
//!
//! Every output entry is summed in an order fixed by the shapes alone, so results do not depend
//! on the number of threads.

use nalgebra::{DMatrix, DMatrixView, DMatrixViewMut};

use super::gemm::mul;

/// Blocks of at most this many rows are multiplied densely (the zero or mirrored half of such a
/// block costs less than another level of recursion).
const DENSE: usize = 64;

/// L·B for a lower-triangular `l` (n×n, its strict upper triangle zero) and `b` (n×m).
pub(crate) fn lower_times(l: DMatrixView<'_, f64>, b: DMatrixView<'_, f64>) -> DMatrix<f64> {
    let (n, m) = b.shape();
    if n <= DENSE {
        return mul(&l, &b);
    }
    // [L11 0; L21 L22]·[B1; B2] = [L11 B1; L21 B1 + L22 B2]; the two halves side by side.
    let (n1, n2) = (n / 2, n - n / 2);
    let (top, mut bottom) = rayon::join(
        || lower_times(l.view((0, 0), (n1, n1)), b.rows(0, n1)),
        || lower_times(l.view((n1, n1), (n2, n2)), b.rows(n1, n2)),
    );
    bottom += mul(&l.view((n1, 0), (n2, n1)), &b.rows(0, n1));
    let mut out = DMatrix::zeros(n, m);
    out.rows_mut(0, n1).copy_from(&top);
    out.rows_mut(n1, n2).copy_from(&bottom);
    out
}

/// B·L for `b` (m×n) and a lower-triangular `l` (n×n, its strict upper triangle zero).
pub(crate) fn times_lower(b: DMatrixView<'_, f64>, l: DMatrixView<'_, f64>) -> DMatrix<f64> {
    let (m, n) = b.shape();
    if n <= DENSE {
        return mul(&b, &l);
    }
    // [B1 B2]·[L11 0; L21 L22] = [B1 L11 + B2 L21, B2 L22]; the two halves side by side.
    let (n1, n2) = (n / 2, n - n / 2);
    let (mut left, right) = rayon::join(
        || times_lower(b.columns(0, n1), l.view((0, 0), (n1, n1))),
        || times_lower(b.columns(n1, n2), l.view((n1, n1), (n2, n2))),
    );
    left += mul(&b.columns(n1, n2), &l.view((n1, 0), (n2, n1)));
    let mut out = DMatrix::zeros(m, n);
    out.columns_mut(0, n1).copy_from(&left);
    out.columns_mut(n1, n2).copy_from(&right);
    out
}

/// C ← C + sign·A·Aᵀ on the lower triangle of the n×n `c` (`a` is n×k; `sign` is ±1). The strict
/// upper triangle of `c` is left partly updated: only the lower one is defined afterwards.
pub(crate) fn add_lower_gram(c: &mut DMatrixViewMut<'_, f64>, a: DMatrixView<'_, f64>, sign: f64) {
    let n = c.nrows();
    if n <= DENSE {
        let update = mul(&a, &a.transpose());
        c.zip_apply(&update, |x, u| *x += sign * u);
        return;
    }
    // [C11 ·; C21 C22] + sign·[P; Q]·[Pᵀ Qᵀ]: C11 += PPᵀ, C21 += QPᵀ, C22 += QQᵀ.
    let (n1, n2) = (n / 2, n - n / 2);
    let (p, q) = (a.rows(0, n1), a.rows(n1, n2));
    let off = mul(&q, &p.transpose());
    c.view_mut((n1, 0), (n2, n1))
        .zip_apply(&off, |x, u| *x += sign * u);
    add_lower_gram(&mut c.view_mut((0, 0), (n1, n1)), p, sign);
    add_lower_gram(&mut c.view_mut((n1, n1), (n2, n2)), q, sign);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lower(n: usize) -> DMatrix<f64> {
        DMatrix::from_fn(n, n, |i, j| {
            if i >= j {
                (((i * 7 + j * 13) % 17) as f64 - 8.0) * 0.1 + if i == j { 3.0 } else { 0.0 }
            } else {
                0.0
            }
        })
    }

    fn general(r: usize, c: usize) -> DMatrix<f64> {
        DMatrix::from_fn(r, c, |i, j| ((i * 5 + j * 3) % 11) as f64 * 0.2 - 1.0)
    }

    #[test]
    fn a_lower_triangular_product_from_the_left_equals_the_dense_one_to_1e12() {
        for (n, m) in [(1, 3), (64, 5), (65, 70), (130, 1), (301, 129)] {
            let (l, b) = (lower(n), general(n, m));
            let want = &l * &b;
            let got = lower_times(l.as_view(), b.as_view());
            assert!(
                (&got - &want).amax() < 1e-12 * want.amax().max(1.0),
                "n={n} m={m}"
            );
        }
    }

    #[test]
    fn a_lower_triangular_product_from_the_right_equals_the_dense_one_to_1e12() {
        for (m, n) in [(3, 1), (5, 64), (70, 65), (1, 130), (129, 301)] {
            let (b, l) = (general(m, n), lower(n));
            let want = &b * &l;
            let got = times_lower(b.as_view(), l.as_view());
            assert!(
                (&got - &want).amax() < 1e-12 * want.amax().max(1.0),
                "m={m} n={n}"
            );
        }
    }

    #[test]
    fn a_symmetric_update_sets_the_lower_triangle_of_the_dense_one_to_1e12() {
        for (n, k) in [(1, 4), (64, 3), (65, 100), (200, 77)] {
            let a = general(n, k);
            for sign in [1.0, -1.0] {
                let mut c = general(n, n);
                let want = &c + sign * (&a * a.transpose());
                add_lower_gram(&mut c.as_view_mut(), a.as_view(), sign);
                let worst = (0..n)
                    .flat_map(|j| (j..n).map(move |i| (i, j)))
                    .map(|(i, j)| (c[(i, j)] - want[(i, j)]).abs())
                    .fold(0.0, f64::max);
                assert!(worst < 1e-12 * want.amax().max(1.0), "n={n} k={k}");
            }
        }
    }
}
