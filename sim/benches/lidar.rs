//! One labelled HDL-64E sweep (rolling shutter on) next to the bare Rapier `cast_ray` loop over
//! the same rays in the same scene on the same threads with the same split (one rayon task per
//! azimuth column at the finest), on situation1, train03 and situation5 (the `urban` rung): the
//! ratio is the cost of labels, flow, the realistic return (ray drop, noise, intensity, glass,
//! foliage, mixed pixels), ego motion removal and the rolling shutter (SPEC §8 target ≤ 1.25,
//! and < 20 ms a sweep on 2 cores). CPU-time ratios, steadier on a shared machine than these
//! wall times, are printed by `cargo run --release -p patchflow-sim --example sweep_timing NAME`.

use criterion::{Criterion, criterion_group, criterion_main};
use patchflow_sim::{EMBEDDED_SCENARIOS, QueryTree, Scenario, Simulation};

/// The scenarios compared, as in docs/speed.md's simulation-speed table.
const SCENARIOS: [&str; 3] = ["situation1", "train03", "situation5"];

fn simulation(name: &str) -> (Simulation, u32) {
    let (_, text) = EMBEDDED_SCENARIOS
        .iter()
        .find(|(n, _)| *n == name)
        .expect("an embedded scenario");
    let scenario = Scenario::from_toml(text, name, name).expect("embedded scenarios are valid");
    let index = scenario.sweeps / 2;
    (Simulation::new(&scenario, 0).expect("scene builds"), index)
}

fn bench_lidar(c: &mut Criterion) {
    for name in SCENARIOS {
        let (mut sim, index) = simulation(name);
        let start_secs = sim.stamp_secs(index);
        let mut group = c.benchmark_group(format!("hdl64e_sweep_{name}"));
        group.sample_size(30);
        group.bench_function("labelled_rolling_shutter", |b| {
            b.iter(|| sim.sweep(index).len())
        });
        // The same scene (moved to the sweep's reference instant, its ray-cast tree rebuilt as
        // the lidar does every sweep), the same rays from the same pose, through the same tree;
        // then through Rapier's own broad-phase BVH as the sweeps left it (same hits, other tree).
        sim.scene_mut().move_to(start_secs);
        sim.scene_mut().rebuild_ray_tree();
        let (lidar, scene) = (sim.lidar(), sim.scene());
        group.bench_function("bare_cast_ray_loop", |b| {
            b.iter(|| lidar.bare_cast_ray_hits(scene, start_secs, QueryTree::RayCast))
        });
        group.bench_function("bare_cast_ray_loop_rapier_broad_phase_bvh", |b| {
            b.iter(|| lidar.bare_cast_ray_hits(scene, start_secs, QueryTree::RapierBroadPhase))
        });
        group.finish();
    }
}

criterion_group!(benches, bench_lidar);
criterion_main!(benches);
