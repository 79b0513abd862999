//! The adjoints of the ARD-scaled squared distances ([`super::ard_distance`]): the length-scale
//! and first-argument gradients of one group of columns from E = −2 G ∘ ∂K/∂r² (gp.md §2.3, where
//! for SE, E = G ∘ K) and its line sums. The O(PQD) part is one product E·B, consumed a group of
//! its columns at a time while in cache; every other loop runs along contiguous columns.

use nalgebra::{DMatrix, DVector};

use super::ard_distance::columns_from;
use super::direct_gemm::{Layout, Lhs, Rhs, Structure, product_consumed};
use super::kernel::Points;
use super::linalg::{mul, sum, transpose, transposed};
use super::shape::Group;
use super::simd::vectorised;

/// Largest inner dimension given to the packing-free products: beyond it the operands' tiles no
/// longer fit the core's caches.
const DIRECT_MAX_DEPTH: usize = 1024;

/// The column sums c_q = Σ_p E_pq and row sums r_p = Σ_q E_pq of a P×Q matrix.
pub(crate) struct LineSums {
    cols: Vec<f64>,
    rows: Vec<f64>,
}

impl LineSums {
    /// Σ_pq E_pq.
    pub fn total(&self) -> f64 {
        sum(&self.cols)
    }
}

/// G ∘ K and its line sums, in one sweep over the columns.
pub(crate) fn product_with_sums(gm: &DMatrix<f64>, k: &DMatrix<f64>) -> (DMatrix<f64>, LineSums) {
    let p_len = k.nrows();
    let mut e = DMatrix::zeros(p_len, k.ncols());
    let mut sums = LineSums {
        cols: Vec::with_capacity(k.ncols()),
        rows: vec![0.0; p_len],
    };
    if p_len == 0 {
        sums.cols.resize(k.ncols(), 0.0);
        return (e, sums);
    }
    vectorised(
        #[inline(always)]
        || {
            for ((e_col, g_col), k_col) in e
                .as_mut_slice()
                .chunks_exact_mut(p_len)
                .zip(gm.as_slice().chunks_exact(p_len))
                .zip(k.as_slice().chunks_exact(p_len))
            {
                for (((ev, gv), kv), r) in
                    e_col.iter_mut().zip(g_col).zip(k_col).zip(&mut sums.rows)
                {
                    *ev = gv * kv;
                    *r += *ev;
                }
                sums.cols.push(sum(e_col));
            }
        },
    );
    (e, sums)
}

/// The line sums of `e` (see [`LineSums`]).
pub(crate) fn line_sums(e: &DMatrix<f64>) -> LineSums {
    let p_len = e.nrows();
    let mut sums = LineSums {
        cols: Vec::with_capacity(e.ncols()),
        rows: vec![0.0; p_len],
    };
    if p_len == 0 {
        sums.cols.resize(e.ncols(), 0.0);
        return sums;
    }
    vectorised(
        #[inline(always)]
        || {
            for col in e.as_slice().chunks_exact(p_len) {
                for (r, v) in sums.rows.iter_mut().zip(col) {
                    *r += v;
                }
                sums.cols.push(sum(col));
            }
        },
    );
    sums
}

