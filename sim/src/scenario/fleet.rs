//! A fleet that varies as real fleets do (SPEC §3a): on the rungs with `[world] fleet = true`,
//! every car and truck without an explicit `size_m` gets its length, width, height and belt-line
//! height drawn per vehicle from published fleet statistics, deterministically from the run seed,
//! the scenario and the vehicle. Sources (docs/realism.md, "A fleet that varies"):
//! - segment shares of European new-car registrations: JATO Dynamics (SUVs 51.3 % of Europe's
//!   registrations in January 2023, small and compact SUVs 79 % of SUVs in October 2019,
//!   subcompact cars 19 % in January 2021);
//! - mean width of new cars in Europe: Transport & Environment (2024), 180.3 cm for the 100
//!   best-selling models of 2023 (ICCT: 180.2 cm over all 2020 registrations); large SUVs
//!   about 200 cm;
//! - each segment's length, width and height: the manufacturers' published dimensions of its
//!   best-selling models (the segments as in EU merger practice, Case COMP/M.1406);
//! - belt lines: on cars about at the hood's rear edge; IIHS (Hu et al., 2023; 2,958 models)
//!   found hood leading edges from 0.76 m or less on cars to above 1.02 m on many SUVs, vans
//!   and pickups, so the belt line spans from below the thesis' slice top (1.0 m) to 0.25 m above;
//! - trucks: rigid trucks within EU Directive 96/53/EC (at most 2.55 m wide).

use patchflow_dataset::ActorClass;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use super::actor_config::{ActorConfig, CarModel};
use crate::seed::{hash_name, mix, sub_seed};

/// One dimension of a segment, metres: a normal draw with `mean` and `std`, redrawn outside
/// `[min, max]` (the segment's published range).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Spread {
    pub mean: f64,
    pub std: f64,
    pub min: f64,
    pub max: f64,
}

const fn spread(mean: f64, std: f64, min: f64, max: f64) -> Spread {
    Spread {
        mean,
        std,
        min,
        max,
    }
}

/// A market segment: its share of the fleet and its dimensions.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Segment {
    /// Share of the cars on the road, percent.
    pub share_pct: f64,
    pub length_m: Spread,
    pub width_m: Spread,
    pub height_m: Spread,
    /// Height of the lower edge of the side glass above the ground.
    pub belt_m: Spread,
}

/// The car segments of the European fleet (see the module documentation for the sources).
pub(crate) const CAR_SEGMENTS: [Segment; 7] = [
    // A (mini): Fiat Panda, VW up!, Toyota Aygo X, Hyundai i10.
    Segment {
        share_pct: 5.0,
        length_m: spread(3.65, 0.06, 3.50, 3.80),
        width_m: spread(1.66, 0.04, 1.58, 1.76),
        height_m: spread(1.52, 0.04, 1.44, 1.62),
        belt_m: spread(0.95, 0.03, 0.88, 1.02),
    },
    // B (small): Renault Clio, Peugeot 208, VW Polo, Toyota Yaris, Dacia Sandero.
    Segment {
        share_pct: 19.0,
        length_m: spread(4.03, 0.07, 3.88, 4.15),
        width_m: spread(1.76, 0.03, 1.69, 1.83),
        height_m: spread(1.46, 0.03, 1.40, 1.54),
        belt_m: spread(0.95, 0.03, 0.88, 1.02),
    },
    // C (medium): VW Golf, Peugeot 308, Ford Focus, Toyota Corolla, Skoda Octavia.
    Segment {
        share_pct: 15.0,
        length_m: spread(4.40, 0.12, 4.20, 4.70),
        width_m: spread(1.81, 0.02, 1.77, 1.86),
        height_m: spread(1.46, 0.02, 1.41, 1.51),
        belt_m: spread(0.98, 0.03, 0.91, 1.05),
    },
    // D/E (large, executive): VW Passat, BMW 3 and 5 Series, Mercedes C-Class, Audi A4, Tesla Model 3.
    Segment {
        share_pct: 8.0,
        length_m: spread(4.80, 0.13, 4.60, 5.10),
        width_m: spread(1.85, 0.03, 1.79, 1.91),
        height_m: spread(1.45, 0.03, 1.39, 1.53),
        belt_m: spread(0.99, 0.03, 0.92, 1.06),
    },
    // B/C SUV: VW T-Roc and Tiguan, Renault Captur, Peugeot 2008, Nissan Qashqai, Kia Sportage, Dacia Duster.
    Segment {
        share_pct: 40.0,
        length_m: spread(4.40, 0.17, 4.05, 4.80),
        width_m: spread(1.80, 0.04, 1.74, 1.93),
        height_m: spread(1.61, 0.04, 1.52, 1.71),
        belt_m: spread(1.08, 0.04, 0.99, 1.17),
    },
    // D/E SUV: BMW X5, Volvo XC90, Audi Q5, Mercedes GLC, Skoda Kodiaq, Tesla Model Y.
    Segment {
        share_pct: 10.0,
        length_m: spread(4.80, 0.12, 4.60, 5.05),
        width_m: spread(1.92, 0.04, 1.85, 2.01),
        height_m: spread(1.70, 0.05, 1.60, 1.81),
        belt_m: spread(1.15, 0.04, 1.06, 1.25),
    },
    // M (MPV) and small vans: Citroën Berlingo, VW Caddy and Transporter, Mercedes Vito, VW Touran.
    Segment {
        share_pct: 3.0,
        length_m: spread(4.75, 0.22, 4.35, 5.20),
        width_m: spread(1.88, 0.04, 1.80, 1.97),
        height_m: spread(1.88, 0.07, 1.70, 2.02),
        belt_m: spread(1.08, 0.05, 0.98, 1.20),
    },
];

