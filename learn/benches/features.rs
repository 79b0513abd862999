//! Per-sweep feature pipeline on a realistic synthetic HDL-64E sweep pair (SPEC §8: perception
//! per scan under 50 ms with GP prediction; the feature part targets under 30 ms on 2 cores).
//!
//! `cargo bench -p patchflow-learn --bench features`

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use patchflow_dataset::Sweep;
use patchflow_learn::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
use patchflow_learn::{FeatureParams, SweepFeatures};

/// A street: building rows on both sides, parked cars, and moving cars in both directions and
/// across; the ego drives along +x at 10 m/s.
fn street_sweeps() -> (Sweep, Sweep) {
    let mut boxes = Vec::new();
    for k in 0..8 {
        let x = -70.0 + 20.0 * f64::from(k);
        boxes.push(SceneBox::wall([x, 14.0], 0.0, [16.0, 6.0, 9.0]));
        boxes.push(SceneBox::wall([x + 6.0, -14.0], 0.0, [14.0, 6.0, 12.0]));
        boxes.push(SceneBox::wall([x + 3.0, -9.5], 0.0, [4.2, 1.8, 1.4]));
    }
    for (id, (x, y, yaw, speed)) in (1..).zip([
        (12.0, -3.0, 0.0, 9.0),
        (-15.0, -3.0, 0.0, 11.0),
        (25.0, 3.0, std::f64::consts::PI, 8.0),
        (6.0, 3.5, std::f64::consts::PI, 7.0),
        (-28.0, 3.0, std::f64::consts::PI, 10.0),
        (33.0, -6.0, 1.57, 4.0),
        (-6.0, 7.0, 0.1, 3.0),
        (40.0, -3.0, 0.0, 6.0),
    ]) {
        boxes.push(SceneBox::car(id, [x, y], yaw, speed));
    }
    let scene = SyntheticScene { boxes };
    let lidar = SyntheticLidar::hdl64e();
    let prev = scene.scan(&lidar, [-1.0, 0.0], 0.0, 0);
    let curr = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
    (prev, curr)
}

fn pipeline(c: &mut Criterion) {
    let (prev, curr) = street_sweeps();
    let params = FeatureParams::default();
    let probe = SweepFeatures::compute(&prev, &curr, &params).expect("features");
    let patches = probe.len().min(2000);
    eprintln!(
        "sweep: {} points, {} in the slice, {} clusters, {} patches per run",
        curr.len(),
        probe.len(),
        probe.clusters().len(),
        patches
    );
    let indices: Vec<usize> = (0..patches).collect();
    let mut group = c.benchmark_group("features");
    group.sample_size(20);
    group.bench_function("sweep_pipeline_with_2000_patches", |b| {
        b.iter(|| {
            let f = SweepFeatures::compute(black_box(&prev), black_box(&curr), &params)
                .expect("features");
            black_box(f.heading_patches(&indices))
        })
    });
    group.bench_function("maps_and_clusters_only", |b| {
        b.iter(|| SweepFeatures::compute(black_box(&prev), black_box(&curr), &params))
    });
    group.bench_function("2000_heading_patches", |b| {
        b.iter(|| black_box(probe.heading_patches(&indices)))
    });
    group.finish();
}

criterion_group!(benches, pipeline);
criterion_main!(benches);
