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

pub(crate) use super::gemm_operands::{Layout, Lhs, Rhs, Structure};
use super::tile_kernel::{RowSource, TileB, kernel_columns, kernel_rows};

/// C = A·B, skipping A's zero half when `structure` says it is triangular.
pub(crate) fn product(a: Lhs<'_>, structure: Structure, b: Rhs<'_>) -> DMatrix<f64> {
    product_then(a, structure, b, |_, _| {})
}

/// C = A·B, with `epilogue(j0, columns)` applied to each group of C's columns j0 .. (all m rows,
/// column-major) while it is still in the first-level cache, before it is stored: a sweep over
/// the columns of C (an elementwise function, column norms and scalings) fused into the product.
/// The epilogue runs in the vectorised context; pass an `#[inline(always)]` closure.
pub(crate) fn product_then<F: FnMut(usize, &mut [f64])>(
    a: Lhs<'_>,
    structure: Structure,
    b: Rhs<'_>,
    epilogue: F,
) -> DMatrix<f64> {
    let (m, n) = (a.m, b.n);
    DMatrix::from_vec(m, n, run(a, structure, b, false, Output::Keep(epilogue)))
}

/// Hands each group of C = A·B's columns to `consume(j0, columns)` (as in [`product_then`])
/// without storing C, for a consumer that keeps only what it derives from it.
pub(crate) fn product_consumed<F: FnMut(usize, &mut [f64])>(
    a: Lhs<'_>,
    structure: Structure,
    b: Rhs<'_>,
    consume: F,
) {
    run(a, structure, b, false, Output::Drop(consume));
}

/// C = A·B for a product known to be symmetric (e.g. Ṽ diag(w) Ṽᵀ): the lower tiles are computed
/// and mirrored, so C is exactly symmetric.
pub(crate) fn symmetric_product(a: Lhs<'_>, structure: Structure, b: Rhs<'_>) -> DMatrix<f64> {
    let m = a.m;
    let mut c = DMatrix::from_vec(
        m,
        b.n,
        run(
            a,
            structure,
            b,
            true,
            Output::Keep(|_: usize, _: &mut [f64]| {}),
        ),
    );
    for j in 1..m {
        for i in 0..j {
            c[(i, j)] = c[(j, i)];
        }
    }
    c
}

/// What becomes of each group of C's columns once its tiles are done.
enum Output<F> {
    /// The epilogue runs on it, then it is stored.
    Keep(F),
    /// The consumer reads it; nothing is stored.
    Drop(F),
}

fn run<F: FnMut(usize, &mut [f64])>(
    a: Lhs<'_>,
    structure: Structure,
    b: Rhs<'_>,
    symmetric: bool,
    output: Output<F>,
) -> Vec<f64> {
    let (m, k, n) = (a.m, a.k, b.n);
    debug_assert_eq!(k, b.k, "inner dimensions differ");
    debug_assert!(
        structure == Structure::General || m == k,
        "a triangular A is square"
    );
    debug_assert!(!symmetric || m == n, "a symmetric product is square");
    if m == 0 || n == 0 || k == 0 {
        // C is zero: the epilogue still sees every column.
        let mut c = vec![0.0; m * n];
        match output {
            Output::Keep(mut f) | Output::Drop(mut f) => {
                for (j0, col) in c.chunks_exact_mut(m.max(1)).enumerate() {
                    f(j0, col);
                }
            }
        }
        return c;
    }
    let job = Job {
        a,
        structure,
        b,
        symmetric,
        output,
    };
    pulp::Arch::new().dispatch(job)
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
        output: Output::Keep(|_: usize, _: &mut [f64]| {}),
    };
    DMatrix::from_vec(a.m, b.n, simd.vectorize(job))
}

/// A product, as dispatched to the widest instruction set; it returns C's values column-major
/// (nothing for [`Output::Drop`]).
struct Job<'a, F> {
    a: Lhs<'a>,
    structure: Structure,
    b: Rhs<'a>,
    symmetric: bool,
    output: Output<F>,
}

