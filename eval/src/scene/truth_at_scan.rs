//! The true motion of the object a table scores at one scan (the target, or any actor).

use serde::{Deserialize, Serialize};

/// The target's true motion at one scan.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TruthAtScan {
    /// Scan number within the situation.
    pub scan: usize,
    /// True heading, radians, counter-clockwise from world +x.
    pub heading_rad: f64,
    /// True speed, m/s.
    pub speed_mps: f64,
    /// True velocity, world frame, m/s.
    pub velocity_xy_mps: [f64; 2],
    /// Distance sensor → target centre in the ground plane, metres, when known; the report
    /// breaks the heading error down by it (the height slice thins out with range).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range_m: Option<f64>,
    /// Sliced points in the target's cluster (what ICP and the GP estimators see), when known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target_points: Option<usize>,
    /// How many ends of the target's cluster (smallest and largest bearing) a nearer return hides,
    /// when known: 2 is a target seen through a gap, a car crossing behind parked cars, whose
    /// motion along itself no difference map shows (`patchflow_learn::RangeProfile`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target_hidden_ends: Option<usize>,
}

impl TruthAtScan {
    /// Truth from a world-frame velocity (heading and speed derived from it).
    pub fn from_velocity(scan: usize, velocity_xy_mps: [f64; 2]) -> Self {
        let [vx, vy] = velocity_xy_mps;
        Self {
            scan,
            heading_rad: vy.atan2(vx),
            speed_mps: vx.hypot(vy),
            velocity_xy_mps,
            range_m: None,
            target_points: None,
            target_hidden_ends: None,
        }
    }
}
