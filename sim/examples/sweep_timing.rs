//! Where a labelled sweep spends its time, robust to a loaded machine (minimum over alternating
//! repetitions): the labelled rolling-shutter sweep, the same sweep at one instant, the bare
//! `cast_ray` loop over the same rays in the same scene on the same threads (through the scene's
//! ray-cast tree, as the lidar, and through Rapier's own broad-phase BVH in the state the sweeps
//! left it), and the scene moves alone; prints the labelled / bare ratio (SPEC §8: ≤ 1.25).
//! `cargo run --release -p patchflow-sim --example sweep_timing [NAME|FILE.toml] [REPETITIONS]`
//! (an embedded scenario by name, or a scenario file).

use std::time::Instant;

use patchflow_sim::{EMBEDDED_SCENARIOS, QueryTree, Scenario, Simulation};

/// Process CPU seconds (user + system, all threads) per call of `work`, over `n` calls; `None`
/// where `/proc/self/stat` is not readable.
fn cpu_secs_per(n: usize, mut work: impl FnMut()) -> Option<f64> {
    let before = process_cpu_secs()?;
    for _ in 0..n {
        work();
    }
    Some((process_cpu_secs()? - before) / n.max(1) as f64)
}

/// User + system CPU seconds of this process so far (Linux `/proc/self/stat`, 100 ticks a second).
fn process_cpu_secs() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let ticks: f64 = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

fn main() {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "situation1".to_owned());
    let repetitions: usize = args.next().and_then(|r| r.parse().ok()).unwrap_or(15);
    let loaded = if name.ends_with(".toml") {
        Scenario::from_file(std::path::Path::new(&name))
    } else {
        let Some((_, text)) = EMBEDDED_SCENARIOS.iter().find(|(n, _)| *n == name) else {
            eprintln!("no embedded scenario {name}");
            std::process::exit(1);
        };
        Scenario::from_toml(text, &name, &name)
    };
    let scenario = match loaded {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    let mut one_instant_scenario = scenario.clone();
    one_instant_scenario.lidar.rolling_shutter = false;
    let (Ok(mut sim), Ok(mut one_instant)) = (
        Simulation::new(&scenario, 0),
        Simulation::new(&one_instant_scenario, 0),
    ) else {
        eprintln!("scene {name} does not build");
        std::process::exit(1);
    };
    let index = scenario.sweeps / 2;
    println!(
        "{name}: {} colliders, realism {}",
        sim.scene().collider_count(),
        scenario.realism
    );
    let t0 = sim.stamp_secs(index);
    let blocks = scenario.lidar.blocks;
    let (mut labelled, mut bare, mut one, mut moves) = (f64::MAX, f64::MAX, f64::MAX, f64::MAX);
    let mut bare_rapier = f64::MAX;
    let (mut points, mut hits) = (0, 0);
    for _ in 0..repetitions {
        let start = Instant::now();
        points = sim.sweep(index).len();
        labelled = labelled.min(start.elapsed().as_secs_f64());

        let start = Instant::now();
        std::hint::black_box(one_instant.sweep(index).len());
        one = one.min(start.elapsed().as_secs_f64());

        sim.scene_mut().move_to(t0);
        sim.scene_mut().rebuild_ray_tree();
        let start = Instant::now();
        hits = sim
            .lidar()
            .bare_cast_ray_hits(sim.scene(), t0, QueryTree::RayCast);
        bare = bare.min(start.elapsed().as_secs_f64());

        let start = Instant::now();
        let rapier_hits =
            sim.lidar()
                .bare_cast_ray_hits(sim.scene(), t0, QueryTree::RapierBroadPhase);
        bare_rapier = bare_rapier.min(start.elapsed().as_secs_f64());
        assert_eq!(rapier_hits, hits, "both trees give the same hits");

        let start = Instant::now();
        for b in 0..blocks {
            sim.scene_mut()
                .move_to(t0 + 0.1 * f64::from(b) / f64::from(blocks));
        }
        moves = moves.min(start.elapsed().as_secs_f64());
    }
    // CPU seconds (all threads) per labelled sweep and per bare loop, from the process's own
    // counters: robust on a machine shared with other jobs, where the wall-clock minimum is not.
    let cpu_labelled = cpu_secs_per(repetitions, || {
        std::hint::black_box(sim.sweep(index).len());
    });
    sim.scene_mut().move_to(t0);
    sim.scene_mut().rebuild_ray_tree();
    let cpu_bare = cpu_secs_per(repetitions, || {
        std::hint::black_box(
            sim.lidar()
                .bare_cast_ray_hits(sim.scene(), t0, QueryTree::RayCast),
        );
    });
    if let (Some(l), Some(b)) = (cpu_labelled, cpu_bare) {
        println!(
            "{name} CPU time per sweep (all threads): labelled {:.1} ms, bare cast_ray loop {:.1} ms, ratio {:.2}; on 2 cores at full use a labelled sweep takes {:.1} ms ({:.1} × real time at {} Hz)",
            l * 1e3,
            b * 1e3,
            l / b,
            l * 1e3 / 2.0,
            scenario.lidar.period_secs() / (l / 2.0),
            scenario.lidar.rate_hz
        );
    }
    println!(
        "{name} ({} threads, best of {repetitions}): labelled {:.2} ms ({points} points), bare cast_ray loop {:.2} ms ({hits} hits), ratio {:.2}; bare through Rapier's broad-phase BVH {:.2} ms (ratio {:.2}); labelled at one instant {:.2} ms; {blocks} scene moves {:.2} ms",
        rayon::current_num_threads(),
        labelled * 1e3,
        bare * 1e3,
        labelled / bare,
        bare_rapier * 1e3,
        labelled / bare_rapier,
        one * 1e3,
        moves * 1e3
    );
}