impl<F: FnMut(usize, &mut [f64])> WithSimd for Job<'_, F> {
    type Output = Vec<f64>;

    #[inline(always)]
    fn with_simd<S: Simd>(mut self, simd: S) -> Vec<f64> {
        // Register tiles: MRV vectors of rows × NR columns of accumulators, within the 32
        // (AVX-512) or 16 (AVX2, SSE2) vector registers.
        match S::F64_LANES {
            8 => tiles::<S, 2, 12, F>(simd, &mut self),
            4 => tiles::<S, 2, 6, F>(simd, &mut self),
            _ => tiles::<S, 2, 4, F>(simd, &mut self),
        }
    }
}

/// Columns per tile at the right edge, where fewer than NR are left.
const NARROW: usize = 4;

/// C, one group of columns at a time (NR wide, the last few NARROW wide), each assembled in a
/// scratch panel, passed through the epilogue and appended, so the output is written once and
/// never zero-filled.
#[inline(always)]
fn tiles<S: Simd, const MRV: usize, const NR: usize, F: FnMut(usize, &mut [f64])>(
    simd: S,
    job: &mut Job<'_, F>,
) -> Vec<f64> {
    let lanes = S::F64_LANES;
    let (m, k, n) = (job.a.m, job.a.k, job.b.n);
    let main_rows = m / (MRV * lanes) * (MRV * lanes);
    let whole = RowSource {
        data: job.a.data,
        ld: job.a.ld,
        rows: main_rows,
        first: 0,
    };
    let keep = matches!(job.output, Output::Keep(_));
    let mut c = Vec::with_capacity(if keep { m * n } else { 0 });
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
        let b = tile_b::<NR, F>(job, j0, NR, &zeros, &mut edge);
        panel_tiles::<S, MRV, NR, F>(simd, job, whole, &b, j0, &mut panel);
        panel_tiles::<S, 1, NR, F>(simd, job, rest, &b, j0, &mut panel);
        finish(&mut job.output, j0, &mut panel[..m * NR], &mut c);
    }
    for j0 in (main_cols..n).step_by(NARROW) {
        let width = NARROW.min(n - j0);
        let b = tile_b::<NARROW, F>(job, j0, width, &zeros, &mut edge);
        panel_tiles::<S, MRV, NARROW, F>(simd, job, whole, &b, j0, &mut panel);
        panel_tiles::<S, 1, NARROW, F>(simd, job, rest, &b, j0, &mut panel);
        finish(&mut job.output, j0, &mut panel[..m * width], &mut c);
    }
    c
}

/// Runs the epilogue (or consumer) on one finished group of columns and stores it if kept.
#[inline(always)]
fn finish<F: FnMut(usize, &mut [f64])>(
    output: &mut Output<F>,
    j0: usize,
    columns: &mut [f64],
    c: &mut Vec<f64>,
) {
    match output {
        Output::Keep(f) => {
            f(j0, columns);
            c.extend_from_slice(columns);
        }
        Output::Drop(f) => f(j0, columns),
    }
}

/// B's columns j0 .. j0 + NR, of which the first `width` exist: in place, or padded with zero
/// columns (`zeros` has k values; `edge` is scratch for a padded copy of rows).
fn tile_b<'a, const NR: usize, F>(
    job: &Job<'a, F>,
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
fn panel_tiles<S: Simd, const MRV: usize, const NR: usize, F>(
    simd: S,
    job: &Job<'_, F>,
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
            // Whole vectors as plain stores (pulp's partial store is an out-of-line call), the
            // ragged end as a partial one.
            let (whole, rest) = S::as_mut_simd_f64s(out);
            for (dst, v) in whole.iter_mut().zip(acc_col) {
                *dst = *v;
            }
            if let (false, Some(v)) = (rest.is_empty(), acc_col.get(whole.len())) {
                simd.partial_store_f64s(rest, *v);
            }
        }
    }
}

#[cfg(test)]
#[path = "direct_gemm_tests.rs"]
mod tests;
