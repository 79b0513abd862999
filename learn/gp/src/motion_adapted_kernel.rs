//! [`Kernel`] for DGPOM's motion-adapted covariance ([`MotionAdapted`]): θ in log coordinates,
//! the covariance and its θ-gradient pair by pair over parallel column blocks (each block's sums
//! reduced in block order, so results do not depend on the number of threads), and the per-point
//! data (carried position, log error) derived once per point set.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use super::kernel::{Kernel, Points};
use super::motion_adapted::{
    LOG_LIMIT, MIN_ERROR_MPS, MotionAdapted, START_LENGTHSCALE_M, START_TIME_SCALE_SECS,
};
use super::motion_field::MotionField;
use crate::{GpError, Result};

/// Output columns per parallel task.
const COLUMNS_PER_TASK: usize = 64;

/// Whether `a` and `b` are the very same point set (k(a, b) is then symmetric).
fn same_points(a: Points<'_>, b: Points<'_>) -> bool {
    let (x, y) = (a.coord_slice(), b.coord_slice());
    x.len() == y.len() && std::ptr::eq(x.as_ptr(), y.as_ptr()) && a.dims() == b.dims()
}

/// Copies the upper triangle of the square `k` onto its lower triangle.
fn mirror_upper(k: &mut DMatrix<f64>) {
    let n = k.nrows();
    for j in 0..n {
        for i in j + 1..n {
            k[(i, j)] = k[(j, i)];
        }
    }
}

impl<F: MotionField> Kernel for MotionAdapted<F> {
    fn n_params(&self) -> usize {
        5
    }

    fn params(&self) -> Vec<f64> {
        let [lx, ly] = self.lengthscales_m;
        [
            lx,
            ly,
            self.signal_variance,
            self.time_scale_a,
            self.decay_b,
        ]
        .iter()
        .map(|v| v.ln())
        .collect()
    }

    fn set_params(&mut self, theta: &[f64]) {
        let ex = |x: f64| x.clamp(-LOG_LIMIT, LOG_LIMIT).exp();
        self.lengthscales_m = [ex(theta[0]), ex(theta[1])];
        self.signal_variance = ex(theta[2]);
        self.time_scale_a = ex(theta[3]);
        self.decay_b = ex(theta[4]);
    }

    fn initialise(&mut self, xt: &DMatrix<f64>, target_variance: f64) -> Result<()> {
        if xt.nrows() != 3 {
            return Err(GpError::InvalidParams(format!(
                "the motion-adapted kernel takes inputs (x, y, t), got {} columns",
                xt.nrows()
            )));
        }
        // a so that l_t is START_TIME_SCALE_SECS at the median error, with b = 1.
        let mut errors: Vec<f64> = xt
            .column_iter()
            .map(|p| self.field.error_mps([p[0], p[1]]).max(MIN_ERROR_MPS))
            .collect();
        errors.sort_by(f64::total_cmp);
        let median = errors.get(errors.len() / 2).copied().unwrap_or(1.0);
        self.lengthscales_m = [START_LENGTHSCALE_M; 2];
        self.signal_variance = target_variance.max(1e-2);
        self.decay_b = 1.0;
        self.time_scale_a = START_TIME_SCALE_SECS * median;
        Ok(())
    }

    fn signal_variance(&self) -> f64 {
        self.signal_variance
    }

    fn log_signal_variance_index(&self) -> usize {
        2
    }

    fn cross(&self, a: Points<'_>, b: Points<'_>) -> DMatrix<f64> {
        let (ca, cb) = (self.carried(a), self.carried(b));
        let mut k = DMatrix::zeros(ca.len(), cb.len());
        let rows = ca.len().max(1);
        // k(a, a) is symmetric: each column up to the diagonal, then mirrored.
        let same = same_points(a, b);
        k.as_mut_slice()
            .par_chunks_mut(rows * COLUMNS_PER_TASK)
            .enumerate()
            .for_each(|(task, chunk)| {
                for (j, col) in chunk.chunks_mut(rows).enumerate() {
                    let column = task * COLUMNS_PER_TASK + j;
                    let q = &cb[column];
                    let upto = if same { column + 1 } else { rows };
                    for (v, p) in col[..upto].iter_mut().zip(&ca) {
                        *v = self.pair(p, q, false).0;
                    }
                }
            });
        if same {
            mirror_upper(&mut k);
        }
        k
    }

    fn diag(&self, a: Points<'_>) -> DVector<f64> {
        DVector::from_element(a.len(), self.signal_variance)
    }

    /// The θ-gradient. The coordinates enter only through the per-point data, which is not
    /// differentiated, so `d_a` gets nothing: such kernels run with fixed pseudo-inputs.
    fn cross_gradient(
        &self,
        a: Points<'_>,
        b: Points<'_>,
        _k: &DMatrix<f64>,
        adjoint: &DMatrix<f64>,
        _d_a: Option<&mut DMatrix<f64>>,
    ) -> DVector<f64> {
        let (ca, cb) = (self.carried(a), self.carried(b));
        let rows = ca.len().max(1);
        // Over one point set the pair terms are symmetric: Σ_ij G_ij ∂k_ij = Σ_{i≤j} W_ij ∂k_ij
        // with W = G + Gᵀ off the diagonal and G on it, so half the pairs are evaluated.
        let same = same_points(a, b);
        let folded;
        let weights = if same {
            let mut w = adjoint + adjoint.transpose();
            for i in 0..w.nrows() {
                w[(i, i)] *= 0.5;
            }
            folded = w;
            &folded
        } else {
            adjoint
        };
        let partial: Vec<[f64; 5]> = weights
            .as_slice()
            .par_chunks(rows * COLUMNS_PER_TASK)
            .enumerate()
            .map(|(task, chunk)| {
                let mut acc = [0.0; 5];
                for (j, col) in chunk.chunks(rows).enumerate() {
                    let column = task * COLUMNS_PER_TASK + j;
                    let q = &cb[column];
                    let upto = if same { column + 1 } else { rows };
                    for (g, p) in col[..upto].iter().zip(&ca) {
                        let (_, d) = self.pair(p, q, true);
                        for (s, dv) in acc.iter_mut().zip(d) {
                            *s += g * dv;
                        }
                    }
                }
                acc
            })
            .collect();
        let mut grad = DVector::zeros(5);
        for acc in partial {
            for (g, v) in grad.iter_mut().zip(acc) {
                *g += v;
            }
        }
        grad
    }

    fn diag_gradient(&self, a: Points<'_>, adjoint: &DVector<f64>) -> DVector<f64> {
        let _ = a;
        let mut grad = DVector::zeros(5);
        grad[2] = self.signal_variance * adjoint.sum();
        grad
    }

    fn point_data(&self, xt: &DMatrix<f64>) -> Option<DMatrix<f64>> {
        Some(self.derive(xt))
    }

    fn standardise_inputs(&self) -> bool {
        false
    }
}
