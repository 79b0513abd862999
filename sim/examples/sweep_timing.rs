//! Where a labelled sweep spends its time, robust to a loaded machine (minimum over alternating
//! repetitions): the labelled rolling-shutter sweep, the bare `cast_ray` loop over the same rays,
//! and the 60 scene moves alone. `cargo run --release -p patchflow-sim --example sweep_timing [NAME]`.

use std::time::Instant;

use patchflow_sim::{EMBEDDED_SCENARIOS, Scenario, Simulation};
use rapier3d::prelude::{Ray, Vector};
use rayon::prelude::*;

fn main() {
    let name = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "situation1".to_owned());
    let Some((_, text)) = EMBEDDED_SCENARIOS.iter().find(|(n, _)| *n == name) else {
        eprintln!("no embedded scenario {name}");
        std::process::exit(1);
    };
    let scenario = match Scenario::from_toml(text, &name, &name) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    let Ok(mut sim) = Simulation::new(&scenario, 0) else {
        return;
    };
    let mut one_instant_scenario = scenario.clone();
    one_instant_scenario.lidar.rolling_shutter = false;
    let Ok(mut one_instant) = Simulation::new(&one_instant_scenario, 0) else {
        return;
    };
    let mut one = f64::MAX;
    let index = scenario.sweeps / 2;
    let pose = sim.world_from_sensor(index);
    let origin = Vector::new(
        pose.translation.x as f32,
        pose.translation.y as f32,
        pose.translation.z as f32,
    );
    let rays: Vec<Vector> = sim
        .lidar()
        .rays_in_sensor()
        .into_iter()
        .map(|d| {
            let w = pose.rotation
                * nalgebra::Vector3::new(f64::from(d[0]), f64::from(d[1]), f64::from(d[2]));
            Vector::new(w.x as f32, w.y as f32, w.z as f32)
        })
        .collect();
    let channels = scenario.lidar.channels as usize;
    let max_range = scenario.lidar.max_range_m as f32;
    let blocks = scenario.lidar.blocks;
    let (mut labelled, mut bare, mut moves) = (f64::MAX, f64::MAX, f64::MAX);
    let mut points = 0;
    for _ in 0..15 {
        let start = Instant::now();
        points = sim.sweep(index).len();
        labelled = labelled.min(start.elapsed().as_secs_f64());
        let start = Instant::now();
        std::hint::black_box(one_instant.sweep(index).len());
        one = one.min(start.elapsed().as_secs_f64());
        let start = Instant::now();
        let scene = sim.scene();
        let hits: usize = rays
            .par_chunks(channels)
            .map(|column| {
                let qp = scene.query_pipeline();
                column
                    .iter()
                    .filter(|d| {
                        qp.cast_ray(&Ray::new(origin, **d), max_range, true)
                            .is_some()
                    })
                    .count()
            })
            .sum();
        bare = bare.min(start.elapsed().as_secs_f64());
        std::hint::black_box(hits);
        let start = Instant::now();
        let t0 = sim.stamp_secs(index);
        for b in 0..blocks {
            sim.scene_mut()
                .move_to(t0 + 0.1 * f64::from(b) / f64::from(blocks));
        }
        moves = moves.min(start.elapsed().as_secs_f64());
    }
    println!(
        "{name}: labelled {:.2} ms ({points} points), bare cast_ray loop {:.2} ms, ratio {:.2}; {blocks} scene moves {:.2} ms; labelled at one instant {:.2} ms",
        labelled * 1e3,
        bare * 1e3,
        labelled / bare,
        moves * 1e3,
        one * 1e3
    );
}
