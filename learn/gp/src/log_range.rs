//! A positive hyperparameter held smoothly inside a range [lo, hi]: the optimiser moves an
//! unbounded raw value and the parameter's log is c + h·tanh((raw − c)/h), c and h the range's
//! centre and half-width in logs. Near the centre the map is the identity (raw = log value), and
//! the fit is never stuck on a flat bound. Used for a temporal length-scale that the window of
//! scans can identify only inside a range (issue 25).

use crate::{GpError, Result};

/// Smallest distance of a value's squashed log from the range's ends, in half-widths (keeps
/// atanh finite when a starting value lies on or outside the range).
const EDGE: f64 = 1e-9;

/// A range [lo, hi] of a positive value, in logs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LogRange {
    centre: f64,
    half_width: f64,
}

impl LogRange {
    /// The range [lo, hi]; errors unless 0 < lo < hi, both finite.
    pub fn new(lo: f64, hi: f64) -> Result<Self> {
        if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo < hi) {
            return Err(GpError::InvalidParams(format!(
                "a hyperparameter range needs 0 < lo < hi, finite (got {lo} … {hi})"
            )));
        }
        let (a, b) = (lo.ln(), hi.ln());
        Ok(Self {
            centre: 0.5 * (a + b),
            half_width: 0.5 * (b - a),
        })
    }

    /// The range's ends.
    pub fn bounds(&self) -> [f64; 2] {
        [
            (self.centre - self.half_width).exp(),
            (self.centre + self.half_width).exp(),
        ]
    }

    /// log value for the raw optimiser coordinate.
    pub fn log_value(&self, raw: f64) -> f64 {
        self.centre + self.half_width * ((raw - self.centre) / self.half_width).tanh()
    }

    /// d log value / d raw at the log value `log_value` (1 − tanh²).
    pub fn slope_at(&self, log_value: f64) -> f64 {
        let u = (log_value - self.centre) / self.half_width;
        (1.0 - u * u).max(0.0)
    }

    /// The raw coordinate of `log_value` (held just inside the range first).
    pub fn raw(&self, log_value: f64) -> f64 {
        let u = ((log_value - self.centre) / self.half_width).clamp(-1.0 + EDGE, 1.0 - EDGE);
        self.centre + self.half_width * u.atanh()
    }

    /// `value` held inside the range (its nearest end's side, a hair inside).
    pub fn hold(&self, value: f64) -> f64 {
        self.log_value(self.raw(value.ln())).exp()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn any_raw_value_lands_inside_the_range_and_raw_inverts_it() {
        let r = LogRange::new(0.25, 30.0).expect("valid");
        for raw in [-1e6, -40.0, -3.0, 0.0, 1.0, 3.0, 40.0, 1e6] {
            let v = r.log_value(raw).exp();
            // Inside within a relative 1e-12 (exp(ln 30) rounds to 30 + 4e-15).
            assert!(
                (0.25 * (1.0 - 1e-12)..=30.0 * (1.0 + 1e-12)).contains(&v),
                "{raw} -> {v}"
            );
        }
        for v in [0.3_f64, 1.0, 5.0, 29.0] {
            let back = r.log_value(r.raw(v.ln())).exp();
            assert!((back - v).abs() < 1e-9 * v, "{v} -> {back}");
        }
    }

    #[test]
    fn the_slope_matches_a_central_difference_within_1e_6() {
        let r = LogRange::new(0.25, 30.0).expect("valid");
        for raw in [-2.0, 0.5, 2.0, 3.2] {
            let h = 1e-6;
            let fd = (r.log_value(raw + h) - r.log_value(raw - h)) / (2.0 * h);
            let slope = r.slope_at(r.log_value(raw));
            assert!((fd - slope).abs() < 1e-6, "{raw}: {fd} vs {slope}");
        }
    }

    #[test]
    fn values_outside_are_held_inside_and_bad_ranges_are_refused() {
        let r = LogRange::new(0.25, 30.0).expect("valid");
        assert!(r.hold(1e7) <= 30.0 && r.hold(1e7) > 29.9);
        assert!(r.hold(1e-3) >= 0.25 && r.hold(1e-3) < 0.2501);
        assert!(LogRange::new(1.0, 1.0).is_err());
        assert!(LogRange::new(0.0, 1.0).is_err());
        assert!(LogRange::new(1.0, f64::INFINITY).is_err());
    }
}
