//! Packing-free matrix products C = A·B for the SPGP passes, where A has M (the pseudo-inputs) rows
//! and every operand fits in the core's caches. A general gemm (matrixmultiply) first copies
//! ("packs") both operands into panels; at these sizes that copy took about a sixth of an SPGP
//! objective + gradient. Here A is read in place, a vector of rows at a time along its contiguous
//! columns, and B one broadcast scalar at a time, from either of its layouts, so neither is
//! copied; only the ragged edges are padded.
//!
//! Each C entry is one sequential fused multiply-add chain over k, so the result does not depend
//! on threads or tiling. A lower- or upper-triangular A skips its zero half, and a product known
//! to be symmetric computes the lower tiles only and mirrors them.

use nalgebra::DMatrix;
use pulp::{Simd, WithSimd};

use super::tile_kernel::{RowSource, TileB, kernel_columns, kernel_rows};

/// How the right operand B (k×n) lies in its slice.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Layout {
    /// B[p, j] at p + j·ld: columns contiguous (e.g. points stored as columns).
    Columns,
    /// B[p, j] at j + p·ld: rows contiguous (e.g. the transpose of a column-major matrix).
    Rows,
}

/// The right operand: a k×n matrix in a slice.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rhs<'a> {
    data: &'a [f64],
    k: usize,
    n: usize,
    ld: usize,
    layout: Layout,
}

impl<'a> Rhs<'a> {
    /// The k×n matrix with B[p, j] at p + j·ld (Columns) or j + p·ld (Rows) of `data`.
    pub fn new(data: &'a [f64], (k, n): (usize, usize), ld: usize, layout: Layout) -> Self {
        let (inner, outer) = match layout {
            Layout::Columns => (k, n),
            Layout::Rows => (n, k),
        };
        debug_assert!(
            inner <= ld && (outer == 0 || inner == 0 || (outer - 1) * ld + inner <= data.len()),
            "operand {k}×{n} (ld {ld}) does not fit its {} values",
            data.len()
        );
        Self {
            data,
            k,
            n,
            ld,
            layout,
        }
    }

    /// Bᵀ for the column-major matrix `b`: B[p, j] = b[j, p].
    pub fn transpose_of(b: &'a DMatrix<f64>) -> Self {
        Self::new(
            b.as_slice(),
            (b.ncols(), b.nrows()),
            b.nrows(),
            Layout::Rows,
        )
    }

    /// The column-major matrix `b` itself.
    pub fn of(b: &'a DMatrix<f64>) -> Self {
        Self::new(b.as_slice(), b.shape(), b.nrows(), Layout::Columns)
    }
}

/// The left operand: an m×k column-major matrix in a slice, columns `ld` apart.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Lhs<'a> {
    data: &'a [f64],
    m: usize,
    k: usize,
    ld: usize,
}

impl<'a> Lhs<'a> {
    /// The m×k matrix with A[i, p] at i + p·ld of `data`.
    pub fn new(data: &'a [f64], (m, k): (usize, usize), ld: usize) -> Self {
        debug_assert!(m <= ld && (k == 0 || m == 0 || (k - 1) * ld + m <= data.len()));
        Self { data, m, k, ld }
    }

    /// The column-major matrix `a` itself.
    pub fn of(a: &'a DMatrix<f64>) -> Self {
        Self::new(a.as_slice(), a.shape(), a.nrows())
    }
}

/// Which entries of a square left operand may be non-zero.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Structure {
    /// Any A.
    General,
    /// A lower-triangular: row i needs B's rows 0..=i only.
    Lower,
    /// A upper-triangular: row i needs B's rows i.. only.
    Upper,
}

/// C = A·B, skipping A's zero half when `structure` says it is triangular.
pub(crate) fn product(a: Lhs<'_>, structure: Structure, b: Rhs<'_>) -> DMatrix<f64> {
    run(a, structure, b, false)
}

