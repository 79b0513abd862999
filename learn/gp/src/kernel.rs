//! The kernel abstraction: a covariance function k(x, x') with hyperparameters θ in log
//! coordinates, evaluated and differentiated on sets of points. The GPs (full, SPGP, SPGP-HET,
//! classification) only talk to kernels through [`Kernel`], so a new covariance function is one
//! new type.
//!
//! Everything the fits need is a kernel-level adjoint (gp.md §2.1): given the matrix K = k(A, B)
//! and ∂𝓛/∂K, the kernel returns ∂𝓛/∂θ and, for pseudo-inputs, ∂𝓛/∂A. Kernels that depend on
//! more than the coordinates, such as DGPOM's motion-adapted kernel (a velocity field Υ(x) and an
//! error field ε(x) at each point, paper eq. 2-6), derive that data once per point set in
//! [`Kernel::point_data`] and read it from [`Points::extra`]; they keep the pseudo-inputs fixed,
//! since the derived data is not differentiated.

use std::fmt;

use nalgebra::{DMatrix, DMatrixView, DVector};

use crate::Result;

/// A set of P points stored as the columns of a D×P matrix (contiguous, column-major), with the
/// optional E×P per-point data of [`Kernel::point_data`].
#[derive(Debug, Clone, Copy)]
pub struct Points<'a> {
    coords: &'a [f64],
    dims: usize,
    extra: Option<(&'a [f64], usize)>,
    /// The same coordinates one dimension per column (P×D column-major, columns `ld` apart), if
    /// the owner keeps that copy: products over the points then read them in place.
    by_dim: Option<(&'a [f64], usize)>,
}

impl<'a> Points<'a> {
    /// Points as the columns of `coords` (D×P), with per-point data `extra` (E×P) if any.
    pub fn new(coords: &'a DMatrix<f64>, extra: Option<&'a DMatrix<f64>>) -> Self {
        Self {
            coords: coords.as_slice(),
            dims: coords.nrows(),
            extra: extra.map(|e| (e.as_slice(), e.nrows())),
            by_dim: None,
        }
    }

    /// These points with a copy of their coordinates one dimension per column: `by_dim` is the
    /// P×D column-major matrix of the same values (e.g. the N×D inputs before transposing).
    pub(crate) fn with_by_dim(self, by_dim: &'a DMatrix<f64>) -> Self {
        debug_assert_eq!(by_dim.shape(), (self.len(), self.dims));
        Self {
            by_dim: Some((by_dim.as_slice(), by_dim.nrows())),
            ..self
        }
    }

    /// The coordinates one dimension per column, if kept: (values, distance between columns);
    /// point p's coordinate d is at p + d·ld.
    pub(crate) fn by_dim(&self) -> Option<(&'a [f64], usize)> {
        self.by_dim
    }

    /// Number of points P.
    pub fn len(&self) -> usize {
        self.coords.len().checked_div(self.dims).unwrap_or(0)
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.coords.is_empty()
    }

    /// Input dimension D.
    pub fn dims(&self) -> usize {
        self.dims
    }

    /// The coordinates, one point per column (D×P).
    pub fn coords(&self) -> DMatrixView<'a, f64> {
        DMatrixView::from_slice(self.coords, self.dims, self.len())
    }

    /// The coordinates as a contiguous column-major slice (point p at `p·D .. (p+1)·D`).
    pub fn coord_slice(&self) -> &'a [f64] {
        self.coords
    }

    /// The per-point data of [`Kernel::point_data`], one point per column (E×P).
    pub fn extra(&self) -> Option<DMatrixView<'a, f64>> {
        let p = self.len();
        self.extra
            .map(|(data, rows)| DMatrixView::from_slice(data, rows, p))
    }

    /// The points `start .. start + len`.
    pub fn range(&self, start: usize, len: usize) -> Self {
        let d = self.dims;
        Self {
            coords: &self.coords[start * d..(start + len) * d],
            dims: d,
            extra: self
                .extra
                .map(|(data, rows)| (&data[start * rows..(start + len) * rows], rows)),
            by_dim: self.by_dim.map(|(data, ld)| (&data[start..], ld)),
        }
    }
}

/// A covariance function with hyperparameters θ (logs of positive quantities).
///
/// Implementations must be symmetric (k(a, b) = k(b, a)) and consistent (`diag` is k(x, x)).
pub trait Kernel: Clone + fmt::Debug + Send + Sync {
    /// Number of hyperparameters.
    fn n_params(&self) -> usize;

