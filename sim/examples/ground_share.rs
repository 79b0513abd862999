//! How much of a sweep is ground, per scenario (issue 9: under half in open streets), and how far
//! the road is from a plane: for every 5th sweep of each scenario, the share of points labelled
//! road, parking, sidewalk, other ground or terrain, and the standard deviation of the road
//! points' world height inside the sweep. Prints a Markdown table and one JSON object per
//! scenario. Every scenario is built with seed 7, as the README's figures.
//! `cargo run --release -p patchflow-sim --example ground_share [NAME|FILE.toml ...]`
//! (default: every embedded scenario).

use patchflow_sim::{EMBEDDED_SCENARIOS, Scenario, Simulation};

/// SemanticKITTI ground classes: road, parking, sidewalk, other-ground, terrain.
const GROUND: [u16; 5] = [40, 44, 48, 49, 72];
/// Every how many sweeps one is measured.
const STRIDE: u32 = 5;

fn load(name: &str) -> Result<Scenario, String> {
    if name.ends_with(".toml") {
        return Scenario::from_file(std::path::Path::new(name)).map_err(|e| e.to_string());
    }
    let (_, text) = EMBEDDED_SCENARIOS
        .iter()
        .find(|(n, _)| *n == name)
        .ok_or_else(|| format!("no embedded scenario {name}"))?;
    Scenario::from_toml(text, name, name).map_err(|e| e.to_string())
}

fn main() {
    let mut names: Vec<String> = std::env::args().skip(1).collect();
    if names.is_empty() {
        names = EMBEDDED_SCENARIOS
            .iter()
            .map(|(n, _)| n.to_string())
            .collect();
    }
    println!("| scenario | rung | ground share, mean (min-max) | road height std in a sweep |");
    println!("|---|---|---|---|");
    let mut json = Vec::new();
    for name in &names {
        let scenario = match load(name) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{e}");
                std::process::exit(1);
            }
        };
        let mut sim = match Simulation::new(&scenario, 7) {
            Ok(sim) => sim,
            Err(e) => {
                eprintln!("{e}");
                std::process::exit(1);
            }
        };
        let (mut shares, mut spreads) = (Vec::new(), Vec::new());
        for index in (0..scenario.sweeps).step_by(STRIDE as usize) {
            let sweep = sim.sweep(index);
            let n = sweep.labels.len().max(1) as f64;
            let ground = sweep
                .labels
                .iter()
                .filter(|l| GROUND.contains(&l.semantic()))
                .count() as f64;
            shares.push(ground / n);
            let pose = sim.world_from_sensor(index);
            let road_z: Vec<f64> = (0..sweep.points_in_sensor.len())
                .filter(|&i| sweep.labels[i].semantic() == 40)
                .map(|i| {
                    let [x, y, z] = sweep.points_in_sensor[i];
                    (pose * nalgebra::Point3::new(f64::from(x), f64::from(y), f64::from(z))).z
                })
                .collect();
            if road_z.len() > 1 {
                let mean = road_z.iter().sum::<f64>() / road_z.len() as f64;
                let var =
                    road_z.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / road_z.len() as f64;
                spreads.push(var.sqrt());
            }
        }
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
        let (lo, hi) = shares
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &s| (a.min(s), b.max(s)));
        println!(
            "| {} | {} | {:.0} % ({:.0}-{:.0} %) | {:.3} m |",
            scenario.name,
            scenario.realism,
            100.0 * mean(&shares),
            100.0 * lo,
            100.0 * hi,
            mean(&spreads)
        );
        json.push(format!(
            "{{\"scenario\": \"{}\", \"realism\": \"{}\", \"sweeps_measured\": {}, \"ground_share_mean\": {:.4}, \"ground_share_min\": {:.4}, \"ground_share_max\": {:.4}, \"road_height_std_m\": {:.4}, \"self_occluded_beams\": {:.4}}}",
            scenario.name,
            scenario.realism,
            shares.len(),
            mean(&shares),
            lo,
            hi,
            mean(&spreads),
            sim.lidar().self_occluded_share()
        ));
    }
    for line in json {
        println!("{line}");
    }
}
