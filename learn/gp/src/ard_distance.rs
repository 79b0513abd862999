//! ARD-scaled squared distances and their adjoints through gemm: r² = ‖a‖²_ℓ + ‖b‖²_ℓ −
//! 2 (A diag(ℓ⁻²)) Bᵀ over one group of columns, and the length-scale and first-argument gradients
//! from E = −2 G ∘ ∂K/∂r² (gp.md §2.3, where for SE, E = G ∘ K).

use nalgebra::{DMatrix, DVector, Dyn, Matrix, Storage};

use super::kernel::Points;
use super::linalg::{mul, transposed};
use super::shape::Group;

/// Squared scaled distances r² between `a` and `b` over the columns of `g`.
pub(crate) fn sq_distances(
    a: Points<'_>,
    b: Points<'_>,
    inv_sq: &DVector<f64>,
    g: Group,
) -> DMatrix<f64> {
    let a_rows = a.coords().rows(g.start, g.len).transpose(); // P×D_g
    let mut scaled = a_rows.clone();
    for (j, mut col) in scaled.column_iter_mut().enumerate() {
        col *= inv_sq[g.start + j];
    }
    let norms = |rows: &DMatrix<f64>, scaled: &DMatrix<f64>| {
        DVector::from_iterator(
            rows.nrows(),
            rows.row_iter()
                .zip(scaled.row_iter())
                .map(|(p, q)| p.dot(&q)),
        )
    };
    let a_norm = norms(&a_rows, &scaled);
    let b_all = b.coords();
    let bt = b_all.rows(g.start, g.len);
    let b_norm = DVector::from_iterator(
        b.len(),
        bt.column_iter().map(|c| {
            c.iter()
                .enumerate()
                .map(|(j, v)| v * v * inv_sq[g.start + j])
                .sum::<f64>()
        }),
    );
    let mut r2 = mul(&scaled, &bt);
    for (j, mut col) in r2.column_iter_mut().enumerate() {
        for (i, v) in col.iter_mut().enumerate() {
            *v = (a_norm[i] + b_norm[j] - 2.0 * *v).max(0.0);
        }
    }
    r2
}

/// Adds the length-scale and first-argument gradients of one group, given E = −2 G ∘ ∂K/∂r²_g.
pub(crate) fn group_gradient<S: Storage<f64, Dyn, Dyn>>(
    a: Points<'_>,
    b: Points<'_>,
    e: &Matrix<f64, Dyn, Dyn, S>,
    inv_sq: &DVector<f64>,
    g: Group,
    d_log_l: &mut [f64],
    d_a: Option<&mut DMatrix<f64>>,
) {
    let (ac, bc) = (a.coords(), b.coords());
    let b_rows = transposed(b.coord_slice(), b.dims(), b.len()); // Q×D view
    let ex = mul(e, &b_rows.columns(g.start, g.len)); // P×D_g
    let r = e.column_sum(); // row sums (P)
    let c = DVector::from_iterator(e.ncols(), e.column_iter().map(|col| col.sum()));
    for j in 0..g.len {
        let d = g.start + j;
        let mut acc = 0.0;
        for (q, cq) in c.iter().enumerate() {
            acc += cq * bc[(d, q)] * bc[(d, q)];
        }
        for p in 0..a.len() {
            let ap = ac[(d, p)];
            acc += r[p] * ap * ap - 2.0 * ap * ex[(p, j)];
        }
        d_log_l[d] += inv_sq[d] * acc;
    }
    if let Some(d_a) = d_a {
        for p in 0..a.len() {
            for j in 0..g.len {
                let d = g.start + j;
                d_a[(d, p)] += inv_sq[d] * (ex[(p, j)] - r[p] * ac[(d, p)]);
            }
        }
    }
}
