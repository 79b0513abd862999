//! What stands along the streets: raised sidewalk slabs whose road-facing faces are the curbs,
//! and seeded clutter at a density per 100 m of street side ([`Item`]): trees, bushes in the
//! gardens, street furniture, traffic lights at the corners, and parked cars slot by slot.
//! Every item keeps clear of the actors' corridors, the scenario's own structures and the items
//! placed before it.

use patchflow_dataset::SemanticClass;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::clearance::Clearance;
use super::ground_field::{GroundField, GroundRecipe};
use super::piece::Piece;
use super::street_item::{Item, item_pieces};
use super::street_map::Street;
use crate::seed::sub_seed;

/// Longest sidewalk slab, metres.
const SLAB_M: f64 = 8.0;
/// Length of a parking slot along the curb, metres (a full curb: 100 / 6 ≈ 17 cars per 100 m).
const PARKING_SLOT_M: f64 = 6.0;
/// Depth of a sidewalk slab below its top, metres.
const SLAB_DEPTH_M: f64 = 0.6;

/// Everything placed along one side of one street.
pub(crate) struct SideBuilder<'a> {
    pub recipe: &'a GroundRecipe<'a>,
    pub field: &'a GroundField,
    pub street: &'a Street,
    /// +1 for the left side of the street's direction, −1 for the right.
    pub side: f64,
    pub seed: u64,
}

