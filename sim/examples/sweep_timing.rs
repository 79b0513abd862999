//! Where a labelled sweep spends its time, robust to a loaded machine (minimum over alternating
//! repetitions): the labelled rolling-shutter sweep, the same sweep at one instant, the bare
//! `cast_ray` loop over the same rays in the same scene on the same threads (through the scene's
//! ray-cast tree, as the lidar, and through Rapier's own broad-phase BVH in the state the sweeps
//! left it), and the scene moves alone; prints the labelled / bare ratio (SPEC §8: ≤ 1.25).
//! `cargo run --release -p patchflow-sim --example sweep_timing [NAME|FILE.toml] [REPETITIONS]`
//! (an embedded scenario by name, or a scenario file).

use std::time::Instant;

use patchflow_sim::{EMBEDDED_SCENARIOS, QueryTree, Scenario, Simulation};

/// CPU seconds of all of this process's threads so far: the sum of each thread's time on a CPU
/// (Linux `/proc/self/task/*/schedstat`, nanoseconds, so one call can be timed); `None` where
/// not readable.
fn process_cpu_secs() -> Option<f64> {
    let mut nanos = 0u64;
    for task in std::fs::read_dir("/proc/self/task").ok()?.flatten() {
        let Ok(text) = std::fs::read_to_string(task.path().join("schedstat")) else {
            continue;
        };
        nanos += text.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(nanos as f64 * 1e-9)
}

/// CPU seconds that `work` takes (all threads), with its result.
fn cpu_secs_of<T>(work: impl FnOnce() -> T) -> (Option<f64>, T) {
    let before = process_cpu_secs();
    let out = work();
    let spent = process_cpu_secs()
        .zip(before)
        .map(|(after, before)| after - before);
    (spent, out)
}

/// Minimum and median of `samples`, `None` if empty.
fn min_and_median(samples: &mut [f64]) -> Option<(f64, f64)> {
    samples.sort_by(f64::total_cmp);
    Some((*samples.first()?, samples[samples.len() / 2]))
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
    // CPU seconds (all threads) of each labelled sweep and each bare loop, taken alternately:
    // on a machine shared with other jobs the load drifts, and alternating calls see the same
    // load, where the wall-clock minimum does not.
    let (mut cpu_labelled, mut cpu_bare) = (Vec::new(), Vec::new());
    for _ in 0..repetitions {
        let start = Instant::now();
        // The sweep is dropped inside the timed call, as a caller that writes it out would.
        let (cpu, sweep_points) = cpu_secs_of(|| sim.sweep(index).len());
        labelled = labelled.min(start.elapsed().as_secs_f64());
        points = sweep_points;
        cpu_labelled.extend(cpu);

        let start = Instant::now();
        std::hint::black_box(one_instant.sweep(index).len());
        one = one.min(start.elapsed().as_secs_f64());

        sim.scene_mut().move_to(t0);
        sim.scene_mut().rebuild_ray_tree();
        let start = Instant::now();
        let (cpu, bare_hits) = cpu_secs_of(|| {
            sim.lidar()
                .bare_cast_ray_hits(sim.scene(), t0, QueryTree::RayCast)
        });
        bare = bare.min(start.elapsed().as_secs_f64());
        hits = bare_hits;
        cpu_bare.extend(cpu);

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
    if let (Some((l_min, l_median)), Some((b_min, b_median))) = (
        min_and_median(&mut cpu_labelled),
        min_and_median(&mut cpu_bare),
    ) {
        println!(
            "{name} CPU time per sweep (all threads, min / median of {repetitions} alternating calls): labelled {:.1} / {:.1} ms, bare cast_ray loop {:.1} / {:.1} ms, ratio {:.2} (of the medians {:.2}); on 2 cores at full use a labelled sweep takes {:.1} ms (median; {:.1} × real time at {} Hz)",
            l_min * 1e3,
            l_median * 1e3,
            b_min * 1e3,
            b_median * 1e3,
            l_min / b_min,
            l_median / b_median,
            l_median * 1e3 / 2.0,
            scenario.lidar.period_secs() / (l_median / 2.0),
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