/// C = A·B for a product known to be symmetric (e.g. Ṽ diag(w) Ṽᵀ): the lower tiles are computed
/// and mirrored, so C is exactly symmetric.
pub(crate) fn symmetric_product(a: Lhs<'_>, structure: Structure, b: Rhs<'_>) -> DMatrix<f64> {
    let mut c = run(a, structure, b, true);
    let m = c.nrows();
    for j in 1..m {
        for i in 0..j {
            c[(i, j)] = c[(j, i)];
        }
    }
    c
}

fn run(a: Lhs<'_>, structure: Structure, b: Rhs<'_>, symmetric: bool) -> DMatrix<f64> {
    let (m, k, n) = (a.m, a.k, b.n);
    debug_assert_eq!(k, b.k, "inner dimensions differ");
    debug_assert!(
        structure == Structure::General || m == k,
        "a triangular A is square"
    );
    debug_assert!(!symmetric || m == n, "a symmetric product is square");
    if m == 0 || n == 0 || k == 0 {
        return DMatrix::zeros(m, n);
    }
    let job = Job {
        a,
        structure,
        b,
        symmetric,
    };
    DMatrix::from_vec(m, n, pulp::Arch::new().dispatch(job))
}

/// C = A·B computed with the instruction set `simd` (the tests check each one the dispatch may pick).
#[cfg(test)]
pub(crate) fn product_with<S: Simd>(
    simd: S,
    a: Lhs<'_>,
    structure: Structure,
    b: Rhs<'_>,
) -> DMatrix<f64> {
    let job = Job {
        a,
        structure,
        b,
        symmetric: false,
    };
    DMatrix::from_vec(a.m, b.n, simd.vectorize(job))
}

/// A product, as dispatched to the widest instruction set; it returns C's values column-major.
struct Job<'a> {
    a: Lhs<'a>,
    structure: Structure,
    b: Rhs<'a>,
    symmetric: bool,
}

impl WithSimd for Job<'_> {
    type Output = Vec<f64>;

    #[inline(always)]
    fn with_simd<S: Simd>(self, simd: S) -> Vec<f64> {
        // Register tiles: MRV vectors of rows × NR columns of accumulators, within the 32
        // (AVX-512) or 16 (AVX2, SSE2) vector registers.
        match S::F64_LANES {
            8 => tiles::<S, 2, 12>(simd, &self),
            4 => tiles::<S, 2, 6>(simd, &self),
            _ => tiles::<S, 2, 4>(simd, &self),
        }
    }
}

/// Columns per tile at the right edge, where fewer than NR are left.
const NARROW: usize = 4;

/// C, one group of columns at a time (NR wide, the last few NARROW wide), each assembled in a
/// scratch panel and appended, so the output is written once and never zero-filled.
#[inline(always)]
fn tiles<S: Simd, const MRV: usize, const NR: usize>(simd: S, job: &Job<'_>) -> Vec<f64> {
    let lanes = S::F64_LANES;
    let (m, k, n) = (job.a.m, job.a.k, job.b.n);
    let main_rows = m / (MRV * lanes) * (MRV * lanes);
    let whole = RowSource {
        data: job.a.data,
        ld: job.a.ld,
        rows: main_rows,
        first: 0,
    };
    let mut c = Vec::with_capacity(m * n);
    // The last rows, padded with zeros to whole vectors, go in tiles of one vector.
    let tail = m - main_rows;
    let ld = tail.div_ceil(lanes) * lanes;
    let mut padded = vec![0.0; ld * k];
    if tail > 0 {
        for (dst, src) in padded.chunks_exact_mut(ld).zip(job.a.data.chunks(job.a.ld)) {
            dst[..tail].copy_from_slice(&src[main_rows..m]);
        }
    }
    let rest = RowSource {
        data: &padded,
        ld,
        rows: tail,
        first: main_rows,
    };
    let mut panel = vec![0.0; m * NR.max(NARROW)];
    let zeros = vec![0.0; k];
    let mut edge = Vec::with_capacity(k * NR);
    let main_cols = n / NR * NR;
    for j0 in (0..main_cols).step_by(NR) {
        let b = tile_b::<NR>(job, j0, NR, &zeros, &mut edge);
        panel_tiles::<S, MRV, NR>(simd, job, whole, &b, j0, &mut panel);
        panel_tiles::<S, 1, NR>(simd, job, rest, &b, j0, &mut panel);
        c.extend_from_slice(&panel[..m * NR]);
    }
    for j0 in (main_cols..n).step_by(NARROW) {
        let width = NARROW.min(n - j0);
        let b = tile_b::<NARROW>(job, j0, width, &zeros, &mut edge);
        panel_tiles::<S, MRV, NARROW>(simd, job, whole, &b, j0, &mut panel);
        panel_tiles::<S, 1, NARROW>(simd, job, rest, &b, j0, &mut panel);
        c.extend_from_slice(&panel[..m * width]);
    }
    c
}

