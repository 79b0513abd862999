//! The GP's merged heading and speed as a velocity measurement for a Kalman filter (thesis 3.1.4:
//! the merged prediction is a Gaussian in heading and speed), for `GP-KF`.
//!
//! `v = s·(cos h, sin h)`; its covariance by first-order propagation,
//! `Σ_v = J diag(σ_s², σ_h²) Jᵀ`, `J = [[cos h, −s sin h], [sin h, s cos h]]`. The merged
//! variances are products over hundreds of points that are far from independent, so they are
//! floored (`min_heading_std_rad`, `min_speed_std_mps`) before they enter the filter; a cluster the
//! moving classifier calls static is measured at rest with the speed floor.
//!
//! Why a persistent part: the GP's error on one object is not white. It reads the same car from
//! the same side through the same clutter scan after scan, so a heading 30° off in one scan is
//! 30° off in the next (`docs/results.md`, issue 27's traces). Fused as independent measurements,
//! twenty such scans outvote the centroids' evidence however wide each one's variance. The error
//! is therefore modelled as white noise plus a first-order Gauss-Markov error that persists over
//! `persistence_secs` (correlated measurement noise by state augmentation: Gelb, *Applied Optimal
//! Estimation*, 1974, §4.5; Bar-Shalom et al. 2001, §8.3). The filter carries that error as two
//! more states ([`crate::ConstantVelocityKalman::update_velocity`]); the centroids tell it apart
//! from the velocity, and the GP's scan-to-scan changes still count in full.

use nalgebra::Matrix2;

use crate::error::EvalError;

/// A velocity measured directly, with its covariance, world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityMeasurement {
    /// Measured velocity, m/s.
    pub velocity_xy_mps: [f64; 2],
    /// Covariance of its white (scan-to-scan) error, (m/s)².
    pub covariance: Matrix2<f64>,
    /// Covariance of its persistent error, (m/s)²: the measuring GP's error that carries over
    /// from scan to scan (zero: none).
    pub persistent_covariance: Matrix2<f64>,
    /// Correlation time of the persistent error, seconds.
    pub persistence_secs: f64,
}

/// How much of the GP's heading and speed error is white and how much persists.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GpVelocityNoise {
    /// Smallest white heading standard deviation, radians.
    pub min_heading_std_rad: f64,
    /// Smallest white speed standard deviation, m/s.
    pub min_speed_std_mps: f64,
    /// Standard deviation of the persistent heading error, radians.
    pub persistent_heading_std_rad: f64,
    /// Standard deviation of the persistent speed error, m/s.
    pub persistent_speed_std_mps: f64,
    /// Correlation time of the persistent error, seconds.
    pub persistence_secs: f64,
}

impl Default for GpVelocityNoise {
    /// White: 10° and 1 m/s floors. Persistent: 20° and 0.5 m/s, about the GP's heading and speed
    /// RMSE on the situations' targets (docs/results.md), lasting 3 s, the time a passing car
    /// takes to change the side it shows.
    fn default() -> Self {
        Self {
            min_heading_std_rad: 10f64.to_radians(),
            min_speed_std_mps: 1.0,
            persistent_heading_std_rad: 20f64.to_radians(),
            persistent_speed_std_mps: 0.5,
            persistence_secs: 3.0,
        }
    }
}

impl GpVelocityNoise {
    /// Checks that the floors and the persistence are positive and finite and the persistent
    /// standard deviations finite and not negative.
    pub fn validate(&self) -> Result<(), EvalError> {
        let checks: [(&'static str, f64, bool); 5] = [
            (
                "GpVelocityNoise.min_heading_std_rad",
                self.min_heading_std_rad,
                true,
            ),
            (
                "GpVelocityNoise.min_speed_std_mps",
                self.min_speed_std_mps,
                true,
            ),
            (
                "GpVelocityNoise.persistence_secs",
                self.persistence_secs,
                true,
            ),
            (
                "GpVelocityNoise.persistent_heading_std_rad",
                self.persistent_heading_std_rad,
                false,
            ),
            (
                "GpVelocityNoise.persistent_speed_std_mps",
                self.persistent_speed_std_mps,
                false,
            ),
        ];
        for (name, value, positive) in checks {
            let ok = value.is_finite() && if positive { value > 0.0 } else { value >= 0.0 };
            if !ok {
                let wanted = if positive { "positive" } else { "not negative" };
                return Err(EvalError::BadParameter {
                    name,
                    reason: format!("must be {wanted} and finite, got {value}"),
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
        noise: &GpVelocityNoise,
    ) -> Self {
        let (s, c) = heading_rad.sin_cos();
        let speed = speed_mps.max(0.0);
        let heading_var = heading_var.max(noise.min_heading_std_rad.powi(2));
        let speed_var = speed_var.max(noise.min_speed_std_mps.powi(2));
        let j = Matrix2::new(c, -speed * s, s, speed * c);
        let along_across = |speed_var: f64, heading_var: f64| {
            j * Matrix2::new(speed_var, 0.0, 0.0, heading_var) * j.transpose()
        };
        Self {
            velocity_xy_mps: [speed * c, speed * s],
            covariance: along_across(speed_var, heading_var),
            persistent_covariance: along_across(
                noise.persistent_speed_std_mps.powi(2),
                noise.persistent_heading_std_rad.powi(2),
            ),
            persistence_secs: noise.persistence_secs,
        }
    }

    /// A measurement at rest, `min_speed_std_mps` per axis, with no persistent error.
    pub fn at_rest(noise: &GpVelocityNoise) -> Self {
        Self {
            velocity_xy_mps: [0.0, 0.0],
            covariance: Matrix2::identity() * noise.min_speed_std_mps.powi(2),
            persistent_covariance: Matrix2::zeros(),
            persistence_secs: noise.persistence_secs,
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
            &GpVelocityNoise::default(),
        );
        assert!(m.velocity_xy_mps[0].abs() < 1e-12 && (m.velocity_xy_mps[1] - 5.0).abs() < 1e-12);
    }

    #[test]
    fn speed_variance_lies_along_the_heading_and_heading_variance_across_it() {
        let noise = GpVelocityNoise::default();
        let m = VelocityMeasurement::from_heading_speed(0.0, 0.04, 10.0, 4.0, &noise);
        assert!((m.covariance[(0, 0)] - 4.0).abs() < 1e-9);
        assert!((m.covariance[(1, 1)] - 100.0 * 0.04).abs() < 1e-9);
        // Tiny GP variances are floored.
        let tight = VelocityMeasurement::from_heading_speed(0.0, 1e-9, 10.0, 1e-9, &noise);
        assert!((tight.covariance[(0, 0)] - 1.0).abs() < 1e-9);
    }

    #[test]
    fn the_persistent_error_lies_along_and_across_the_heading_like_the_white_one() {
        let noise = GpVelocityNoise::default();
        let m = VelocityMeasurement::from_heading_speed(0.0, 0.04, 10.0, 4.0, &noise);
        let across = 10.0 * noise.persistent_heading_std_rad;
        assert!((m.persistent_covariance[(0, 0)] - 0.25).abs() < 1e-9);
        assert!((m.persistent_covariance[(1, 1)] - across * across).abs() < 1e-9);
        assert!(m.persistent_covariance[(0, 1)].abs() < 1e-9);
    }

    #[test]
    fn a_negative_persistent_error_is_refused_by_name() {
        let noise = GpVelocityNoise {
            persistent_heading_std_rad: -0.1,
            ..GpVelocityNoise::default()
        };
        let error = noise.validate().unwrap_err().to_string();
        assert!(error.contains("persistent_heading_std_rad"), "{error}");
    }
}
