//! ARD-scaled squared distances and their adjoints through gemm: r² = ‖a‖²_ℓ + ‖b‖²_ℓ −
//! 2 (A diag(ℓ⁻²)) Bᵀ over one group of columns, and the length-scale and first-argument gradients
//! from E = −2 G ∘ ∂K/∂r² (gp.md §2.3, where for SE, E = G ∘ K). Apart from the two gemms every
//! loop runs along contiguous point columns.

use nalgebra::{DMatrix, DVector};

use super::kernel::Points;
use super::linalg::{mul, sum, transposed};
use super::shape::Group;

/// Σ_j v_j² w_j with four partial sums, so the loop vectorises.
fn weighted_sq_sum(v: &[f64], w: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (vc, wc) = (v.chunks_exact(4), w.chunks_exact(4));
    let (vr, wr) = (vc.remainder(), wc.remainder());
    for (a, b) in vc.zip(wc) {
        for l in 0..4 {
            acc[l] += a[l] * a[l] * b[l];
        }
    }
    let tail: f64 = vr.iter().zip(wr).map(|(a, b)| a * a * b).sum();
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// Σ_{d∈g} v_d² ℓ_d⁻² for each point.
fn scaled_norms(p: Points<'_>, inv_sq: &[f64], g: Group) -> Vec<f64> {
    let d = p.dims();
    p.coord_slice()
        .chunks_exact(d)
        .map(|col| weighted_sq_sum(&col[g.start..g.start + g.len], inv_sq))
        .collect()
}

/// Squared scaled distances r² (P×Q) between `a` and `b` over the columns of `g`.
pub(crate) fn sq_distances(
    a: Points<'_>,
    b: Points<'_>,
    inv_sq: &DVector<f64>,
    g: Group,
) -> DMatrix<f64> {
    let w = &inv_sq.as_slice()[g.start..g.start + g.len];
    let d = a.dims();
    // A diag(ℓ⁻²) as P×D_g rows.
    let ac = a.coord_slice();
    let scaled = DMatrix::from_fn(a.len(), g.len, |p, j| ac[p * d + g.start + j] * w[j]);
    let (a_norm, b_norm) = (scaled_norms(a, w, g), scaled_norms(b, w, g));
    let b_all = b.coords();
    let mut r2 = mul(&scaled, &b_all.rows(g.start, g.len));
    for (col, bn) in r2.as_mut_slice().chunks_exact_mut(a.len()).zip(&b_norm) {
        for (v, an) in col.iter_mut().zip(&a_norm) {
            *v = (an + bn - 2.0 * *v).max(0.0);
        }
    }
    r2
}

/// Adds the length-scale and first-argument gradients of one group, given E = −2 G ∘ ∂K/∂r²_g:
/// ∂/∂log ℓ_d = ℓ_d⁻² Σ_pq E_pq (a_pd − b_qd)², ∂/∂a_pd = ℓ_d⁻² Σ_q E_pq (b_qd − a_pd).
pub(crate) fn group_gradient(
    a: Points<'_>,
    b: Points<'_>,
    e: &DMatrix<f64>,
    inv_sq: &DVector<f64>,
    g: Group,
    d_log_l: &mut [f64],
    d_a: Option<&mut DMatrix<f64>>,
) {
    let (p_len, d) = (a.len(), a.dims());
    // E B with B's rows read as a row-major view (the fast way round for gemm), then transposed
    // to D_g×P so that each point's row of it is a contiguous column below.
    let b_rows = transposed(b.coord_slice(), d, b.len());
    let ex_t = mul(e, &b_rows.columns(g.start, g.len)).transpose();
    let mut acc = vec![0.0; g.len];
    // Σ_q c_q b_qd² with c_q = Σ_p E_pq.
    for (col, bq) in e
        .as_slice()
        .chunks_exact(p_len)
        .zip(b.coord_slice().chunks_exact(d))
    {
        let c = sum(col);
        for (a, v) in acc.iter_mut().zip(&bq[g.start..g.start + g.len]) {
            *a += c * v * v;
        }
    }
    // Σ_p r_p a_pd² − 2 a_pd (E B)_pd, with r_p = Σ_q E_pq; and ∂/∂a_pd.
    let r = e.column_sum();
    let w = &inv_sq.as_slice()[g.start..g.start + g.len];
    let mut d_a = d_a;
    for (p, (a_col, ex_col)) in a
        .coord_slice()
        .chunks_exact(d)
        .zip(ex_t.as_slice().chunks_exact(g.len))
        .enumerate()
    {
        let a_g = &a_col[g.start..g.start + g.len];
        for ((a_acc, v), exv) in acc.iter_mut().zip(a_g).zip(ex_col) {
            *a_acc += r[p] * v * v - 2.0 * v * exv;
        }
        if let Some(d_a) = d_a.as_deref_mut() {
            let out = &mut d_a.as_mut_slice()[p * d + g.start..p * d + g.start + g.len];
            for (((o, wj), v), exv) in out.iter_mut().zip(w).zip(a_g).zip(ex_col) {
                *o += wj * (exv - r[p] * v);
            }
        }
    }
    for (j, a_acc) in acc.iter().enumerate() {
        d_log_l[g.start + j] += w[j] * a_acc;
    }
}
