//! SemanticKITTI semantic ids and the packed per-point label (semantic id low 16 bits, instance high 16).

use serde::{Deserialize, Serialize};

/// The SemanticKITTI classes patchflow emits. Ids follow `semantic-kitti-all.yaml`;
/// moving actors use the moving classes 252-259.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[repr(u16)]
pub enum SemanticClass {
    /// No label (a ray that hit nothing is not written at all).
    Unlabeled = 0,
    /// A parked or stopped car.
    Car = 10,
    /// A parked or stopped truck.
    Truck = 18,
    /// A standing person.
    Person = 30,
    /// A bicyclist standing still.
    Bicyclist = 31,
    /// Road surface.
    Road = 40,
    /// Sidewalk.
    Sidewalk = 48,
    /// Building facade.
    Building = 50,
    /// Fence or wall.
    Fence = 51,
    /// Other static structure.
    OtherStructure = 52,
    /// Vegetation: tree crowns, bushes.
    Vegetation = 70,
    /// Tree trunk.
    Trunk = 71,
    /// Terrain: grass, soil, gravel.
    Terrain = 72,
    /// Pole.
    Pole = 80,
    /// Traffic sign (and traffic-light head).
    TrafficSign = 81,
    /// Other object (bins and the like).
    OtherObject = 99,
    /// A moving car.
    MovingCar = 252,
    /// A moving bicyclist.
    MovingBicyclist = 253,
    /// A walking person.
    MovingPerson = 254,
    /// A moving truck.
    MovingTruck = 258,
}

impl SemanticClass {
    /// The numeric SemanticKITTI id.
    pub fn id(self) -> u16 {
        self as u16
    }

    /// True for the moving classes 252-259.
    pub fn is_moving(self) -> bool {
        is_moving_id(self.id())
    }
}

/// True for a SemanticKITTI moving-class id (252-259).
pub fn is_moving_id(id: u16) -> bool {
    (252..=259).contains(&id)
}

/// One point's label as stored in a `.label` file: semantic id in the low 16 bits, instance id in the high 16.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[repr(transparent)]
pub struct PointLabel(pub u32);

impl PointLabel {
    /// Packs a class and an instance id (0 for "no instance", the static world).
    pub fn new(class: SemanticClass, instance: u16) -> Self {
        Self::from_parts(class.id(), instance)
    }

    /// Packs raw ids.
    pub fn from_parts(semantic: u16, instance: u16) -> Self {
        Self(u32::from(semantic) | (u32::from(instance) << 16))
    }

    /// The SemanticKITTI semantic id (low 16 bits).
    pub fn semantic(self) -> u16 {
        (self.0 & 0xFFFF) as u16
    }

    /// The instance id (high 16 bits): the actor id, 0 for the static world.
    pub fn instance(self) -> u16 {
        (self.0 >> 16) as u16
    }

    /// True if the point lies on a moving actor (classes 252-259).
    pub fn is_moving(self) -> bool {
        is_moving_id(self.semantic())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packing_round_trips_semantic_and_instance() {
        for (class, inst) in [
            (SemanticClass::MovingTruck, 65535u16),
            (SemanticClass::Road, 0),
            (SemanticClass::Car, 12),
        ] {
            let label = PointLabel::new(class, inst);
            assert_eq!(label.semantic(), class.id());
            assert_eq!(label.instance(), inst);
        }
    }

    #[test]
    fn only_classes_252_to_259_count_as_moving() {
        assert!(SemanticClass::MovingCar.is_moving());
        assert!(SemanticClass::MovingPerson.is_moving());
        assert!(!SemanticClass::Car.is_moving());
        assert!(!is_moving_id(251));
        assert!(!is_moving_id(260));
    }
}
