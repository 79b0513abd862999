//! Seeded random traffic for larger training sets: cars driving a Manhattan street grid in the
//! right-hand lane, turning at intersections with realistic radii, and pedestrians on the sidewalks.

use patchflow_dataset::ActorClass;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::{ActorConfig, TrafficConfig};
use crate::seed::{hash_name, mix, sub_seed};

/// Lateral offset of a lane centre from the street centre, metres.
const LANE_OFFSET_M: f64 = 1.75;
/// Lateral offset of a sidewalk from the street centre, metres.
const SIDEWALK_OFFSET_M: f64 = 6.5;

/// The random actors of a scenario, drawn from `seed` and the scenario name. Their paths are
/// long enough for `horizon_secs` of driving.
pub fn random_traffic(
    config: &TrafficConfig,
    seed: u64,
    scenario: &str,
    horizon_secs: f64,
) -> Vec<ActorConfig> {
    let mut rng = ChaCha8Rng::seed_from_u64(sub_seed(mix(seed ^ hash_name(scenario)), 0x7A_FF1C));
    let mut actors = Vec::new();
    for i in 0..config.random_cars {
        actors.push(random_car(config, &mut rng, i, horizon_secs));
    }
    for i in 0..config.random_pedestrians {
        actors.push(random_pedestrian(config, &mut rng, i, horizon_secs));
    }
    actors
}

fn left(d: [f64; 2]) -> [f64; 2] {
    [-d[1], d[0]]
}

/// A random start on the grid: a street, a direction along it and a position, in the lane at `offset`.
fn random_start(config: &TrafficConfig, rng: &mut ChaCha8Rng, offset: f64) -> ([f64; 2], [f64; 2]) {
    let g = config.grid_spacing_m;
    let streets = (config.extent_m / g).floor() as i64;
    let street = rng.random_range(-streets..=streets) as f64 * g;
    let along = rng.random_range(-config.extent_m..config.extent_m);
    let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
    let horizontal = rng.random::<bool>();
    let (p, d) = if horizontal {
        ([along, street], [sign, 0.0])
    } else {
        ([street, along], [0.0, sign])
    };
    let l = left(d);
    let c = config.centre_m;
    (
        [c[0] + p[0] - offset * l[0], c[1] + p[1] - offset * l[1]],
        d,
    )
}

fn random_car(
    config: &TrafficConfig,
    rng: &mut ChaCha8Rng,
    i: u32,
    horizon_secs: f64,
) -> ActorConfig {
    let [lo, hi] = config.car_speed_mps;
    let speed = if hi > lo {
        rng.random_range(lo..hi)
    } else {
        lo
    };
    let truck = rng.random::<f64>() < 0.1;
    let radius = rng.random_range(6.0..10.0) + if truck { 4.0 } else { 0.0 };
    let (start, mut d) = random_start(config, rng, LANE_OFFSET_M);
    let g = config.grid_spacing_m;
    let mut points = vec![start];
    let mut at = start;
    let mut remaining = speed * horizon_secs + 60.0;
    while remaining > 0.0 {
        // Distance to the next intersection ahead (street centres lie on the grid around centre_m).
        let coord = if d[0] != 0.0 {
            at[0] - config.centre_m[0]
        } else {
            at[1] - config.centre_m[1]
        };
        let sign = d[0] + d[1];
        let next = ((coord * sign / g).floor() + 1.0) * g * sign;
        let mut run = (next - coord).abs();
        if run < 2.0 * radius + LANE_OFFSET_M {
            run += g;
        }
        let turn = rng.random_range(0..4u8);
        let out = match turn {
            0 => left(d),
            1 => [d[1], -d[0]],
            _ => d,
        };
        // The corner between the incoming and outgoing lanes at that intersection.
        let centre_line = [at[0] + d[0] * run, at[1] + d[1] * run];
        let corner = if out == d {
            centre_line
        } else {
            // The incoming lane is already offset; shift along d to the outgoing lane's line.
            let lo_ = left(out);
            let shift = -LANE_OFFSET_M * (lo_[0] * d[0] + lo_[1] * d[1]);
            [centre_line[0] + d[0] * shift, centre_line[1] + d[1] * shift]
        };
        remaining -= (corner[0] - at[0]).hypot(corner[1] - at[1]);
        points.push(corner);
        at = corner;
        d = out;
    }
    ActorConfig {
        name: format!("random_car{}", i + 1),
        class: if truck {
            ActorClass::Truck
        } else {
            ActorClass::Car
        },
        model: None,
        size_m: None,
        target: false,
        path_m: points,
        turn_radius_m: Some(radius),
        speed_mps: speed,
        initial_speed_mps: None,
        accel_mps2: None,
        start_secs: 0.0,
        speed_changes: Vec::new(),
        reflectivity: Some(rng.random_range(0.2..0.8)),
        mesh: None,
        mesh_data: None,
    }
    .resolved()
}

fn random_pedestrian(
    config: &TrafficConfig,
    rng: &mut ChaCha8Rng,
    i: u32,
    horizon_secs: f64,
) -> ActorConfig {
    let speed = rng.random_range(0.8..1.8);
    let (start, d) = random_start(config, rng, SIDEWALK_OFFSET_M);
    let length = speed * horizon_secs + 10.0;
    ActorConfig {
        name: format!("random_pedestrian{}", i + 1),
        class: ActorClass::Pedestrian,
        model: None,
        size_m: None,
        target: false,
        path_m: vec![start, [start[0] + d[0] * length, start[1] + d[1] * length]],
        turn_radius_m: None,
        speed_mps: speed,
        initial_speed_mps: None,
        accel_mps2: None,
        start_secs: 0.0,
        speed_changes: Vec::new(),
        reflectivity: None,
        mesh: None,
        mesh_data: None,
    }
    .resolved()
}

impl ActorConfig {
    fn resolved(mut self) -> Self {
        self.resolve();
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn config() -> TrafficConfig {
        TrafficConfig {
            random_cars: 30,
            random_pedestrians: 10,
            ..TrafficConfig::default()
        }
    }

    #[test]
    fn random_traffic_is_the_same_for_the_same_seed_and_differs_for_another() {
        assert_eq!(
            random_traffic(&config(), 3, "t", 20.0),
            random_traffic(&config(), 3, "t", 20.0)
        );
        assert_ne!(
            random_traffic(&config(), 3, "t", 20.0),
            random_traffic(&config(), 4, "t", 20.0)
        );
    }

    #[test]
    fn every_random_actor_has_a_valid_smooth_trajectory() {
        for actor in random_traffic(&config(), 11, "t", 30.0) {
            assert!(actor.problems().is_empty(), "{:?}", actor.problems());
            assert!(
                actor.trajectory().is_ok(),
                "{}: {:?}",
                actor.name,
                actor.trajectory().err()
            );
        }
    }
}
