//! The realism ladder (SPEC §3a): named rungs that set every realism knob at once. `ideal` is the
//! clean world of the first release, kept byte for byte; `urban` (the default) is a street that
//! standard lidar tools can work on; `harsh` has more of everything. A scenario names its rung
//! with `realism = "..."` and may still set any knob of `[world]`, `[sensor]` or `[pose_error]`
//! on its own; `generate --realism NAME` replaces the rung of every scenario it runs.

use serde::{Deserialize, Serialize};

/// A rung of the realism ladder.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Realism {
    /// Flat ground, box shapes, ideal sensor, exact poses: the world of the first release.
    Ideal,
    /// Cambered roads, curbs, sidewalks, uneven terrain, clutter, façade detail, vehicle shapes,
    /// ray drop, mixed pixels, calibration error and a drifting ego pose estimate.
    #[default]
    Urban,
    /// More of each: dense clutter, strong ray drop, larger pose error.
    Harsh,
}

impl Realism {
    /// Every rung, mildest first.
    pub const ALL: [Realism; 3] = [Realism::Ideal, Realism::Urban, Realism::Harsh];

    /// The rung's name as written in scenario files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Ideal => "ideal",
            Self::Urban => "urban",
            Self::Harsh => "harsh",
        }
    }

    /// Parses a rung name (`ideal`, `urban`, `harsh`).
    ///
    /// ```
    /// use patchflow_sim::Realism;
    /// assert_eq!(Realism::parse("harsh"), Some(Realism::Harsh));
    /// assert_eq!(Realism::parse("perfect"), None);
    /// ```
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|r| r.name() == name)
    }
}

impl std::fmt::Display for Realism {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_rung_parses_back_from_its_name() {
        for rung in Realism::ALL {
            assert_eq!(Realism::parse(rung.name()), Some(rung));
        }
    }
}
