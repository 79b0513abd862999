//! One item of street clutter ([`Item`]) and the pieces it is built from: a tree (a trunk and
//! a porous crown), a bush, a street light, a sign, a bollard, a bin, a bench or planter, a
//! utility cabinet, a traffic light, or a parked car.

use patchflow_dataset::{ActorClass, SemanticClass};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use super::Material;
use super::body_shapes::parked_car_parts;
use super::clearance::ItemExtent;
use super::piece::{Piece, PieceShape};
use crate::scenario::VehicleBody;

/// The pieces of `item` standing at `p` on ground `base` metres high, beside a street of yaw
/// `yaw` on its `side` (+1 left, −1 right); a parked car's body is drawn from the fleet
/// statistics if `fleet` is on (`VehicleBody`), else it is one of three fixed sizes.
pub(super) fn item_pieces(
    item: Item,
    p: [f64; 2],
    base: f64,
    (yaw, side): (f64, f64),
    rng: &mut ChaCha8Rng,
    fleet: bool,
) -> Vec<Piece> {
    let (x, y) = (p[0] as f32, p[1] as f32);
    let column = |half: f32, r: f32, z0: f64, semantic, reflectivity: f32| Piece {
        shape: PieceShape::Column(half, r),
        centre_m: [x, y, z0 as f32 + half],
        yaw_rad: 0.0,
        semantic,
        reflectivity,
        material: Material::SOLID,
    };
    match item {
        Item::Tree => {
            let trunk_h = rng.random_range(2.2f32..3.5);
            let crown = rng.random_range(1.4f32..2.8);
            vec![
                column(
                    trunk_h / 2.0 + 0.1,
                    rng.random_range(0.12..0.25),
                    base - 0.1,
                    SemanticClass::Trunk,
                    0.35,
                ),
                Piece {
                    shape: PieceShape::Ball(crown),
                    centre_m: [x, y, (base as f32) + trunk_h + 0.7 * crown],
                    yaw_rad: 0.0,
                    semantic: SemanticClass::Vegetation,
                    reflectivity: 0.5,
                    material: Material::foliage(0.6),
                },
            ]
        }
        Item::Bush => {
            let r = rng.random_range(0.5f32..1.1);
            vec![Piece {
                shape: PieceShape::Ball(r),
                centre_m: [x, y, base as f32 + 0.55 * r],
                yaw_rad: 0.0,
                semantic: SemanticClass::Vegetation,
                reflectivity: 0.45,
                material: Material::foliage(0.3),
            }]
        }
        Item::StreetLight => vec![column(3.6, 0.09, base - 0.1, SemanticClass::Pole, 0.5)],
        Item::Bollard => vec![column(0.5, 0.09, base - 0.1, SemanticClass::Pole, 0.45)],
        // A bench or a planter at the back of the sidewalk, along it.
        Item::Bench => vec![Piece::block(
            p,
            base - 0.1,
            [rng.random_range(1.5..2.5), 0.6, rng.random_range(0.5..0.9)],
            yaw,
            SemanticClass::OtherObject,
            rng.random_range(0.2..0.5),
        )],
        // A utility cabinet or a bike stand near the curb.
        Item::Cabinet => vec![Piece::block(
            p,
            base - 0.1,
            [rng.random_range(0.8..1.6), 0.5, rng.random_range(0.9..1.4)],
            yaw,
            SemanticClass::OtherObject,
            rng.random_range(0.25..0.6),
        )],
        Item::Bin => vec![column(
            0.55,
            0.3,
            base - 0.1,
            SemanticClass::OtherObject,
            0.3,
        )],
        Item::Sign => vec![
            column(1.3, 0.04, base - 0.1, SemanticClass::Pole, 0.5),
            Piece::block(
                p,
                base + 2.0,
                [0.04, 0.65, 0.65],
                yaw,
                SemanticClass::TrafficSign,
                0.9,
            ),
        ],
        Item::TrafficLight => vec![
            column(1.9, 0.08, base - 0.1, SemanticClass::Pole, 0.45),
            Piece::block(
                p,
                base + 2.5,
                [0.35, 0.35, 1.0],
                yaw,
                SemanticClass::TrafficSign,
                0.3,
            ),
        ],
        Item::ParkedCar => {
            let body = if fleet {
                VehicleBody::draw(ActorClass::Car, None, rng.random::<u64>())
                    .map(|b| (b.size_m, Some(b.belt_m)))
            } else {
                None
            };
            let body = body.unwrap_or_else(|| {
                let size = match rng.random_range(0..3u8) {
                    0 => [3.9, 1.7, 1.45],
                    1 => [4.7, 1.8, 1.45],
                    _ => [5.1, 1.95, 1.95],
                };
                (size, None)
            });
            let heading = if side > 0.0 {
                yaw + std::f64::consts::PI
            } else {
                yaw
            };
            let reflectivity = rng.random_range(0.1f32..0.8);
            parked_car_parts(body, reflectivity, [p[0], p[1]], heading, base)
        }
    }
}

/// Kinds of street clutter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Item {
    ParkedCar,
    Tree,
    Bush,
    StreetLight,
    Sign,
    Bollard,
    Bin,
    Bench,
    Cabinet,
    TrafficLight,
}

impl Item {
    /// Footprint radius for spacing, metres.
    pub(super) fn radius_m(self) -> f64 {
        match self {
            Self::ParkedCar => 2.6,
            Self::Tree => 0.6,
            Self::Bush => 1.0,
            Self::Bin => 0.35,
            Self::Bench => 1.3,
            Self::Cabinet => 0.8,
            Self::StreetLight | Self::Sign | Self::Bollard | Self::TrafficLight => 0.2,
        }
    }

    /// What must keep off a road user's corridor, for an item along a street of yaw `yaw_rad`:
    /// a parked car, a bench or a cabinet with its length along the street and its width across;
    /// a tree with its trunk (its crown overhangs the corridor); anything else with its radius.
    pub(super) fn body(self, yaw_rad: f64) -> ItemExtent {
        let along = |half_across_m| ItemExtent {
            half_along_m: self.radius_m(),
            half_across_m,
            yaw_rad,
        };
        match self {
            Self::ParkedCar => along(1.0),
            Self::Bench | Self::Cabinet => along(0.3),
            Self::Tree => ItemExtent::disc(0.3),
            other => ItemExtent::disc(other.radius_m()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_items_lie_along_the_street_and_a_tree_keeps_only_its_trunk_off_a_corridor() {
        let yaw = 0.4;
        for item in [Item::ParkedCar, Item::Bench, Item::Cabinet] {
            let body = item.body(yaw);
            assert_eq!((body.half_along_m, body.yaw_rad), (item.radius_m(), yaw));
            assert!(body.half_across_m < body.half_along_m, "{item:?}");
        }
        assert_eq!(Item::Tree.body(yaw), ItemExtent::disc(0.3));
        assert_eq!(
            Item::Bush.body(yaw),
            ItemExtent::disc(Item::Bush.radius_m())
        );
    }
}
