//! What every method emits per scan: a heading and speed (with optional variances) for the target.

use nalgebra::{Matrix2, Vector2};
use patchflow_learn::ClusterMotion;
use serde::{Deserialize, Serialize};

/// One method's motion estimate of the target at one scan. A method emits `Option<MotionEstimate>`
/// per scan: `None` means no estimate (no coverage) at that scan.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MotionEstimate {
    /// Heading: direction of the velocity in the ground plane, counter-clockwise from world +x, radians.
    pub heading_rad: f64,
    /// Speed, m/s.
    pub speed_mps: f64,
    /// Velocity in the world frame, m/s.
    pub velocity_xy_mps: [f64; 2],
    /// Variance of the heading, rad², when the method provides one.
    pub heading_var: Option<f64>,
    /// Variance of the speed, (m/s)², when the method provides one.
    pub speed_var: Option<f64>,
}

impl MotionEstimate {
    /// A static decision: zero velocity, facing `heading_rad`. A zero velocity has no direction,
    /// so a method that decides "static" keeps the heading its own motion estimate gives (the
    /// GP's, the track's) rather than the world's +x axis, which would make the per-target
    /// heading score depend on how the world is turned; the decision shows in the speed.
    pub fn at_rest(heading_rad: f64) -> Self {
        Self {
            heading_rad,
            speed_mps: 0.0,
            velocity_xy_mps: [0.0, 0.0],
            heading_var: None,
            speed_var: None,
        }
    }

    /// An estimate from a world-frame velocity, without variances.
    pub fn from_velocity(velocity_xy_mps: [f64; 2]) -> Self {
        let [vx, vy] = velocity_xy_mps;
        Self {
            heading_rad: vy.atan2(vx),
            speed_mps: vx.hypot(vy),
            velocity_xy_mps,
            heading_var: None,
            speed_var: None,
        }
    }

    /// An estimate from a velocity and its 2×2 covariance. Heading and speed variances come from
    /// first-order propagation through `atan2` and the norm (Jacobians `(−vy, vx)/s²` and `(vx, vy)/s`);
    /// at zero speed the heading is undefined, so its variance is `None`.
    pub fn from_velocity_with_covariance(
        velocity_xy_mps: [f64; 2],
        velocity_covariance: Matrix2<f64>,
    ) -> Self {
        let mut estimate = Self::from_velocity(velocity_xy_mps);
        let v = Vector2::new(velocity_xy_mps[0], velocity_xy_mps[1]);
        let speed = estimate.speed_mps;
        if speed > 1e-9 {
            let heading_jacobian = Vector2::new(-v.y, v.x) / (speed * speed);
            let speed_jacobian = v / speed;
            estimate.heading_var =
                Some(heading_jacobian.dot(&(velocity_covariance * heading_jacobian)));
            estimate.speed_var = Some(speed_jacobian.dot(&(velocity_covariance * speed_jacobian)));
        } else {
            // At rest the speed is |v| of a zero-mean Gaussian; use the mean variance per axis.
            estimate.speed_var = Some(velocity_covariance.trace() / 2.0);
        }
        estimate
    }
}

/// A merged cluster motion as the estimate the tables score.
pub(crate) fn to_estimate(motion: ClusterMotion) -> MotionEstimate {
    let (s, c) = motion.heading_rad.sin_cos();
    MotionEstimate {
        heading_rad: motion.heading_rad,
        speed_mps: motion.speed_mps,
        velocity_xy_mps: [motion.speed_mps * c, motion.speed_mps * s],
        heading_var: Some(motion.heading_var),
        speed_var: Some(motion.speed_var),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heading_and_speed_follow_from_the_velocity() {
        let e = MotionEstimate::from_velocity([0.0, -3.0]);
        assert!((e.heading_rad + std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!((e.speed_mps - 3.0).abs() < 1e-12);
    }

    #[test]
    fn isotropic_velocity_noise_gives_heading_variance_sigma_squared_over_speed_squared() {
        let e =
            MotionEstimate::from_velocity_with_covariance([4.0, 3.0], Matrix2::identity() * 0.25);
        assert!((e.heading_var.unwrap() - 0.25 / 25.0).abs() < 1e-12);
        assert!((e.speed_var.unwrap() - 0.25).abs() < 1e-12);
    }
}
