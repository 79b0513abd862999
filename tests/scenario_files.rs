//! Every shipped scenario loads and validates; a few sweeps of each have a plausible point count
//! (60,000 to 130,000 in open streets) and the situations' target is hit. The full check over
//! every sweep is run by hand (see `scenarios/README.md`), not in CI.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use patchflow_sim::{EMBEDDED_SCENARIOS, Scenario, Simulation};

fn shipped() -> Vec<Scenario> {
    EMBEDDED_SCENARIOS
        .iter()
        .map(|(name, text)| Scenario::from_toml(text, &format!("{name}.toml"), name).unwrap())
        .collect()
}

#[test]
fn every_embedded_scenario_matches_its_file_in_the_repository() {
    let dir = patchflow_tests::workspace_root().join("scenarios");
    for (name, text) in EMBEDDED_SCENARIOS {
        let on_disk = std::fs::read_to_string(dir.join(format!("{name}.toml"))).unwrap();
        assert_eq!(on_disk, text, "{name}");
        Scenario::from_file(&dir.join(format!("{name}.toml"))).unwrap();
    }
}

#[test]
fn situations_have_one_car_target_and_30_to_100_sweeps() {
    for scenario in shipped().iter().filter(|s| s.name.starts_with("situation")) {
        let targets: Vec<_> = scenario.actors.iter().filter(|a| a.target).collect();
        assert_eq!(targets.len(), 1, "{}", scenario.name);
        assert_eq!(
            targets[0].class,
            patchflow_sim::dataset::ActorClass::Car,
            "{}",
            scenario.name
        );
        assert!(
            (30..=100).contains(&scenario.sweeps),
            "{}: {} sweeps",
            scenario.name,
            scenario.sweeps
        );
    }
    assert_eq!(
        shipped()
            .iter()
            .filter(|s| s.name.starts_with("situation"))
            .count(),
        5
    );
}

#[test]
fn training_tracks_have_100_to_200_sweeps_clutter_and_speeds_of_2_to_10() {
    let tracks: Vec<Scenario> = shipped()
        .into_iter()
        .filter(|s| s.name.starts_with("train"))
        .collect();
    assert_eq!(tracks.len(), 9);
    for track in &tracks {
        assert!((100..=200).contains(&track.sweeps), "{}", track.name);
        assert!(
            track
                .structures
                .iter()
                .any(|s| s.kind == patchflow_sim::StructureKind::ParkedCar),
            "{}",
            track.name
        );
        assert!(
            track
                .actors
                .iter()
                .any(|a| a.class == patchflow_sim::dataset::ActorClass::Pedestrian),
            "{}",
            track.name
        );
    }
    let speeds: Vec<f64> = tracks
        .iter()
        .flat_map(|t| t.actors.iter())
        .filter(|a| a.class == patchflow_sim::dataset::ActorClass::Car)
        .map(|a| a.speed_mps)
        .collect();
    assert!(
        speeds.iter().any(|&v| v <= 2.5) && speeds.iter().any(|&v| v >= 9.5),
        "{speeds:?}"
    );
}

#[test]
fn sampled_sweeps_of_every_scenario_have_plausible_point_counts_and_hit_the_target() {
    for scenario in shipped() {
        let mut sim = Simulation::new(&scenario, 0).unwrap();
        for index in [0, scenario.sweeps / 2, scenario.sweeps - 1] {
            let sweep = sim.sweep(index);
            assert!(
                (60_000..=130_000).contains(&sweep.len()),
                "{} sweep {index}: {} points",
                scenario.name,
                sweep.len()
            );
            if let Some(target) = sweep.target() {
                assert!(
                    target.point_count > 0,
                    "{} sweep {index}: target not hit",
                    scenario.name
                );
            }
        }
    }
}
