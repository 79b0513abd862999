//! The operands of the packing-free products ([`super::direct_gemm`]): a column-major left
//! operand A read in place, a right operand B in either of its layouts, and the structure
//! (general or triangular) of A.

use nalgebra::DMatrix;

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
    pub(crate) data: &'a [f64],
    pub(crate) k: usize,
    pub(crate) n: usize,
    pub(crate) ld: usize,
    pub(crate) layout: Layout,
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
    pub(crate) data: &'a [f64],
    pub(crate) m: usize,
    pub(crate) k: usize,
    pub(crate) ld: usize,
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