impl SideBuilder<'_> {
    /// The intervals `[from, to]` (metres along the street) where this side's sidewalk is off
    /// every carriageway and on the ground field.
    pub(crate) fn free_intervals(
        &self,
        on_carriageway: &dyn Fn([f64; 2]) -> bool,
    ) -> Vec<(f64, f64)> {
        let k = &self.recipe.knobs;
        let (w, band) = (self.street.half_width_m, k.sidewalk_width_m);
        let (lo, hi) = self.field.bounds();
        let inside = |p: [f64; 2]| {
            p[0] > f64::from(lo[0]) + 1.0
                && p[1] > f64::from(lo[1]) + 1.0
                && p[0] < f64::from(hi[0]) - 1.0
                && p[1] < f64::from(hi[1]) - 1.0
        };
        let length = self.street.length_m();
        let mut out = Vec::new();
        let mut start: Option<f64> = None;
        let steps = (length / 0.5).floor() as usize;
        for k in 0..=steps {
            let s = k as f64 * 0.5;
            let free = [w + 0.05, w + band / 2.0, w + band - 0.05]
                .iter()
                .all(|&d| {
                    let p = self.street.point_at(s, self.side * d);
                    inside(p) && !on_carriageway(p)
                });
            match (free, start) {
                (true, None) => start = Some(s),
                (false, Some(a)) => {
                    if s - 0.5 - a > 1.0 {
                        out.push((a, s - 0.5));
                    }
                    start = None;
                }
                _ => {}
            }
        }
        if let Some(a) = start
            && length - a > 1.0
        {
            out.push((a, length));
        }
        out
    }

    /// The sidewalk slabs over `[from, to]`, at most [`SLAB_M`] long, each topped at the local
    /// sidewalk height (its road-facing face is the curb).
    pub(crate) fn slabs(&self, (from, to): (f64, f64)) -> Vec<Piece> {
        let k = &self.recipe.knobs;
        let (w, band) = (self.street.half_width_m, k.sidewalk_width_m);
        let count = ((to - from) / SLAB_M).ceil().max(1.0) as usize;
        let length = (to - from) / count as f64;
        (0..count)
            .map(|i| {
                let s = from + (i as f64 + 0.5) * length;
                let centre = self.street.point_at(s, self.side * (w + band / 2.0));
                let top = self
                    .recipe
                    .sidewalk_top_m(self.street.point_at(s, self.side * w), w);
                let shade = ValueJitter(sub_seed(self.seed, i as u64)).unit();
                Piece::block(
                    centre,
                    top - SLAB_DEPTH_M,
                    [length, band, SLAB_DEPTH_M],
                    self.street.yaw_rad(),
                    SemanticClass::Sidewalk,
                    0.28 + 0.06 * shade,
                )
            })
            .collect()
    }

    /// Seeded clutter and parked cars along `[from, to]`; `corner` marks interval ends that are
    /// street corners (traffic lights stand there).
    pub(crate) fn clutter(&self, (from, to): (f64, f64), clearance: &mut Clearance) -> Vec<Piece> {
        let k = self.recipe.knobs;
        let mut rng = ChaCha8Rng::seed_from_u64(sub_seed(self.seed, 0xC1u64));
        let (w, band) = (self.street.half_width_m, k.sidewalk_width_m.max(1.0));
        let per_100m = (to - from) / 100.0;
        let mut out = Vec::new();
        // Parked cars fill the curb slot by slot (as real parking does), the rest is scattered.
        let slots = ((to - from - 6.0) / PARKING_SLOT_M).floor().max(0.0) as usize;
        let occupancy = k.parked_cars_per_100m * PARKING_SLOT_M / 100.0;
        let kinds: [(Item, f64); 10] = [
            (Item::ParkedCar, k.parked_cars_per_100m),
            (Item::Tree, 4.0 * k.clutter),
            (Item::Bush, 4.0 * k.clutter),
            (Item::StreetLight, 2.5 * k.clutter),
            (Item::Sign, 1.5 * k.clutter),
            (Item::Bollard, 3.0 * k.clutter),
            (Item::Bin, 1.5 * k.clutter),
            (Item::Bench, 2.0 * k.clutter),
            (Item::Cabinet, 2.0 * k.clutter),
            (Item::TrafficLight, if k.clutter > 0.0 { 2.0 } else { 0.0 }),
        ];
        for (item, density) in kinds {
            let expected = density * per_100m;
            let count = if item == Item::ParkedCar {
                slots
            } else {
                expected.floor() as usize + usize::from(rng.random::<f64>() < expected.fract())
            };
            for slot in 0..count {
                let s = match item {
                    Item::ParkedCar => {
                        if rng.random::<f64>() >= occupancy {
                            continue;
                        }
                        from + 3.0
                            + (slot as f64 + 0.5) * PARKING_SLOT_M
                            + rng.random_range(-0.3..0.3)
                    }
                    // Traffic lights stand at the ends of a sidewalk run: the corners.
                    Item::TrafficLight => {
                        if rng.random::<bool>() {
                            from + 0.8
                        } else {
                            to - 0.8
                        }
                    }
                    _ => rng.random_range(from..to),
                };
                let across = match item {
                    Item::ParkedCar => w - 1.1,
                    Item::Tree => w + rng.random_range(0.8..band.max(1.0) + 2.5),
                    // In the gardens behind the frontage.
                    Item::Bush => w + band + rng.random_range(1.8..5.0),
                    Item::StreetLight | Item::TrafficLight => w + 0.6,
                    Item::Sign => w + 0.4,
                    Item::Bollard => w + 0.35,
                    Item::Bin => w + band - 0.4,
                    Item::Bench => w + band - 0.5,
                    Item::Cabinet => w + 0.5,
                };
                if item == Item::ParkedCar && (s - from < 3.0 || to - s < 3.0) {
                    continue;
                }
                let p = self.street.point_at(s, self.side * across);
                let radius = item.radius_m();
                let body = item.body(self.street.yaw_rad());
                if !clearance.is_free(p, radius, body, 0.3) {
                    continue;
                }
                let base = f64::from(self.field.height_at(p[0] as f32, p[1] as f32));
                let side = (self.street.yaw_rad(), self.side);
                let pieces = item_pieces(item, p, base, side, &mut rng, k.fleet);
                if pieces.is_empty() {
                    continue;
                }
                clearance.occupy(p, radius);
                out.extend(pieces);
            }
        }
        out
    }
}

/// A hash of a seed as a value in [−1, 1].
struct ValueJitter(u64);

impl ValueJitter {
    fn unit(&self) -> f64 {
        (crate::seed::mix(self.0) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}