/// Adds the length-scale and first-argument gradients of one group, given E = −2 G ∘ ∂K/∂r²_g
/// and its line sums: ∂/∂log ℓ_d = ℓ_d⁻² Σ_pq E_pq (a_pd − b_qd)², ∂/∂a_pd = ℓ_d⁻² Σ_q E_pq
/// (b_qd − a_pd), the latter into `d_a` (P×D, one row per point).
#[allow(clippy::too_many_arguments)]
pub(crate) fn group_gradient(
    a: Points<'_>,
    b: Points<'_>,
    (e, sums): (&DMatrix<f64>, &LineSums),
    inv_sq: &DVector<f64>,
    g: Group,
    d_log_l: &mut [f64],
    d_a: Option<&mut DMatrix<f64>>,
) {
    let d = a.dims();
    let mut acc = vec![0.0; g.len];
    let w = &inv_sq.as_slice()[g.start..g.start + g.len];
    // Σ_q c_q b_qd² with c_q = Σ_p E_pq.
    vectorised(
        #[inline(always)]
        || {
            for (&c, bq) in sums.cols.iter().zip(b.coord_slice().chunks_exact(d)) {
                for (a, v) in acc.iter_mut().zip(&bq[g.start..g.start + g.len]) {
                    *a += c * v * v;
                }
            }
        },
    );
    // A's coordinates one dimension per column, contiguous over its points.
    let owned;
    let (a_by_dim, lda) = match a.by_dim() {
        Some(kept) => kept,
        None => {
            owned = transpose(&a.coords().into_owned());
            (owned.as_slice(), a.len())
        }
    };
    let mut terms = PointTerms {
        a_by_dim,
        lda,
        lo: g.start,
        rows: &sums.rows,
        w,
        acc: &mut acc,
        d_a: d_a.map(|m| m.as_mut_slice()),
    };
    if b.len() <= DIRECT_MAX_DEPTH {
        // E B with B read in place: one dimension per column when the points keep that copy (the
        // training inputs), else its rows (B_g's points are contiguous rows of B). Each group of
        // its columns is consumed while in cache: E B itself is never stored.
        let b_g = match b.by_dim() {
            Some((data, ld)) => {
                Rhs::new(&data[g.start * ld..], (b.len(), g.len), ld, Layout::Columns)
            }
            None => Rhs::new(columns_from(b, g), (b.len(), g.len), d, Layout::Rows),
        };
        product_consumed(
            Lhs::of(e),
            Structure::General,
            b_g,
            #[inline(always)]
            |j0, columns| terms.add(j0, columns),
        );
    } else {
        // Deep products (a full GP's N×N adjoint) go through gemm's cache blocking.
        let b_rows = transposed(b.coord_slice(), d, b.len());
        let ex = mul(e, &b_rows.columns(g.start, g.len));
        vectorised(
            #[inline(always)]
            || terms.add(0, ex.as_slice()),
        );
    }
    for (j, a_acc) in acc.iter().enumerate() {
        d_log_l[g.start + j] += w[j] * a_acc;
    }
}

/// The terms of one group's gradients that involve (E B)_pd, added a group of its columns at a
/// time: Σ_p r_p a_pd² − 2 a_pd (E B)_pd into the length-scale sums, with r_p = Σ_q E_pq, and
/// ℓ_d⁻² ((E B)_pd − r_p a_pd) into ∂/∂a_pd. Every loop runs along contiguous columns.
struct PointTerms<'a> {
    /// A's coordinate d of point p at p + d·lda.
    a_by_dim: &'a [f64],
    lda: usize,
    /// The group's first column.
    lo: usize,
    /// r_p.
    rows: &'a [f64],
    /// ℓ⁻² of the group's columns.
    w: &'a [f64],
    /// The length-scale sums of the group's columns.
    acc: &'a mut [f64],
    /// ∂/∂A, P×D column-major.
    d_a: Option<&'a mut [f64]>,
}

impl PointTerms<'_> {
    /// Adds the terms of the group's columns j0 .. j0 + w given (E B)'s columns there (P×w,
    /// column-major); each column's sum has a fixed order, whatever the grouping.
    #[inline(always)]
    fn add(&mut self, j0: usize, ex: &[f64]) {
        let p_len = self.rows.len();
        if p_len == 0 {
            return;
        }
        for (j, ex_col) in (j0..).zip(ex.chunks_exact(p_len)) {
            let col = self.lo + j;
            let a_col = &self.a_by_dim[col * self.lda..][..p_len];
            self.acc[j] += point_sum(a_col, self.rows, ex_col);
            if let Some(d_a) = self.d_a.as_deref_mut() {
                let wj = self.w[j];
                let out = &mut d_a[col * p_len..][..p_len];
                for (((o, v), r), x) in out.iter_mut().zip(a_col).zip(self.rows).zip(ex_col) {
                    *o += wj * (x - r * v);
                }
            }
        }
    }
}

/// Σ_p r_p a_p² − 2 a_p x_p in four interleaved partial sums (vectorised, fixed order).
#[inline(always)]
fn point_sum(a: &[f64], r: &[f64], x: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (ac, rc, xc) = (a.chunks_exact(4), r.chunks_exact(4), x.chunks_exact(4));
    let tail: f64 = (ac
        .remainder()
        .iter()
        .zip(rc.remainder())
        .zip(xc.remainder()))
    .map(|((a, r), x)| r * a * a - 2.0 * a * x)
    .sum();
    for ((a, r), x) in ac.zip(rc).zip(xc) {
        for l in 0..4 {
            acc[l] += r[l] * a[l] * a[l] - 2.0 * a[l] * x[l];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}
