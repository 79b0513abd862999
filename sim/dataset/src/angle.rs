//! The one home of angle wrapping, in the lowest crate that needs it (the simulator and the
//! evaluation both depend on the dataset vocabulary; the occupancy maps too).
//!
//! Two conventions live here because both are in outputs whose bytes must not change: the
//! simulator's headings (written into every dataset) use (−π, π], the scores and maps use
//! [−π, π). The two differ only at ±π and in the last bit of some results.

use std::f64::consts::{PI, TAU};

/// An angle wrapped to [−π, π): heading errors, bearings, plots.
///
/// ```
/// use patchflow_dataset::wrap_angle_rad;
/// assert!((wrap_angle_rad(3.0 * std::f64::consts::PI) + std::f64::consts::PI).abs() < 1e-12);
/// ```
pub fn wrap_angle_rad(angle_rad: f64) -> f64 {
    (angle_rad + PI).rem_euclid(TAU) - PI
}

/// An angle wrapped to (−π, π]: the simulator's path headings and yaw rates.
pub fn wrap_angle_upper_rad(angle_rad: f64) -> f64 {
    let mut a = angle_rad.rem_euclid(TAU);
    if a > PI {
        a -= TAU;
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_wraps_agree_inside_the_circle_to_1e12_and_differ_only_at_pi() {
        for k in -40..=40 {
            let a = f64::from(k) * 0.37;
            let (lower, upper) = (wrap_angle_rad(a), wrap_angle_upper_rad(a));
            assert!((lower - upper).abs() < 1e-12, "{a}: {lower} vs {upper}");
            assert!((-PI..PI).contains(&lower));
            assert!(((a - lower) / TAU - ((a - lower) / TAU).round()).abs() < 1e-12);
        }
        assert_eq!(wrap_angle_rad(PI), -PI);
        assert_eq!(wrap_angle_upper_rad(PI), PI);
    }
}
