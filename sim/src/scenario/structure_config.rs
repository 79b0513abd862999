//! One `[[structures]]` entry: a static box (building, wall, fence, pole, parked car), or a row of them.

use patchflow_dataset::SemanticClass;
use serde::{Deserialize, Serialize};

use super::bounds::{COORD_M, MAX_ROW_BOXES, SIZE_M, SPACING_M, YAW_DEG, reflectivity_problem};

/// What a static structure is; sets its label, default size and reflectivity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StructureKind {
    /// A building block (default 20 × 12 × 10 m).
    Building,
    /// A wall (default 10 × 0.3 × 2.5 m).
    Wall,
    /// A fence (default 10 × 0.1 × 1.5 m).
    Fence,
    /// A pole (default 0.25 × 0.25 × 5 m).
    Pole,
    /// A parked car (default 4.5 × 1.8 × 1.45 m), part of the static world (instance 0).
    ParkedCar,
    /// A raised sidewalk slab (default 10 × 3 × 0.15 m).
    Sidewalk,
}

/// A static box, or with `repeat_to_m` a row of equal boxes from `centre_m` to `repeat_to_m`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StructureConfig {
    /// What it is.
    pub kind: StructureKind,
    /// Ground-plane centre of the (first) box, metres.
    pub centre_m: [f64; 2],
    /// Length (along yaw), width, height, metres (default per kind).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size_m: Option<[f64; 3]>,
    /// Yaw of the box's length axis, degrees counter-clockwise from +x.
    #[serde(default)]
    pub yaw_deg: f64,
    /// Centre of the last box of a row; boxes are placed every `spacing_m` from `centre_m` towards it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub repeat_to_m: Option<[f64; 2]>,
    /// Distance between the centres of a row's boxes, metres (default: the box length plus 1 m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spacing_m: Option<f64>,
    /// Lidar reflectivity in [0, 1] (default per kind).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reflectivity: Option<f64>,
}

impl StructureKind {
    /// Default size: length, width, height.
    pub(crate) fn default_size(self) -> [f64; 3] {
        match self {
            Self::Building => [20.0, 12.0, 10.0],
            Self::Wall => [10.0, 0.3, 2.5],
            Self::Fence => [10.0, 0.1, 1.5],
            Self::Pole => [0.25, 0.25, 5.0],
            Self::ParkedCar => [4.5, 1.8, 1.45],
            Self::Sidewalk => [10.0, 3.0, 0.15],
        }
    }

    /// Default lidar reflectivity.
    pub(crate) fn default_reflectivity(self) -> f64 {
        match self {
            Self::Building => 0.45,
            Self::Wall => 0.5,
            Self::Fence => 0.4,
            Self::Pole => 0.6,
            Self::ParkedCar => 0.55,
            Self::Sidewalk => 0.25,
        }
    }

    /// SemanticKITTI class of its points.
    pub(crate) fn semantic(self) -> SemanticClass {
        match self {
            Self::Building => SemanticClass::Building,
            Self::Wall | Self::Fence => SemanticClass::Fence,
            Self::Pole => SemanticClass::Pole,
            Self::ParkedCar => SemanticClass::Car,
            Self::Sidewalk => SemanticClass::Sidewalk,
        }
    }
}

impl StructureConfig {
    /// Fills size, spacing and reflectivity with their defaults; on a world whose `fleet` knob is
    /// on, a parked car without `size_m` keeps none (each car's body is drawn when the world is
    /// built, `VehicleBody`) and a row of them is spaced by the default size.
    pub(crate) fn resolve(&mut self, fleet: bool) {
        let size = if fleet && self.kind == StructureKind::ParkedCar {
            self.size_m.unwrap_or(self.kind.default_size())
        } else {
            *self.size_m.get_or_insert(self.kind.default_size())
        };
        if self.repeat_to_m.is_some() {
            self.spacing_m.get_or_insert(size[0] + 1.0);
        }
        self.reflectivity
            .get_or_insert(self.kind.default_reflectivity());
    }

    /// Number of boxes this entry stands for (one, or a row), from the row's length and spacing
    /// alone, so a row too long to build is caught before it is built.
    pub(crate) fn box_count(&self) -> u64 {
        let Some(end) = self.repeat_to_m else {
            return 1;
        };
        let length = (end[0] - self.centre_m[0]).hypot(end[1] - self.centre_m[1]);
        let spacing = self.spacing_m.unwrap_or(1.0).max(1e-3);
        // Float-to-integer casts saturate (and map NaN to 0), so this cannot overflow.
        ((length / spacing + 1e-9).floor() as u64).saturating_add(1)
    }

    /// The centres of every box this entry stands for (one, or a row); call on a validated
    /// scenario, whose rows hold at most `bounds::MAX_ROW_BOXES` boxes.
    pub fn centres_m(&self) -> Vec<[f64; 2]> {
        let Some(end) = self.repeat_to_m else {
            return vec![self.centre_m];
        };
        let (dx, dy) = (end[0] - self.centre_m[0], end[1] - self.centre_m[1]);
        let length = dx.hypot(dy);
        let spacing = self.spacing_m.unwrap_or(1.0).max(1e-3);
        let count = self.box_count().min(MAX_ROW_BOXES) as usize;
        (0..count)
            .map(|i| {
                let f = if length > 0.0 {
                    i as f64 * spacing / length
                } else {
                    0.0
                };
                [self.centre_m[0] + f * dx, self.centre_m[1] + f * dy]
            })
            .collect()
    }

    /// Reasons this entry is impossible, each with the offending field's name (call after
    /// `resolve`); the number of boxes is checked with the other derived sizes.
    pub(crate) fn problems(&self) -> Vec<(&'static str, String)> {
        let mut out = Vec::new();
        out.extend(COORD_M.check_each("centre_m", &self.centre_m));
        if let Some(size) = &self.size_m {
            out.extend(SIZE_M.check_each("size_m", size));
        }
        out.extend(YAW_DEG.check("yaw_deg", self.yaw_deg));
        if let Some(end) = &self.repeat_to_m {
            out.extend(COORD_M.check_each("repeat_to_m", end));
        }
        if let Some(s) = self.spacing_m {
            out.extend(SPACING_M.check("spacing_m", s));
        }
        out.extend(reflectivity_problem(self.reflectivity));
        out
    }
}
