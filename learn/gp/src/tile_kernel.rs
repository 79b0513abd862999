//! The register tiles of the packing-free products ([`super::direct_gemm`]): MRV vectors of rows
//! of A times NR columns of B, accumulated in registers by one fused multiply-add per vector and
//! column at each depth p. A's columns are read in place as vectors; B's values are broadcast one
//! at a time, from contiguous columns or from contiguous rows.

use pulp::Simd;

/// Rows of A read by one pass: `data` is column-major with leading dimension `ld`; its row 0 is
/// row `first` of the full A.
#[derive(Clone, Copy)]
pub(crate) struct RowSource<'a> {
    /// The rows' values, column-major.
    pub data: &'a [f64],
    /// Distance between columns in `data`.
    pub ld: usize,
    /// Number of rows of C this pass writes.
    pub rows: usize,
    /// Index in A (and C) of the first row.
    pub first: usize,
}

/// NR columns of B as seen by one tile.
pub(crate) enum TileB<'a, const NR: usize> {
    /// One contiguous slice of length k per column.
    Columns([&'a [f64]; NR]),
    /// Rows of NR contiguous values, `ld` apart.
    Rows(&'a [f64], usize),
}

/// The MRV-vector column of A at depth p of rows `i0 ..` of `src`.
#[inline(always)]
fn a_column<S: Simd, const MRV: usize>(src: RowSource<'_>, i0: usize, p: usize) -> [S::f64s; MRV] {
    let start = p * src.ld + i0;
    let (v, _) = S::as_simd_f64s(&src.data[start..start + MRV * S::F64_LANES]);
    std::array::from_fn(|r| v[r])
}

/// Σ_{p ∈ depth} A[i0.., p] B[p, ..] for B with contiguous columns.
#[inline(always)]
pub(crate) fn kernel_columns<S: Simd, const MRV: usize, const NR: usize>(
    simd: S,
    src: RowSource<'_>,
    i0: usize,
    depth: std::ops::Range<usize>,
    b: &[&[f64]; NR],
) -> [[S::f64s; MRV]; NR] {
    let mut acc = [[simd.splat_f64s(0.0); MRV]; NR];
    let b: [&[f64]; NR] = std::array::from_fn(|j| &b[j][depth.clone()]);
    for (q, p) in depth.enumerate() {
        let a = a_column::<S, MRV>(src, i0, p);
        for (acc_col, b_col) in acc.iter_mut().zip(&b) {
            let bv = simd.splat_f64s(b_col[q]);
            for (c, av) in acc_col.iter_mut().zip(&a) {
                *c = simd.mul_add_f64s(*av, bv, *c);
            }
        }
    }
    acc
}

/// Σ_{p ∈ depth} A[i0.., p] B[p, ..] for B with contiguous rows `ld` apart.
#[inline(always)]
pub(crate) fn kernel_rows<S: Simd, const MRV: usize, const NR: usize>(
    simd: S,
    src: RowSource<'_>,
    i0: usize,
    depth: std::ops::Range<usize>,
    b: &[f64],
    ld: usize,
) -> [[S::f64s; MRV]; NR] {
    let mut acc = [[simd.splat_f64s(0.0); MRV]; NR];
    for p in depth {
        let a = a_column::<S, MRV>(src, i0, p);
        let b_row = &b[p * ld..][..NR];
        for (acc_col, bv) in acc.iter_mut().zip(b_row) {
            let bv = simd.splat_f64s(*bv);
            for (c, av) in acc_col.iter_mut().zip(&a) {
                *c = simd.mul_add_f64s(*av, bv, *c);
            }
        }
    }
    acc
}
