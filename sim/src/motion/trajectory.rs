//! An actor's motion: a smooth path driven with a speed profile. Pose, velocity, heading and yaw
//! rate come in closed form at any time t (never by finite differences).

use super::{Path, SpeedProfile};
use patchflow_dataset::wrap_angle_upper_rad;

/// The exact motion state of a box following its path at one instant (ground plane, world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionState {
    /// Box centre in the ground plane, metres.
    pub position_m: [f64; 2],
    /// Yaw of the box's long axis (the path tangent), counter-clockwise from +x.
    pub yaw_rad: f64,
    /// Velocity of the box centre, m/s.
    pub velocity_mps: [f64; 2],
    /// |velocity|, m/s.
    pub speed_mps: f64,
    /// Direction of the velocity (equals the yaw, also when standing still).
    pub heading_rad: f64,
    /// Yaw rate = curvature × speed, counter-clockwise positive, rad/s.
    pub yaw_rate_radps: f64,
}

impl MotionState {
    /// Velocity of a point `p` rigidly attached to the box: v + ω × (p − c), ground plane.
    pub fn velocity_at_mps(&self, p: [f64; 2]) -> [f64; 2] {
        let (rx, ry) = (p[0] - self.position_m[0], p[1] - self.position_m[1]);
        [
            self.velocity_mps[0] - self.yaw_rate_radps * ry,
            self.velocity_mps[1] + self.yaw_rate_radps * rx,
        ]
    }
}

/// Speed from which an actor counts as moving (moving SemanticKITTI classes), m/s.
pub const MOVING_SPEED_MPS: f64 = 0.05;

/// A path and a speed profile.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    path: Path,
    profile: SpeedProfile,
}

impl Trajectory {
    /// Builds a trajectory from its parts.
    pub fn new(path: Path, profile: SpeedProfile) -> Self {
        Self { path, profile }
    }

    /// The exact state at time `t_secs`.
    pub fn state_at(&self, t_secs: f64) -> MotionState {
        let progress = self.profile.at(t_secs);
        let point = self.path.at(progress.s_m);
        let (sin, cos) = point.heading_rad.sin_cos();
        MotionState {
            position_m: point.position_m,
            yaw_rad: wrap_angle_upper_rad(point.heading_rad),
            velocity_mps: [progress.speed_mps * cos, progress.speed_mps * sin],
            speed_mps: progress.speed_mps,
            heading_rad: wrap_angle_upper_rad(point.heading_rad),
            yaw_rate_radps: point.curvature_per_m * progress.speed_mps,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn velocity_and_yaw_rate_match_the_change_of_pose() {
        let path = Path::new(&[[0.0, 0.0], [30.0, 0.0], [30.0, 30.0]], 6.0).unwrap();
        let trajectory = Trajectory::new(path, SpeedProfile::new(0.0, 2.0, 9.0, 2.0, &[]));
        let h = 1e-5;
        for i in 0..80 {
            let t = i as f64 * 0.1;
            let (a, b, now) = (
                trajectory.state_at(t - h),
                trajectory.state_at(t + h),
                trajectory.state_at(t),
            );
            let vx = (b.position_m[0] - a.position_m[0]) / (2.0 * h);
            let vy = (b.position_m[1] - a.position_m[1]) / (2.0 * h);
            assert!(
                (vx - now.velocity_mps[0]).abs() < 1e-4 && (vy - now.velocity_mps[1]).abs() < 1e-4,
                "velocity at t = {t}"
            );
            let yaw_rate = wrap_angle_upper_rad(b.yaw_rad - a.yaw_rad) / (2.0 * h);
            // Skip the instants where an arc meets a straight (the curvature steps there).
            if (a.yaw_rate_radps - b.yaw_rate_radps).abs() < 1e-3 {
                assert!(
                    (yaw_rate - now.yaw_rate_radps).abs() < 1e-4,
                    "yaw rate at t = {t}"
                );
            }
        }
    }

    #[test]
    fn a_point_ahead_of_a_left_turning_box_moves_left() {
        let state = MotionState {
            position_m: [0.0, 0.0],
            yaw_rad: 0.0,
            velocity_mps: [5.0, 0.0],
            speed_mps: 5.0,
            heading_rad: 0.0,
            yaw_rate_radps: 0.5,
        };
        let v = state.velocity_at_mps([2.0, 0.0]);
        assert!((v[0] - 5.0).abs() < 1e-12 && (v[1] - 1.0).abs() < 1e-12);
    }
}
