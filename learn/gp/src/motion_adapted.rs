//! DGPOM's motion-adapted covariance (O'Callaghan & Ramos, eqs. 2-6) over inputs (x, y, t):
//!
//! k(x̂, x̂') = s · exp(−½ Σ_d (ẑ_d − ẑ'_d)²/ℓ_d²) · k_t(|t − t'|; l_t(x), l_t(x')),
//!
//! - the spatial squared exponential (eq. 2) compares the two observations after carrying them
//!   along the motion map Υ to one reference time t_r: ẑ = x + ψ(t, t_r, x) (eq. 4, integrated with
//!   fixed Runge-Kutta steps, [`transported`]);
//! - the temporal part is the non-stationary Matérn 3/2 of eq. 5 with the local temporal
//!   length-scale l_t(x) = a · ε(x)^(−1/b) of eq. 6, ε the motion map's error field; a and b are
//!   learned with ℓ and s by maximising the marginal likelihood.
//!
//! Why a common reference time: eq. 2 compares x̂ with A x̂', i.e. x with x' carried from t' to t.
//! For a uniform velocity that is |x − x' − v(t − t')|, exactly what ẑ − ẑ' gives. For a velocity
//! that varies in space, carrying x' to t is not the same as carrying x to t', so eq. 2 read
//! literally is not symmetric (and need not be positive definite), which a GP covariance must be.
//! Carrying both to t_r keeps eq. 2's zero-distance set (a particle's path) and makes the kernel a
//! squared exponential of a feature map, hence symmetric and positive semidefinite. With t_r the
//! query time, a query point is compared with each observation carried forward to it: eq. 2 as
//! printed, for every prediction.
//!
//! The motion map enters through per-point data ([`Kernel::point_data`]: ẑ and log ε, derived once
//! per point set), so inputs stay in metres and seconds (no standardisation) and the pseudo-inputs
//! of a sparse GP stay fixed. θ = (log ℓ_x, log ℓ_y, log s, log a, log b).

use std::sync::Arc;

use nalgebra::DMatrix;

use super::kernel::Points;
use super::motion_field::{MotionField, transported};
use super::nonstationary_matern::nonstationary_matern32;
use crate::{GpError, Result};

/// Largest magnitude of a log-parameter and of log l_t; keeps exp() finite.
pub(crate) const LOG_LIMIT: f64 = 30.0;
/// Smallest error the field may report, m/s (ε^(−1/b) stays finite).
pub(crate) const MIN_ERROR_MPS: f64 = 1e-6;
/// Default integration step of the flow lines, seconds.
const DEFAULT_STEP_SECS: f64 = 0.1;
/// Starting spatial length-scale, metres (a car's width).
pub(crate) const START_LENGTHSCALE_M: f64 = 1.0;
/// Starting temporal length-scale at the median error, seconds.
pub(crate) const START_TIME_SCALE_SECS: f64 = 2.0;

/// The motion-adapted spatio-temporal kernel over (x m, y m, t s).
#[derive(Debug)]
pub struct MotionAdapted<F> {
    pub(crate) field: Arc<F>,
    pub(crate) reference_secs: f64,
    pub(crate) step_secs: f64,
    pub(crate) lengthscales_m: [f64; 2],
    pub(crate) signal_variance: f64,
    pub(crate) time_scale_a: f64,
    pub(crate) decay_b: f64,
    /// log l_t is held inside this range (what the observations' time span can identify).
    pub(crate) log_temporal_range: [f64; 2],
}

impl<F> Clone for MotionAdapted<F> {
    fn clone(&self) -> Self {
        Self {
            field: Arc::clone(&self.field),
            ..*self
        }
    }
}

/// One input as the kernel sees it: carried position, time, log error, and at the current a, b
/// its l_t (seconds) with the slope of log l_t by the unbounded log a·ε^(−1/b) (computed once per
/// point, not per pair).
#[derive(Clone, Copy)]
pub(crate) struct Carried {
    z: [f64; 2],
    t: f64,
    log_error: f64,
    lt: f64,
    slope: f64,
}

impl<F: MotionField> MotionAdapted<F> {
    /// The kernel for motion map `field`, carrying observations to `reference_secs` (the query
    /// time of the map), with starting values that a fit replaces.
    pub fn new(field: Arc<F>, reference_secs: f64) -> Self {
        Self {
            field,
            reference_secs,
            step_secs: DEFAULT_STEP_SECS,
            lengthscales_m: [START_LENGTHSCALE_M; 2],
            signal_variance: 1.0,
            time_scale_a: START_TIME_SCALE_SECS,
            decay_b: 1.0,
            log_temporal_range: [-LOG_LIMIT, LOG_LIMIT],
        }
    }

