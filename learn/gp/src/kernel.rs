//! The squared-exponential ARD kernel k(x,x') = s·exp(−½ Σ_d (x_d − x'_d)²/ℓ_d²) (thesis eq. 3.11,
//! with lengthscales not squared as in gp.md §0), evaluated through gemm: the squared distance is
//! ‖x‖²_ℓ + ‖z‖²_ℓ − 2 (Z diag(ℓ⁻²)) Xᵀ, so the O(NMD) part is one matrix-matrix product.

use nalgebra::{DMatrix, DVector, Dyn, Matrix, Storage};

use super::linalg::{mul, t_view};

/// One side of a covariance evaluation: points as rows, pre-scaled by ℓ⁻², with scaled norms.
pub(crate) struct ScaledPoints {
    /// The points times diag(ℓ⁻²), one row per point.
    pub scaled: DMatrix<f64>,
    /// Σ_d p_d²/ℓ_d² per point.
    pub sqnorm: DVector<f64>,
}

/// ℓ⁻² for each input dimension.
pub(crate) fn inverse_squares(lengthscales: &DVector<f64>) -> DVector<f64> {
    lengthscales.map(|l| 1.0 / (l * l))
}

/// Prepares the rows of `points` (P×D) for covariance evaluations.
pub(crate) fn scale_points(points: &DMatrix<f64>, inv_sq: &DVector<f64>) -> ScaledPoints {
    let mut scaled = points.clone();
    for (mut col, w) in scaled.column_iter_mut().zip(inv_sq.iter()) {
        col *= *w;
    }
    let sqnorm = DVector::from_iterator(
        points.nrows(),
        points
            .row_iter()
            .zip(scaled.row_iter())
            .map(|(p, q)| p.dot(&q)),
    );
    ScaledPoints { scaled, sqnorm }
}

/// Scaled squared norms of samples stored as columns: `xt_sq` holds x² (D×B).
pub(crate) fn column_sqnorms<S: Storage<f64, Dyn, Dyn>>(
    xt_sq: &Matrix<f64, Dyn, Dyn, S>,
    inv_sq: &DVector<f64>,
) -> DVector<f64> {
    DVector::from_iterator(xt_sq.ncols(), xt_sq.column_iter().map(|c| c.dot(inv_sq)))
}

/// Covariance P×B between prepared points and samples stored as the columns of `xt` (D×B).
pub(crate) fn cross_covariance<S: Storage<f64, Dyn, Dyn>>(
    side: &ScaledPoints,
    xt: &Matrix<f64, Dyn, Dyn, S>,
    x_sqnorm: &DVector<f64>,
    signal_variance: f64,
) -> DMatrix<f64> {
    let mut k = mul(&side.scaled, xt);
    for (j, mut col) in k.column_iter_mut().enumerate() {
        let xn = x_sqnorm[j];
        for (i, v) in col.iter_mut().enumerate() {
            let r2 = (side.sqnorm[i] + xn - 2.0 * *v).max(0.0);
            *v = signal_variance * (-0.5 * r2).exp();
        }
    }
    k
}

/// Covariance K_M among the rows of `points` (P×P, exact diagonal `signal_variance`).
pub(crate) fn self_covariance(
    points: &DMatrix<f64>,
    inv_sq: &DVector<f64>,
    signal_variance: f64,
) -> DMatrix<f64> {
    let side = scale_points(points, inv_sq);
    let mut k = cross_covariance(&side, &t_view(points), &side.sqnorm, signal_variance);
    for i in 0..k.nrows() {
        k[(i, i)] = signal_variance;
    }
    // Symmetrise so the Cholesky sees an exactly symmetric matrix.
    let kt = k.transpose();
    (k + kt) * 0.5
}

/// Covariance between the rows of `a` (P×D) and the rows of `b` (Q×D): P×Q.
pub(crate) fn covariance_rows(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    inv_sq: &DVector<f64>,
    signal_variance: f64,
) -> DMatrix<f64> {
    let side = scale_points(a, inv_sq);
    let bt = b.transpose();
    let b_norm = column_sqnorms(&bt.map(|v| v * v), inv_sq);
    cross_covariance(&side, &bt, &b_norm, signal_variance)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gemm_kernel_matches_the_direct_formula() {
        let a = DMatrix::from_fn(7, 3, |i, j| ((i * 5 + j * 3) % 7) as f64 * 0.3 - 1.0);
        let b = DMatrix::from_fn(9, 3, |i, j| ((i * 2 + j) % 5) as f64 * 0.4 - 0.8);
        let ls = DVector::from_vec(vec![0.7, 1.3, 2.0]);
        let k = covariance_rows(&a, &b, &inverse_squares(&ls), 1.7);
        for p in 0..7 {
            for q in 0..9 {
                let r2: f64 = (0..3)
                    .map(|d| ((a[(p, d)] - b[(q, d)]) / ls[d]).powi(2))
                    .sum();
                let want = 1.7 * (-0.5 * r2).exp();
                assert!((k[(p, q)] - want).abs() < 1e-13, "{p},{q}");
            }
        }
    }
}
