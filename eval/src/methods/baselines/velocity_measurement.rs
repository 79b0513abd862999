//! The GP's merged heading and speed as a velocity measurement for a Kalman filter (thesis 3.1.4:
//! the merged prediction is a Gaussian in heading and speed), for `GP-KF`.
//!
//! `v = s·(cos h, sin h)`; its covariance by first-order propagation,
//! `Σ_v = J diag(σ_s², σ_h²) Jᵀ`, `J = [[cos h, −s sin h], [sin h, s cos h]]`. The merged
//! variances are products over hundreds of points that are far from independent, so they are
//! floored (`min_heading_std_rad`, `min_speed_std_mps`) before they enter the filter; a cluster the
//! moving classifier calls static is measured at rest with the speed floor.

use nalgebra::Matrix2;

use crate::error::EvalError;

/// A velocity measured directly, with its covariance, world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityMeasurement {
    /// Measured velocity, m/s.
    pub velocity_xy_mps: [f64; 2],
    /// Its covariance, (m/s)².
    pub covariance: Matrix2<f64>,
}

/// Floors of the GP's variances when they become filter measurements.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityFloors {
    /// Smallest heading standard deviation, radians.
    pub min_heading_std_rad: f64,
    /// Smallest speed standard deviation, m/s.
    pub min_speed_std_mps: f64,
}

impl Default for VelocityFloors {
    /// 10° and 1 m/s: about the GPs' heading and speed RMSE on the targets (docs/results.md).
    fn default() -> Self {
        Self {
            min_heading_std_rad: 10f64.to_radians(),
            min_speed_std_mps: 1.0,
        }
    }
}

impl VelocityFloors {
    /// Checks that both floors are positive and finite.
    pub fn validate(&self) -> Result<(), EvalError> {
        for (name, value) in [
            (
                "VelocityFloors.min_heading_std_rad",
                self.min_heading_std_rad,
            ),
            ("VelocityFloors.min_speed_std_mps", self.min_speed_std_mps),
        ] {
            if !(value > 0.0 && value.is_finite()) {
                return Err(EvalError::BadParameter {
                    name,
                    reason: format!("must be positive and finite, got {value}"),
                });
            }
        }
        Ok(())
    }
}

impl VelocityMeasurement {
    /// The measurement of a merged heading and speed with their variances.
    pub fn from_heading_speed(
        heading_rad: f64,
        heading_var: f64,
        speed_mps: f64,
        speed_var: f64,
        floors: &VelocityFloors,
    ) -> Self {
        let (s, c) = heading_rad.sin_cos();
        let speed = speed_mps.max(0.0);
        let heading_var = heading_var.max(floors.min_heading_std_rad.powi(2));
        let speed_var = speed_var.max(floors.min_speed_std_mps.powi(2));
        let j = Matrix2::new(c, -speed * s, s, speed * c);
        let d = Matrix2::new(speed_var, 0.0, 0.0, heading_var);
        Self {
            velocity_xy_mps: [speed * c, speed * s],
            covariance: j * d * j.transpose(),
        }
    }

    /// A measurement at rest, `min_speed_std_mps` per axis.
    pub fn at_rest(floors: &VelocityFloors) -> Self {
        Self {
            velocity_xy_mps: [0.0, 0.0],
            covariance: Matrix2::identity() * floors.min_speed_std_mps.powi(2),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_measured_velocity_points_along_the_heading_with_the_speed() {
        let m = VelocityMeasurement::from_heading_speed(
            std::f64::consts::FRAC_PI_2,
            0.0,
            5.0,
            0.0,
            &VelocityFloors::default(),
        );
        assert!(m.velocity_xy_mps[0].abs() < 1e-12 && (m.velocity_xy_mps[1] - 5.0).abs() < 1e-12);
    }

    #[test]
    fn speed_variance_lies_along_the_heading_and_heading_variance_across_it() {
        let floors = VelocityFloors::default();
        let m = VelocityMeasurement::from_heading_speed(0.0, 0.04, 10.0, 4.0, &floors);
        assert!((m.covariance[(0, 0)] - 4.0).abs() < 1e-9);
        assert!((m.covariance[(1, 1)] - 100.0 * 0.04).abs() < 1e-9);
        // Tiny GP variances are floored.
        let tight = VelocityMeasurement::from_heading_speed(0.0, 1e-9, 10.0, 1e-9, &floors);
        assert!((tight.covariance[(0, 0)] - 1.0).abs() < 1e-9);
    }
}
