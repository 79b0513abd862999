//! Per-sweep ground truth of one actor: pose, size and exact motion in the world frame.

use serde::{Deserialize, Serialize};

use crate::SemanticClass;

/// What kind of actor an object is. Cars come in several sizes; the class does not fix the size.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ActorClass {
    /// A passenger car (compact to van size).
    Car,
    /// A truck.
    Truck,
    /// A pedestrian.
    Pedestrian,
    /// A bicyclist.
    Cyclist,
}

impl ActorClass {
    /// The SemanticKITTI class of this actor, moving or not.
    pub fn semantic(self, moving: bool) -> SemanticClass {
        match (self, moving) {
            (Self::Car, false) => SemanticClass::Car,
            (Self::Car, true) => SemanticClass::MovingCar,
            (Self::Truck, false) => SemanticClass::Truck,
            (Self::Truck, true) => SemanticClass::MovingTruck,
            (Self::Pedestrian, false) => SemanticClass::Person,
            (Self::Pedestrian, true) => SemanticClass::MovingPerson,
            (Self::Cyclist, false) => SemanticClass::Bicyclist,
            (Self::Cyclist, true) => SemanticClass::MovingBicyclist,
        }
    }
}

/// Ground truth of one actor at a sweep's reference time, world frame (z up, metres, radians).
///
/// `heading_rad` is the direction of the ground-plane velocity, counter-clockwise from world +x;
/// for an actor standing still it equals `yaw_rad`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectTruth {
    /// Actor id; equals the instance id in the high 16 bits of its points' labels (never 0).
    pub id: u16,
    /// The actor's name in the scenario file.
    pub name: String,
    /// Actor class.
    pub class: ActorClass,
    /// True for the one actor a situation marks as the benchmark target.
    pub target: bool,
    /// True if the actor moves at this instant (speed at least 0.05 m/s); decides moving vs static ids.
    pub moving: bool,
    /// Centre of the bounding box, world frame.
    pub centre_m: [f64; 3],
    /// Box size: length (along yaw), width, height.
    pub size_m: [f64; 3],
    /// Yaw of the box's long axis, counter-clockwise from world +x.
    pub yaw_rad: f64,
    /// Velocity of the box centre, world frame.
    pub velocity_mps: [f64; 3],
    /// |velocity| in the ground plane.
    pub speed_mps: f64,
    /// Direction of the ground-plane velocity, counter-clockwise from world +x.
    pub heading_rad: f64,
    /// Yaw rate, counter-clockwise positive.
    pub yaw_rate_radps: f64,
    /// Number of lidar points on this actor in this sweep.
    pub point_count: u32,
}

/// Fastest an object may move, m/s: far above any road user (a record car is below 150 m/s).
pub const MAX_OBJECT_SPEED_MPS: f64 = 1000.0;

/// Largest object box side, metres: far above any vehicle (a road train is about 50 m).
pub const MAX_OBJECT_SIZE_M: f64 = 1000.0;
/// Fastest yaw rate an object may have, rad/s (a car turning hard stays below 3).
const MAX_YAW_RATE_RADPS: f64 = 1000.0;
/// Largest yaw or heading magnitude, radians (they are written within ±π).
const MAX_ANGLE_RAD: f64 = 1000.0;

impl ObjectTruth {
    /// What is wrong with this record, if anything: an id of 0 (the static world's instance) or
    /// a value that is not finite.
    pub fn problem(&self) -> Option<String> {
        if self.id == 0 {
            return Some(format!(
                "object {:?} has id 0, which is the static world",
                self.name
            ));
        }
        let values = self
            .centre_m
            .iter()
            .chain(&self.size_m)
            .chain(&self.velocity_mps)
            .chain([
                &self.yaw_rad,
                &self.speed_mps,
                &self.heading_rad,
                &self.yaw_rate_radps,
            ]);
        let finite = values.clone().all(|v| v.is_finite());
        let sized = self.size_m.iter().all(|v| *v > 0.0) && self.speed_mps >= 0.0;
        // hypot: a velocity of 4e250 m/s is named as such, not as "inf".
        let velocity = self.velocity_mps.iter().fold(0.0f64, |a, v| a.hypot(*v));
        if finite && (velocity > MAX_OBJECT_SPEED_MPS || self.speed_mps > MAX_OBJECT_SPEED_MPS) {
            return Some(format!(
                "object {} ({:?}) moves at {:e} m/s, more than the {MAX_OBJECT_SPEED_MPS} m/s any road user reaches",
                self.id,
                self.name,
                velocity.max(self.speed_mps)
            ));
        }
        let huge = |what: &str, v: f64, limit: f64, unit: &str| {
            (v.abs() > limit).then(|| {
                format!(
                    "object {} ({:?}) has {what} {v:e} {unit}, beyond the ±{limit} {unit} any road user has",
                    self.id, self.name
                )
            })
        };
        let absurd = self
            .size_m
            .iter()
            .find_map(|&v| huge("a size of", v, MAX_OBJECT_SIZE_M, "m"))
            .or_else(|| {
                huge(
                    "a yaw rate of",
                    self.yaw_rate_radps,
                    MAX_YAW_RATE_RADPS,
                    "rad/s",
                )
            })
            .or_else(|| huge("a yaw of", self.yaw_rad, MAX_ANGLE_RAD, "rad"))
            .or_else(|| huge("a heading of", self.heading_rad, MAX_ANGLE_RAD, "rad"));
        if finite && let Some(reason) = absurd {
            return Some(reason);
        }
        let far = self
            .centre_m
            .iter()
            .any(|v| v.abs() > crate::MAX_COORDINATE_M);
        if finite && far {
            return Some(format!(
                "object {} ({:?}) is centred {:?} m from the origin, beyond the ±{} m a dataset spans",
                self.id,
                self.name,
                self.centre_m,
                crate::MAX_COORDINATE_M
            ));
        }
        (!finite || !sized).then(|| {
            format!(
                "object {} ({:?}) has a value that is not finite, a size that is not positive or a negative speed",
                self.id, self.name
            )
        })
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn an_object_faster_than_any_road_user_is_refused() {
        let mut sweep = crate::reader::tests::sample_sweep(0);
        sweep.objects[0].velocity_mps = [0.0, 4e250, 0.0];
        let reason = sweep.objects[0].problem().unwrap();
        assert!(reason.contains("4e250 m/s"), "{reason}");
    }

    #[test]
    fn an_astronomical_size_yaw_rate_or_heading_is_refused_naming_the_field() {
        let base = crate::reader::tests::sample_sweep(0).objects[0].clone();
        type Edit = fn(&mut super::ObjectTruth);
        let cases: [(&str, Edit); 4] = [
            ("size", |o| o.size_m[1] = 3e200),
            ("yaw rate", |o| o.yaw_rate_radps = -1e250),
            ("yaw", |o| o.yaw_rad = 7e120),
            ("heading", |o| o.heading_rad = 1e300),
        ];
        for (field, edit) in cases {
            let mut object = base.clone();
            edit(&mut object);
            let reason = object.problem().unwrap();
            assert!(
                reason.contains(field) && reason.contains("e"),
                "{field}: {reason}"
            );
        }
        assert_eq!(base.problem(), None);
    }
}
