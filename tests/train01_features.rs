//! On the shipped `train01` track, map patches of a car driving along the sensor's line of sight
//! show far more change than patches of a static wall (features issue: at least 5× the mean
//! absolute difference value). Uses the real simulator and the real feature pipeline.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use patchflow_dataset::{SemanticClass, Sweep};
use patchflow_learn::{FeatureParams, SweepFeatures};
use patchflow_sim::{EMBEDDED_SCENARIOS, Realism, Scenario, Simulation};

/// Mean of the patches' mean absolute difference values over the chosen points, and their count.
fn mean_weight(features: &SweepFeatures, chosen: &[usize]) -> f64 {
    let patches = features.heading_patches(chosen);
    patches.iter().map(|p| p.mean_abs_difference()).sum::<f64>() / patches.len() as f64
}

/// Sliced points on moving actors whose heading is within ~25° of the line of sight (either way).
fn line_of_sight_car_points(features: &SweepFeatures, sweep: &Sweep) -> Vec<usize> {
    (0..features.len())
        .filter(|&i| {
            let label = sweep.labels[features.points()[i].index];
            let Some(actor) = sweep
                .objects
                .iter()
                .find(|o| o.id == label.instance() && o.moving)
            else {
                return false;
            };
            label.is_moving()
                && actor.speed_mps > 2.0
                && (actor.heading_rad - features.bearing_rad(i)).cos().abs() > 0.9
        })
        .collect()
}

fn wall_points(features: &SweepFeatures, sweep: &Sweep) -> Vec<usize> {
    (0..features.len())
        .filter(|&i| {
            let semantic = sweep.labels[features.points()[i].index].semantic();
            semantic == SemanticClass::Fence.id() || semantic == SemanticClass::Building.id()
        })
        .collect()
}

#[test]
fn a_car_on_the_line_of_sight_changes_the_maps_at_least_five_times_more_than_a_static_wall() {
    let (name, text) = EMBEDDED_SCENARIOS
        .iter()
        .find(|(name, _)| *name == "train01")
        .unwrap();
    // The ideal rung: the thesis' flat-ground height slice (learn) is what this checks; on the
    // urban rung it needs the local ground estimate of the realism issue's item 5 first.
    let scenario =
        Scenario::from_toml_at_rung(text, "<embedded train01.toml>", name, Some(Realism::Ideal))
            .unwrap();
    let mut simulation = Simulation::new(&scenario, 7).unwrap();
    let params = FeatureParams::default();
    let (mut car_weights, mut wall_weights) = (Vec::new(), Vec::new());
    // Look at a few sweep pairs spread over the track until both kinds of points are seen.
    for index in (10..scenario.sweeps).step_by(15) {
        let previous = simulation.sweep(index - 1);
        let current = simulation.sweep(index);
        let features = SweepFeatures::compute(&previous, &current, &params).unwrap();
        let car = line_of_sight_car_points(&features, &current);
        let wall = wall_points(&features, &current);
        if car.len() >= 20 && wall.len() >= 20 {
            car_weights.push(mean_weight(&features, &car));
            wall_weights.push(mean_weight(&features, &wall));
        }
        if car_weights.len() >= 3 {
            break;
        }
    }
    assert!(
        !car_weights.is_empty(),
        "no sweep of train01 shows a car on the line of sight next to a wall"
    );
    let car = car_weights.iter().sum::<f64>() / car_weights.len() as f64;
    let wall = wall_weights.iter().sum::<f64>() / wall_weights.len() as f64;
    println!(
        "line-of-sight car {car:.4}, static wall {wall:.4}, ratio {:.1}",
        car / wall
    );
    assert!(car >= 5.0 * wall, "car {car:.4} vs wall {wall:.4}");
}
