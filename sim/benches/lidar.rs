//! One labelled HDL-64E sweep (rolling shutter on) next to the bare Rapier `cast_ray` loop over
//! the same rays in the same scene on the same threads: the ratio is the cost of labels, noise,
//! intensity and the rolling shutter (SPEC §8 target ≤ 1.25, and < 20 ms a sweep on 2 cores).

use criterion::{Criterion, criterion_group, criterion_main};
use patchflow_sim::{EMBEDDED_SCENARIOS, Scenario, Simulation};
use rapier3d::prelude::{Ray, Vector};
use rayon::prelude::*;

fn situation1() -> Simulation {
    let (name, text) = EMBEDDED_SCENARIOS[0];
    let scenario = Scenario::from_toml(text, name, name).expect("situation1 is valid");
    Simulation::new(&scenario, 0).expect("scene builds")
}

fn bench_lidar(c: &mut Criterion) {
    let mut sim = situation1();
    let index = 30;
    let mut group = c.benchmark_group("hdl64e_sweep");
    group.sample_size(30);
    group.bench_function("labelled_rolling_shutter", |b| {
        b.iter(|| sim.sweep(index).len())
    });

    // The bare loop: the same rays from the sensor pose at the sweep start, same scene, same
    // rayon split by azimuth column, nothing but `cast_ray`.
    let sim = situation1();
    let pose = sim.world_from_sensor(index);
    let origin = Vector::new(
        pose.translation.x as f32,
        pose.translation.y as f32,
        pose.translation.z as f32,
    );
    let rotation = pose.rotation;
    let channels = sim.lidar().config().channels as usize;
    let rays: Vec<Vector> = sim
        .lidar()
        .rays_in_sensor()
        .into_iter()
        .map(|d| {
            let w = rotation
                * nalgebra::Vector3::new(f64::from(d[0]), f64::from(d[1]), f64::from(d[2]));
            Vector::new(w.x as f32, w.y as f32, w.z as f32)
        })
        .collect();
    let max_range = sim.lidar().config().max_range_m as f32;
    let scene = sim.scene();
    group.bench_function("bare_cast_ray_loop", |b| {
        b.iter(|| {
            rays.par_chunks(channels)
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
                .sum::<usize>()
        })
    });
    group.finish();
}

criterion_group!(benches, bench_lidar);
criterion_main!(benches);
