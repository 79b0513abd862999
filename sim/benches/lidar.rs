//! One labelled HDL-64E sweep (rolling shutter on) next to the bare Rapier `cast_ray` loop over
//! the same rays in the same scene on the same threads with the same split (one rayon task per
//! azimuth column at the finest): the ratio is the cost of labels, flow, noise, intensity, ego
//! motion removal and the rolling shutter (SPEC §8 target ≤ 1.25, and < 20 ms a sweep on 2 cores).
//! The ratio itself is printed by `cargo run --release -p patchflow-sim --example sweep_timing`.

use criterion::{Criterion, criterion_group, criterion_main};
use patchflow_sim::{EMBEDDED_SCENARIOS, QueryTree, Scenario, Simulation};

fn situation1() -> Simulation {
    let (name, text) = EMBEDDED_SCENARIOS[0];
    let scenario = Scenario::from_toml(text, name, name).expect("situation1 is valid");
    Simulation::new(&scenario, 0).expect("scene builds")
}

fn bench_lidar(c: &mut Criterion) {
    let mut sim = situation1();
    let index = 30;
    let start_secs = sim.stamp_secs(index);
    let mut group = c.benchmark_group("hdl64e_sweep");
    group.sample_size(30);
    group.bench_function("labelled_rolling_shutter", |b| {
        b.iter(|| sim.sweep(index).len())
    });
    // The same scene (moved to the sweep's reference instant, its ray-cast tree rebuilt as the
    // lidar does every sweep), the same rays from the same pose, through the same tree; then
    // through Rapier's own broad-phase BVH as the sweeps left it (same hits, other tree).
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

criterion_group!(benches, bench_lidar);
criterion_main!(benches);