/// Rigid trucks (7.5-18 t distribution trucks; Directive 96/53/EC caps the width at 2.55 m).
pub(crate) const TRUCK_SEGMENT: Segment = Segment {
    share_pct: 100.0,
    length_m: spread(8.2, 0.9, 6.5, 10.0),
    width_m: spread(2.48, 0.05, 2.30, 2.55),
    height_m: spread(3.5, 0.2, 3.0, 4.0),
    belt_m: spread(2.0, 0.1, 1.75, 2.25),
};

/// The drawn body of one vehicle: its truth box and its belt line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VehicleBody {
    /// Length, width, height, metres (the truth box of the object files).
    pub size_m: [f64; 3],
    /// Height of the lower edge of the side glass above the box bottom, metres.
    pub belt_m: f64,
}

impl VehicleBody {
    /// The body of a vehicle of `class` (and car body style `model`; `None` draws from the whole
    /// fleet) drawn from the stream `key`; `None` for classes that are not vehicles.
    pub fn draw(class: ActorClass, model: Option<CarModel>, key: u64) -> Option<Self> {
        let mut rng = ChaCha8Rng::seed_from_u64(key);
        let segment = match class {
            ActorClass::Car => pick(segments_of(model), rng.random::<f64>()),
            ActorClass::Truck => &TRUCK_SEGMENT,
            ActorClass::Pedestrian | ActorClass::Cyclist => return None,
        };
        let size_m =
            [segment.length_m, segment.width_m, segment.height_m].map(|s| s.draw(&mut rng));
        // The glass keeps at least a quarter of the height, the body at least half.
        let belt_m = segment
            .belt_m
            .draw(&mut rng)
            .clamp(0.5 * size_m[2], 0.75 * size_m[2]);
        Some(Self { size_m, belt_m })
    }
}

/// The car segments a body style draws from.
pub(crate) fn segments_of(model: Option<CarModel>) -> &'static [Segment] {
    match model {
        Some(CarModel::Compact) => &CAR_SEGMENTS[0..2],
        Some(CarModel::Sedan) => &CAR_SEGMENTS[2..4],
        Some(CarModel::Van) => &CAR_SEGMENTS[6..7],
        None => &CAR_SEGMENTS,
    }
}

/// The segment at cumulative share `u` in [0, 1).
fn pick(segments: &[Segment], u: f64) -> &Segment {
    let total: f64 = segments.iter().map(|s| s.share_pct).sum();
    let mut at = u * total;
    for segment in segments {
        if at < segment.share_pct {
            return segment;
        }
        at -= segment.share_pct;
    }
    &segments[segments.len() - 1]
}

impl Spread {
    /// One draw inside `[min, max]`: normal draws outside are redrawn (at most 32 times, then
    /// clamped), so the shape is the normal truncated to the published range.
    fn draw(&self, rng: &mut ChaCha8Rng) -> f64 {
        let mut value = self.mean;
        for _ in 0..32 {
            value = self.mean + self.std * rng.sample::<f64, _>(StandardNormal);
            if (self.min..=self.max).contains(&value) {
                return value;
            }
        }
        value.clamp(self.min, self.max)
    }
}

/// `actors` with the body of every car and truck that has no `size_m` drawn from the fleet (its
/// size filled in), and each actor's drawn body (`None`: not drawn), when `fleet` is on; each
/// vehicle's stream is [`fleet_key`] of the run seed, the scenario and the actor's name.
pub(crate) fn drawn_bodies(
    actors: &[ActorConfig],
    fleet: bool,
    seed: u64,
    scenario: &str,
) -> (Vec<ActorConfig>, Vec<Option<VehicleBody>>) {
    let mut sized = actors.to_vec();
    let bodies = sized
        .iter_mut()
        .map(|actor| {
            if !fleet || actor.size_m.is_some() {
                return None;
            }
            let key = fleet_key(seed, scenario, &actor.name);
            let body = VehicleBody::draw(actor.class, actor.model, key)?;
            actor.size_m = Some(body.size_m);
            Some(body)
        })
        .collect();
    (sized, bodies)
}

/// Random traffic's vehicles come resolved at their class default; on a fleet world their body
/// is drawn like that of any vehicle without `size_m`.
pub(crate) fn reopen_for_fleet(actors: &mut [ActorConfig]) {
    for actor in actors {
        if matches!(actor.class, ActorClass::Car | ActorClass::Truck) && actor.mesh.is_none() {
            actor.size_m = None;
            actor.model = None;
        }
    }
}

/// The stream of the vehicle `vehicle` (an actor's name, or `structures[i][j]` for box `j` of
/// the `i`-th structure entry, a parked car) of `scenario` under run seed `seed`: with it,
/// [`VehicleBody::draw`] gives the body a generated sequence holds.
///
/// ```
/// use patchflow_sim::{CarModel, VehicleBody, dataset::ActorClass, fleet_key};
/// let key = fleet_key(7, "situation1", "oncoming");
/// let body = VehicleBody::draw(ActorClass::Car, Some(CarModel::Sedan), key);
/// assert!(body.is_some_and(|b| (4.2..5.1).contains(&b.size_m[0])));
/// ```
pub fn fleet_key(seed: u64, scenario: &str, vehicle: &str) -> u64 {
    sub_seed(
        mix(seed ^ hash_name(scenario)),
        0xF1EE7 ^ hash_name(vehicle),
    )
}

#[cfg(test)]
#[path = "fleet_tests.rs"]
mod tests;
