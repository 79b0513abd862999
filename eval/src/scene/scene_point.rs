//! The points the whole-scene evaluation scores: every height-sliced point of a scan inside the
//! map window (the points every method sees), with its true displacement over the sweep interval,
//! its class and its actor.

use patchflow_dataset::{PointLabel, Sweep};
use patchflow_learn::SweepFeatures;
use serde::{Deserialize, Serialize};

/// What a point belongs to, for the foreground / background split of Argoverse 2 and the
/// per-class buckets of the normalised EPE: road users are foreground, the rest background.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FlowClass {
    /// Road, sidewalk, buildings, fences, poles, vegetation.
    Background,
    /// Cars, parked or moving (SemanticKITTI 10, 252).
    Car,
    /// Trucks (18, 258).
    Truck,
    /// Pedestrians (30, 254).
    Pedestrian,
    /// Cyclists (31, 253).
    Cyclist,
}

impl FlowClass {
    /// Every class, in index order.
    pub const ALL: [Self; 5] = [
        Self::Background,
        Self::Car,
        Self::Truck,
        Self::Pedestrian,
        Self::Cyclist,
    ];

    /// The class of a point label (its SemanticKITTI id, moving or not).
    pub fn of_label(label: PointLabel) -> Self {
        match label.semantic() {
            10 | 252 => Self::Car,
            18 | 258 => Self::Truck,
            30 | 254 => Self::Pedestrian,
            31 | 253 => Self::Cyclist,
            _ => Self::Background,
        }
    }

    /// Whether points of this class are foreground (road users).
    pub fn is_foreground(self) -> bool {
        self != Self::Background
    }

    /// Position in [`Self::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// Lower-case name for reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Background => "background",
            Self::Car => "car",
            Self::Truck => "truck",
            Self::Pedestrian => "pedestrian",
            Self::Cyclist => "cyclist",
        }
    }
}

/// The scored points of one scan, parallel to `features.points()`.
#[derive(Debug, Clone, PartialEq)]
pub struct ScenePoints {
    /// Time since the previous sweep, seconds: the interval the displacements span.
    pub dt_secs: f64,
    /// World x, y of each point.
    pub xy: Vec<[f64; 2]>,
    /// True displacement over the interval, world frame, metres (the dataset's `flow/` velocity
    /// times `dt_secs`; displacement norms do not depend on the frame).
    pub truth_m: Vec<[f64; 3]>,
    /// Class of each point.
    pub class: Vec<FlowClass>,
    /// Actor id of each point (0 for the static world).
    pub actor: Vec<u16>,
}

impl ScenePoints {
    /// The sliced points of `features` with the truth of the sweep they were cut from.
    pub fn new(features: &SweepFeatures, sweep: &Sweep, dt_secs: f64) -> Self {
        let n = features.len();
        let mut out = Self {
            dt_secs,
            xy: Vec::with_capacity(n),
            truth_m: Vec::with_capacity(n),
            class: Vec::with_capacity(n),
            actor: Vec::with_capacity(n),
        };
        for p in features.points() {
            let v = sweep.flow_in_world_mps[p.index].map(f64::from);
            let label = sweep.labels[p.index];
            out.xy.push([p.x_m, p.y_m]);
            out.truth_m.push(v.map(|v| v * dt_secs));
            out.class.push(FlowClass::of_label(label));
            out.actor.push(label.instance());
        }
        out
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.xy.len()
    }

    /// A world-frame ground-plane velocity as a displacement over the interval.
    pub fn displacement_of(&self, velocity_xy_mps: [f64; 2]) -> [f64; 3] {
        [
            velocity_xy_mps[0] * self.dt_secs,
            velocity_xy_mps[1] * self.dt_secs,
            0.0,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use patchflow_dataset::SemanticClass;

    #[test]
    fn road_users_are_foreground_moving_or_not_and_the_rest_background() {
        let of = |c: SemanticClass| FlowClass::of_label(PointLabel::new(c, 3));
        assert_eq!(of(SemanticClass::Car), FlowClass::Car);
        assert_eq!(of(SemanticClass::MovingCar), FlowClass::Car);
        assert_eq!(of(SemanticClass::MovingTruck), FlowClass::Truck);
        assert_eq!(of(SemanticClass::MovingBicyclist), FlowClass::Cyclist);
        assert_eq!(of(SemanticClass::Person), FlowClass::Pedestrian);
        for c in [
            SemanticClass::Building,
            SemanticClass::Pole,
            SemanticClass::Road,
        ] {
            assert!(!of(c).is_foreground());
        }
        assert!(
            FlowClass::ALL
                .iter()
                .enumerate()
                .all(|(i, c)| c.index() == i)
        );
    }
}
