//! Tests of the fleet draws: deterministic, inside the cited ranges, matching the cited fleet
//! means, belt lines on both sides of the thesis' slice top, and only where the rung asks.

use super::*;
use crate::scenario::{Realism, Scenario};

fn cars(model: Option<CarModel>, n: u64) -> Vec<VehicleBody> {
    (0..n)
        .map(|i| {
            VehicleBody::draw(
                ActorClass::Car,
                model,
                fleet_key(7, "fleet", &format!("car{i}")),
            )
            .unwrap()
        })
        .collect()
}

fn inside(s: &Spread, v: f64) -> bool {
    (s.min - 1e-12..=s.max + 1e-12).contains(&v)
}

#[test]
fn the_same_seed_scenario_and_vehicle_draw_the_same_body_and_others_differ() {
    let key = fleet_key(7, "situation1", "oncoming");
    let a = VehicleBody::draw(ActorClass::Car, Some(CarModel::Sedan), key);
    assert_eq!(
        a,
        VehicleBody::draw(ActorClass::Car, Some(CarModel::Sedan), key)
    );
    for other in [
        fleet_key(8, "situation1", "oncoming"),
        fleet_key(7, "situation2", "oncoming"),
        fleet_key(7, "situation1", "other"),
    ] {
        assert_ne!(
            a,
            VehicleBody::draw(ActorClass::Car, Some(CarModel::Sedan), other)
        );
    }
    assert_eq!(VehicleBody::draw(ActorClass::Pedestrian, None, key), None);
    assert_eq!(VehicleBody::draw(ActorClass::Cyclist, None, key), None);
}

#[test]
fn every_drawn_car_lies_inside_a_cited_segment_of_its_body_style() {
    for model in [
        None,
        Some(CarModel::Compact),
        Some(CarModel::Sedan),
        Some(CarModel::Van),
    ] {
        let segments = segments_of(model);
        for body in cars(model, 2_000) {
            let [l, w, h] = body.size_m;
            let fits = segments
                .iter()
                .any(|s| inside(&s.length_m, l) && inside(&s.width_m, w) && inside(&s.height_m, h));
            assert!(fits, "{model:?}: {body:?} fits no segment");
            assert!(
                (0.5 * h - 1e-12..=0.75 * h + 1e-12).contains(&body.belt_m),
                "{body:?}"
            );
            assert!(
                segments.iter().any(|s| inside(&s.belt_m, body.belt_m)),
                "{body:?}"
            );
        }
    }
    for i in 0..500 {
        let body = VehicleBody::draw(ActorClass::Truck, None, fleet_key(1, "t", &i.to_string()));
        let [l, w, h] = body.unwrap().size_m;
        // Directive 96/53/EC: at most 2.55 m wide, a rigid truck at most 12 m long, 4 m high.
        assert!(
            w <= 2.55 && (6.5..=10.0).contains(&l) && (3.0..=4.0).contains(&h),
            "{l} {w} {h}"
        );
    }
}

#[test]
fn the_whole_fleet_matches_the_cited_mean_width_and_suv_share() {
    let fleet = cars(None, 20_000);
    let n = fleet.len() as f64;
    let mean_width_cm = 100.0 * fleet.iter().map(|b| b.size_m[1]).sum::<f64>() / n;
    // T&E 2024: 180.3 cm over the 100 best-selling models of 2023 (ICCT: 180.2 cm in 2020).
    assert!(
        (mean_width_cm - 180.3).abs() < 1.0,
        "mean width {mean_width_cm:.1} cm"
    );
    // JATO: about half of new cars are SUVs (51.3 % in January 2023): taller than 1.52 m here.
    let tall = fleet.iter().filter(|b| b.size_m[2] > 1.55).count() as f64 / n;
    assert!((0.4..0.65).contains(&tall), "{tall}");
}

#[test]
fn belt_lines_fall_on_both_sides_of_the_thesis_slice_top() {
    // 2.1.1 slices 0.5-1.0 m above the ground: no edge may coincide with every car's belt line.
    for model in [None, Some(CarModel::Sedan)] {
        let fleet = cars(model, 5_000);
        let below = fleet.iter().filter(|b| b.belt_m < 0.99).count() as f64 / 5_000.0;
        let above = fleet.iter().filter(|b| b.belt_m > 1.01).count() as f64 / 5_000.0;
        assert!(
            below > 0.15 && above > 0.15,
            "{model:?}: {below} below, {above} above"
        );
    }
}

/// A scenario with an unsized car `a`, a sized car `b` and an unsized parked car; `extra` goes
/// first, or last if it is a table.
fn resolved(extra: &str) -> Scenario {
    let (head, tail) = if extra.starts_with('[') {
        ("", extra)
    } else {
        (extra, "")
    };
    let text = format!(
        "{head}\nsweeps = 1\n[ego]\npath_m = [[0.0, 0.0], [50.0, 0.0]]\nspeed_mps = 5.0\n\
         [[actors]]\nname = \"a\"\npath_m = [[0.0, 5.0], [50.0, 5.0]]\nspeed_mps = 3.0\n\
         [[actors]]\nname = \"b\"\nsize_m = [4.1, 1.7, 1.5]\npath_m = [[0.0, 9.0], [50.0, 9.0]]\nspeed_mps = 3.0\n\
         [[structures]]\nkind = \"parked_car\"\ncentre_m = [8.0, -4.0]\n{tail}\n"
    );
    Scenario::from_toml(&text, "fleet.toml", "fleet").unwrap()
}

#[test]
fn the_ideal_rung_resolves_sizes_as_before_and_draws_nothing() {
    let s = resolved("realism = \"ideal\"");
    assert!(!s.world.knobs().fleet);
    assert_eq!(s.actors[0].size_m, Some([4.7, 1.8, 1.45]));
    assert_eq!(s.actors[0].model, Some(CarModel::Sedan));
    assert_eq!(s.structures[0].size_m, Some([4.5, 1.8, 1.45]));
    let (actors, bodies) = drawn_bodies(&s.actors, false, 7, &s.name);
    assert_eq!(actors, s.actors);
    assert!(bodies.iter().all(Option::is_none));
}

#[test]
fn on_urban_an_explicit_size_is_kept_and_the_others_are_drawn_and_read_back() {
    let s = resolved("");
    assert!(s.world.knobs().fleet);
    assert_eq!((s.actors[0].size_m, s.actors[0].model), (None, None));
    assert_eq!(s.structures[0].size_m, None);
    let (actors, bodies) = drawn_bodies(&s.actors, true, 7, &s.name);
    let drawn = bodies[0].unwrap();
    assert_eq!(actors[0].size_m, Some(drawn.size_m));
    assert_eq!(
        Some(drawn),
        VehicleBody::draw(ActorClass::Car, None, fleet_key(7, "fleet", "a"))
    );
    assert_eq!((actors[1].size_m, bodies[1]), (Some([4.1, 1.7, 1.5]), None));
    // The resolved text says what is drawn (no size) and reads back equal.
    let back = Scenario::from_toml(&s.to_toml(), "resolved.toml", "x").unwrap();
    assert_eq!(back, s);
    // A single knob turns the draws off on a realistic rung.
    let off = resolved("[world]\nfleet = false");
    assert_eq!(off.actors[0].size_m, Some([4.7, 1.8, 1.45]));
    assert_eq!(off.realism, Realism::Urban);
}