/// B's columns j0 .. j0 + NR, of which the first `width` exist: in place, or padded with zero
/// columns (`zeros` has k values; `edge` is scratch for a padded copy of rows).
fn tile_b<'a, const NR: usize>(
    job: &Job<'a>,
    j0: usize,
    width: usize,
    zeros: &'a [f64],
    edge: &'a mut Vec<f64>,
) -> TileB<'a, NR> {
    let b = job.b;
    match b.layout {
        Layout::Columns => TileB::Columns(std::array::from_fn(|j| {
            let start = (j0 + j) * b.ld;
            if j < width {
                &b.data[start..start + b.k]
            } else {
                zeros
            }
        })),
        // Rows NR wide already: read in place.
        Layout::Rows if width == NR && b.ld == NR => TileB::Rows(&b.data[j0..], b.ld),
        // Otherwise copy the tile's k short rows, each in its own cache lines, to one
        // contiguous block (zero-padded past `width`): read by every row tile, it then streams
        // from the first-level cache.
        Layout::Rows => {
            edge.clear();
            edge.resize(b.k * NR, 0.0);
            for (dst, src) in edge.chunks_exact_mut(NR).zip(b.data[j0..].chunks(b.ld)) {
                dst[..width].copy_from_slice(&src[..width]);
            }
            TileB::Rows(&edge[..], NR)
        }
    }
}

/// The tiles of the rows of `src` against one group of B's columns, written into `panel` (C's
/// columns j0 .. j0 + NR, leading dimension m).
#[inline(always)]
fn panel_tiles<S: Simd, const MRV: usize, const NR: usize>(
    simd: S,
    job: &Job<'_>,
    src: RowSource<'_>,
    b: &TileB<'_, NR>,
    j0: usize,
    panel: &mut [f64],
) {
    let (m, k) = (job.a.m, job.b.k);
    let mr = MRV * S::F64_LANES;
    for i0 in (0..src.rows).step_by(mr) {
        let row = src.first + i0;
        if job.symmetric && j0 >= row + mr {
            continue; // strictly above the diagonal: mirrored afterwards
        }
        let depth = match job.structure {
            Structure::General => 0..k,
            Structure::Lower => 0..(row + mr).min(k),
            Structure::Upper => row..k,
        };
        let acc = match b {
            TileB::Columns(b) => kernel_columns::<S, MRV, NR>(simd, src, i0, depth, b),
            TileB::Rows(b, ld) => kernel_rows::<S, MRV, NR>(simd, src, i0, depth, b, *ld),
        };
        let rows = mr.min(src.rows - i0);
        for (j, acc_col) in acc.iter().enumerate() {
            let out = &mut panel[j * m + row..][..rows];
            for (r, v) in acc_col.iter().enumerate() {
                let lo = r * S::F64_LANES;
                if lo < rows {
                    simd.partial_store_f64s(&mut out[lo..rows.min(lo + S::F64_LANES)], *v);
                }
            }
        }
    }
}

#[cfg(test)]
#[path = "direct_gemm_tests.rs"]
mod tests;