    /// θ, in the optimiser's coordinates.
    fn params(&self) -> Vec<f64>;

    /// Sets θ (of length [`Kernel::n_params`]).
    fn set_params(&mut self, theta: &[f64]);

    /// Sets the starting point of the evidence maximisation for inputs `xt` (D×N, one sample per
    /// column, standardised unless [`Kernel::standardise_inputs`] says otherwise) and targets of
    /// variance `target_variance`. Errors if the kernel cannot take D inputs.
    fn initialise(&mut self, xt: &DMatrix<f64>, target_variance: f64) -> Result<()>;

    /// The overall scale s of the kernel: the jitter on K_M is relative to it.
    fn signal_variance(&self) -> f64;

    /// Index of log s in θ (the jitter's gradient is added there).
    fn log_signal_variance_index(&self) -> usize;

    /// K = k(a_i, b_j), P×Q.
    fn cross(&self, a: Points<'_>, b: Points<'_>) -> DMatrix<f64>;

    /// k(x, x) for each point.
    fn diag(&self, a: Points<'_>) -> DVector<f64>;

    /// Given K = [`Kernel::cross`]`(a, b)` and the adjoint G = ∂𝓛/∂K (P×Q), returns
    /// Σ_ij G_ij ∂k(a_i, b_j)/∂θ and, if `d_a` (P×D) is given, adds Σ_j G_ij ∂k(a_i, b_j)/∂a_i to
    /// its row i (the derivative in the first argument only).
    fn cross_gradient(
        &self,
        a: Points<'_>,
        b: Points<'_>,
        k: &DMatrix<f64>,
        adjoint: &DMatrix<f64>,
        d_a: Option<&mut DMatrix<f64>>,
    ) -> DVector<f64>;

    /// Σ_i g_i ∂k(x_i, x_i)/∂θ for the adjoint g of [`Kernel::diag`].
    fn diag_gradient(&self, a: Points<'_>, adjoint: &DVector<f64>) -> DVector<f64>;

    /// Per-point data derived once from the coordinates `xt` (D×P), passed back in
    /// [`Points::extra`]; `None` (the default) for kernels of the coordinates alone.
    fn point_data(&self, xt: &DMatrix<f64>) -> Option<DMatrix<f64>> {
        let _ = xt;
        None
    }

    /// Whether the fit standardises each input column first (the default). Kernels whose
    /// structure is tied to physical units, e.g. a motion map in metres, return false.
    fn standardise_inputs(&self) -> bool {
        true
    }
}

/// Points owned in the kernel's layout: coordinates as columns and the kernel's per-point data.
#[derive(Debug, Clone)]
pub(crate) struct OwnedPoints {
    coords: DMatrix<f64>,
    extra: Option<DMatrix<f64>>,
    /// The same points one per row (P×D), for [`Points::by_dim`], if kept.
    rows: Option<DMatrix<f64>>,
}

impl OwnedPoints {
    /// The rows of `x` (P×D) as points of `kernel`.
    pub fn of_rows<K: Kernel>(x: &DMatrix<f64>, kernel: &K) -> Self {
        let coords = x.transpose();
        let extra = kernel.point_data(&coords);
        Self {
            coords,
            extra,
            rows: None,
        }
    }

    /// [`OwnedPoints::of_rows`] keeping a copy of `x` as the points' coordinates by dimension:
    /// for points that are the first argument of covariances (and of their gradients), such as
    /// pseudo-inputs, whose products then read them in place.
    pub fn of_rows_kept<K: Kernel>(x: &DMatrix<f64>, kernel: &K) -> Self {
        Self {
            rows: Some(x.clone()),
            ..Self::of_rows(x, kernel)
        }
    }

    /// A view for the kernel.
    pub fn points(&self) -> Points<'_> {
        let p = Points::new(&self.coords, self.extra.as_ref());
        match &self.rows {
            Some(rows) => p.with_by_dim(rows),
            None => p,
        }
    }
}

/// k(p, p) among a set of points, exactly symmetric with the exact diagonal (for Cholesky).
pub(crate) fn self_covariance<K: Kernel>(kernel: &K, p: Points<'_>) -> DMatrix<f64> {
    let k = kernel.cross(p, p);
    let mut sym = (&k + k.transpose()) * 0.5;
    sym.set_diagonal(&kernel.diag(p));
    sym
}

#[cfg(test)]
#[path = "kernel_tests.rs"]
mod tests;