    /// Holds l_t(x) inside (`lo`, `hi`) seconds (default: unbounded but for exp()'s range):
    /// beyond the span of the observations' times every longer l_t means "no decay" and the
    /// marginal likelihood cannot tell them apart. log l_t is squashed smoothly into the range
    /// (a tanh of the unbounded log l_t about the range's centre). Errors unless 0 < lo < hi,
    /// both finite.
    pub fn temporal_range_secs(mut self, lo: f64, hi: f64) -> Result<Self> {
        if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo < hi) {
            return Err(GpError::InvalidParams(format!(
                "temporal length-scale range must satisfy 0 < lo < hi, got [{lo}, {hi}]"
            )));
        }
        self.log_temporal_range = [lo.ln().max(-LOG_LIMIT), hi.ln().min(LOG_LIMIT)];
        Ok(self)
    }

    /// The integration step of the flow lines (default 0.1 s).
    pub fn step_secs(mut self, step_secs: f64) -> Self {
        self.step_secs = step_secs;
        self
    }

    /// Sets (ℓ_x, ℓ_y) in metres, s, a and b; errors unless all are positive and finite.
    pub fn with_values(
        mut self,
        lengthscales_m: [f64; 2],
        signal_variance: f64,
        time_scale_a: f64,
        decay_b: f64,
    ) -> Result<Self> {
        let values = [
            lengthscales_m[0],
            lengthscales_m[1],
            signal_variance,
            time_scale_a,
            decay_b,
        ];
        if !values.iter().all(|v| v.is_finite() && *v > 0.0) {
            return Err(GpError::InvalidParams(format!(
                "motion-adapted kernel values must be positive and finite, got {values:?}"
            )));
        }
        self.lengthscales_m = lengthscales_m;
        self.signal_variance = signal_variance;
        self.time_scale_a = time_scale_a;
        self.decay_b = decay_b;
        Ok(self)
    }

    /// Spatial length-scales (ℓ_x, ℓ_y), metres.
    pub fn lengthscales_m(&self) -> [f64; 2] {
        self.lengthscales_m
    }

    /// a of eq. 6.
    pub fn time_scale_a(&self) -> f64 {
        self.time_scale_a
    }

    /// b of eq. 6.
    pub fn decay_b(&self) -> f64 {
        self.decay_b
    }

    /// The reference time the observations are carried to, seconds.
    pub fn reference_secs(&self) -> f64 {
        self.reference_secs
    }

    /// The motion map.
    pub fn field(&self) -> &F {
        &self.field
    }

    /// l_t = a · ε^(−1/b) (eq. 6) for an error of `error_mps`, seconds.
    pub fn temporal_lengthscale_secs(&self, error_mps: f64) -> f64 {
        self.log_temporal(error_mps.max(MIN_ERROR_MPS).ln()).0.exp()
    }

    /// log l_t for log ε and its derivative by the unbounded a·ε^(−1/b)'s log. Without a range,
    /// clamped to exp()'s range (derivative 0 outside); with one, squashed smoothly into it by
    /// c + h·tanh((raw − c)/h) (c, h the range's centre and half-width in logs), so the fit is
    /// never stuck on a flat bound.
    fn log_temporal(&self, log_error: f64) -> (f64, f64) {
        let raw = self.time_scale_a.ln() - log_error / self.decay_b;
        let [lo, hi] = self.log_temporal_range;
        if lo <= -LOG_LIMIT && hi >= LOG_LIMIT {
            let inside = raw.abs() <= LOG_LIMIT;
            return (
                raw.clamp(-LOG_LIMIT, LOG_LIMIT),
                f64::from(u8::from(inside)),
            );
        }
        let (c, h) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        let th = ((raw - c) / h).tanh();
        (c + h * th, 1.0 - th * th)
    }

    /// The carried inputs of `p`, from its per-point data or, if it has none, derived now.
    pub(crate) fn carried(&self, p: Points<'_>) -> Vec<Carried> {
        let coords = p.coord_slice();
        let own;
        let extra = match p.extra() {
            Some(e) => e,
            None => {
                own = self.derive(&p.coords().into_owned());
                own.as_view()
            }
        };
        (0..p.len())
            .map(|i| {
                let log_error = extra[(2, i)];
                let (log_lt, slope) = self.log_temporal(log_error);
                Carried {
                    z: [extra[(0, i)], extra[(1, i)]],
                    t: coords[i * 3 + 2],
                    log_error,
                    lt: log_lt.exp(),
                    slope,
                }
            })
            .collect()
    }

    /// Per point (column of `xt`, 3×P): ẑ carried to the reference time and log ε at x.
    pub(crate) fn derive(&self, xt: &DMatrix<f64>) -> DMatrix<f64> {
        let mut out = DMatrix::zeros(3, xt.ncols());
        for (col, p) in out.column_iter_mut().zip(xt.column_iter()) {
            let xy = [p[0], p[1]];
            let z = transported(&*self.field, xy, p[2], self.reference_secs, self.step_secs);
            let mut col = col;
            col[0] = z[0];
            col[1] = z[1];
            col[2] = self.field.error_mps(xy).max(MIN_ERROR_MPS).ln();
        }
        out
    }

    /// k and its θ-gradient for one pair: (k, [∂/∂log ℓ_x, ∂/∂log ℓ_y, ∂/∂log s, ∂/∂log a,
    /// ∂/∂log b]).
    pub(crate) fn pair(&self, p: &Carried, q: &Carried, with_gradient: bool) -> (f64, [f64; 5]) {
        let [lx, ly] = self.lengthscales_m;
        let (rx, ry) = (
            ((p.z[0] - q.z[0]) / lx).powi(2),
            ((p.z[1] - q.z[1]) / ly).powi(2),
        );
        let se = self.signal_variance * (-0.5 * (rx + ry)).exp();
        let (kt, dp, dq) = nonstationary_matern32(p.t - q.t, p.lt, q.lt);
        let k = se * kt;
        if !with_gradient {
            return (k, [0.0; 5]);
        }
        // log l_t = log a − log ε / b: ∂/∂log a = 1, ∂/∂log b = log ε / b.
        let (dp, dq) = (dp * p.slope, dq * q.slope);
        let b = self.decay_b;
        (
            k,
            [
                k * rx,
                k * ry,
                k,
                se * (dp + dq),
                se * (dp * p.log_error + dq * q.log_error) / b,
            ],
        )
    }
}

#[cfg(test)]
#[path = "motion_adapted_tests.rs"]
mod tests;
