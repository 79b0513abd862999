//! The `[pose_error]` table: the ego's localisation error (GPS/INS-like, slowly drifting). The
//! points are ego-motion-compensated with the estimated pose and the estimate is written to
//! `poses_estimated.txt`; `poses.txt` stays the truth. Knobs default to the realism rung.

use serde::{Deserialize, Serialize};

use super::bounds::Bound;
use super::realism::Realism;

/// Pose-error knobs, as written in a scenario file.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoseErrorConfig {
    /// Std of the horizontal position error along each axis, metres (0: exact poses).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position_std_m: Option<f64>,
    /// Std of the heading (yaw) error, degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yaw_std_deg: Option<f64>,
    /// Typical time over which the error drifts by about one std, seconds.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drift_secs: Option<f64>,
}

/// The resolved `[pose_error]` knobs as plain values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoseErrorKnobs {
    /// See [`PoseErrorConfig::position_std_m`].
    pub position_std_m: f64,
    /// See [`PoseErrorConfig::yaw_std_deg`].
    pub yaw_std_deg: f64,
    /// See [`PoseErrorConfig::drift_secs`].
    pub drift_secs: f64,
}

impl PoseErrorKnobs {
    /// The knobs of a rung.
    pub fn of(rung: Realism) -> Self {
        match rung {
            Realism::Ideal => Self {
                position_std_m: 0.0,
                yaw_std_deg: 0.0,
                drift_secs: 30.0,
            },
            Realism::Urban => Self {
                position_std_m: 0.3,
                yaw_std_deg: 0.3,
                drift_secs: 30.0,
            },
            Realism::Harsh => Self {
                position_std_m: 1.0,
                yaw_std_deg: 1.0,
                drift_secs: 20.0,
            },
        }
    }

    /// True if the ego knows its pose exactly.
    pub fn exact(&self) -> bool {
        self.position_std_m == 0.0 && self.yaw_std_deg == 0.0
    }
}

impl PoseErrorConfig {
    /// Fills every missing knob from `rung`.
    pub(crate) fn resolve(&mut self, rung: Realism) {
        let k = PoseErrorKnobs::of(rung);
        self.position_std_m.get_or_insert(k.position_std_m);
        self.yaw_std_deg.get_or_insert(k.yaw_std_deg);
        self.drift_secs.get_or_insert(k.drift_secs);
    }

    /// The knobs as plain values (those still missing from the `urban` rung).
    pub fn knobs(&self) -> PoseErrorKnobs {
        let k = PoseErrorKnobs::of(Realism::Urban);
        PoseErrorKnobs {
            position_std_m: self.position_std_m.unwrap_or(k.position_std_m),
            yaw_std_deg: self.yaw_std_deg.unwrap_or(k.yaw_std_deg),
            drift_secs: self.drift_secs.unwrap_or(k.drift_secs),
        }
    }

    /// Every knob outside its range, with the field's name.
    pub(crate) fn problems(&self) -> Vec<(&'static str, String)> {
        let k = self.knobs();
        [
            POSITION_STD_M.check("position_std_m", k.position_std_m),
            YAW_STD_DEG.check("yaw_std_deg", k.yaw_std_deg),
            DRIFT_SECS.check("drift_secs", k.drift_secs),
        ]
        .into_iter()
        .flatten()
        .collect()
    }
}

// Documented in scenarios/README.md ("The realism ladder"); change both together.

/// Horizontal position error (std per axis).
const POSITION_STD_M: Bound = Bound::new(
    0.0,
    10.0,
    "m",
    "from RTK to a poor GPS fix in a street canyon",
);
/// Heading error (std).
const YAW_STD_DEG: Bound = Bound::new(0.0, 10.0, "°", "from a good INS to a bare compass");
/// Drift time of the error.
const DRIFT_SECS: Bound = Bound::new(1.0, 3600.0, "s", "a second to an hour");
