//! ARD-scaled squared distances through one packing-free product: r² = ‖a‖²_ℓ + ‖b‖²_ℓ −
//! 2 (A diag(ℓ⁻²)) Bᵀ over one group of columns, the norms (and the kernel's profile) applied in
//! the product's epilogue. Their adjoints are in [`super::ard_gradient`].

use nalgebra::{DMatrix, DVector};

use super::direct_gemm::{Layout, Lhs, Rhs, Structure, product_then};
use super::kernel::Points;
use super::shape::Group;
use super::simd::vectorised;

/// The coordinates of `p` from column `g.start` of its first point on (empty for no points).
pub(crate) fn columns_from(p: Points<'_>, g: Group) -> &[f64] {
    p.coord_slice().get(g.start..).unwrap_or(&[])
}

/// Σ_j v_j² w_j in sixteen interleaved partial sums: two vectors of eight lanes (four of four
/// with AVX2), so the loop is not held up by the latency of one chain of additions.
#[inline(always)]
fn weighted_sq_sum(v: &[f64], w: &[f64]) -> f64 {
    const LANES: usize = 16;
    let mut acc = [0.0; LANES];
    let (vc, wc) = (v.chunks_exact(LANES), w.chunks_exact(LANES));
    let (vr, wr) = (vc.remainder(), wc.remainder());
    for (a, b) in vc.zip(wc) {
        for l in 0..LANES {
            acc[l] += a[l] * a[l] * b[l];
        }
    }
    let tail: f64 = vr.iter().zip(wr).map(|(a, b)| a * a * b).sum();
    // A fixed pairwise reduction: the same order on every instruction set.
    let mut width = LANES;
    while width > 1 {
        width /= 2;
        for l in 0..width {
            acc[l] += acc[l + width];
        }
    }
    acc[0] + tail
}

/// Σ_{d∈g} v_d² ℓ_d⁻² for each point.
fn scaled_norms(p: Points<'_>, inv_sq: &[f64], g: Group) -> Vec<f64> {
    let d = p.dims();
    let mut out = Vec::with_capacity(p.len());
    vectorised(
        #[inline(always)]
        || {
            // A plain loop: an iterator's `collect` would run in a baseline (unvectorised) copy.
            for col in p.coord_slice().chunks_exact(d) {
                out.push(weighted_sq_sum(&col[g.start..g.start + g.len], inv_sq));
            }
        },
    );
    out
}

/// A diag(ℓ⁻²) over the columns of `g` (P×D_g), column by column from the points' copy one
/// dimension per column when they keep one.
fn scaled_columns(a: Points<'_>, w: &[f64], g: Group) -> DMatrix<f64> {
    let (p_len, d) = (a.len(), a.dims());
    match a.by_dim() {
        Some((data, ld)) => {
            let mut out = Vec::with_capacity(p_len * g.len);
            for (j, wj) in w.iter().enumerate() {
                out.extend(data[(g.start + j) * ld..][..p_len].iter().map(|v| v * wj));
            }
            DMatrix::from_vec(p_len, g.len, out)
        }
        None => {
            let ac = a.coord_slice();
            DMatrix::from_fn(p_len, g.len, |p, j| ac[p * d + g.start + j] * w[j])
        }
    }
}

/// Squared scaled distances r² (P×Q) between `a` and `b` over the columns of `g`.
pub(crate) fn sq_distances(
    a: Points<'_>,
    b: Points<'_>,
    inv_sq: &DVector<f64>,
    g: Group,
) -> DMatrix<f64> {
    sq_distances_then(a, b, inv_sq, g, |_| {})
}

/// [`sq_distances`] with `then` applied to each group of finished columns of r² inside the
/// product (e.g. the kernel's profile), while they are in the first-level cache. Pass an
/// `#[inline(always)]` closure: it runs in the vectorised context.
pub(crate) fn sq_distances_then<F: FnMut(&mut [f64])>(
    a: Points<'_>,
    b: Points<'_>,
    inv_sq: &DVector<f64>,
    g: Group,
    mut then: F,
) -> DMatrix<f64> {
    let w = &inv_sq.as_slice()[g.start..g.start + g.len];
    let d = a.dims();
    let scaled = scaled_columns(a, w, g);
    let (a_norm, b_norm) = (scaled_norms(a, w, g), scaled_norms(b, w, g));
    let b_g = Rhs::new(columns_from(b, g), (g.len, b.len()), d, Layout::Columns);
    let p_len = a.len();
    product_then(
        Lhs::of(&scaled),
        Structure::General,
        b_g,
        #[inline(always)]
        |j0, columns| {
            for (col, bn) in columns.chunks_exact_mut(p_len).zip(&b_norm[j0..]) {
                for (v, an) in col.iter_mut().zip(&a_norm) {
                    *v = (an + bn - 2.0 * *v).max(0.0);
                }
            }
            then(columns);
        },
    )
}
