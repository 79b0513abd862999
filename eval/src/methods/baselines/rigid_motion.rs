//! A cluster's motion from ICP (thesis 3.2.1): the displacement of its centroid under the transform
//! that aligns the cluster at t−1 with the cluster at t, and the same transform applied to every
//! point for per-point scene flow.

use nalgebra::{Isometry2, Point2};

use crate::methods::baselines::icp::{IcpAlignment, IcpParams, align_icp, align_icp_from};
use crate::methods::estimate::MotionEstimate;
use crate::methods::observation::centroid_of;

/// ICP motion estimate of a cluster seen at t−1 (`previous`) and t (`current`), `dt_secs` apart.
pub fn icp_motion_estimate(
    previous: &[[f64; 2]],
    current: &[[f64; 2]],
    dt_secs: f64,
    params: &IcpParams,
) -> Option<MotionEstimate> {
    icp_rigid_motion(previous, current, dt_secs, params).map(|m| m.estimate)
}

/// What ICP says about a cluster seen at t−1 and t: the object's motion (its centroid's
/// displacement) and the rigid transform that moves every one of its points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidMotion {
    /// Heading and speed from the source centroid's displacement.
    pub estimate: MotionEstimate,
    /// The alignment found.
    pub alignment: IcpAlignment,
    /// Time between the two scans, seconds.
    pub dt_secs: f64,
}

impl RigidMotion {
    /// Velocity of a point of the current scan: where the transform says it came from, to where
    /// it is, over the interval (`(p − T⁻¹p) / Δt`), world frame, m/s.
    pub fn velocity_of_current_point(&self, xy: [f64; 2]) -> [f64; 2] {
        let p = Point2::new(xy[0], xy[1]);
        let from = self
            .alignment
            .target_from_source
            .inverse_transform_point(&p);
        [(p.x - from.x) / self.dt_secs, (p.y - from.y) / self.dt_secs]
    }
}

/// [`icp_motion_estimate`] with the transform kept, so it can move every point of the cluster.
pub fn icp_rigid_motion(
    previous: &[[f64; 2]],
    current: &[[f64; 2]],
    dt_secs: f64,
    params: &IcpParams,
) -> Option<RigidMotion> {
    if dt_secs <= 0.0 || !dt_secs.is_finite() {
        return None;
    }
    let alignment = align_icp(previous, current, params)?;
    rigid_motion_of(previous, alignment, dt_secs)
}

/// [`icp_rigid_motion`] started from a known velocity (`GP-ICP`: the GP's merged heading and
/// speed): the initial transform moves the cluster at t−1 by `velocity × Δt`.
pub fn icp_rigid_motion_from(
    previous: &[[f64; 2]],
    current: &[[f64; 2]],
    dt_secs: f64,
    initial_velocity_xy_mps: [f64; 2],
    params: &IcpParams,
) -> Option<RigidMotion> {
    if dt_secs <= 0.0 || !dt_secs.is_finite() {
        return None;
    }
    let [vx, vy] = initial_velocity_xy_mps;
    let initial = Isometry2::translation(vx * dt_secs, vy * dt_secs);
    let alignment = align_icp_from(previous, current, initial, params)?;
    rigid_motion_of(previous, alignment, dt_secs)
}

/// The motion an alignment of `previous` describes over `dt_secs`.
fn rigid_motion_of(
    previous: &[[f64; 2]],
    alignment: IcpAlignment,
    dt_secs: f64,
) -> Option<RigidMotion> {
    let finite_previous: Vec<[f64; 2]> = previous
        .iter()
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .copied()
        .collect();
    let centroid = centroid_of(&finite_previous)?;
    Some(RigidMotion {
        estimate: MotionEstimate::from_velocity(alignment.velocity_of(centroid, dt_secs)),
        alignment,
        dt_secs,
    })
}
