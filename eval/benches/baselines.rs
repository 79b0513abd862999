//! Criterion benches of the baselines: ICP on a car-sized cluster pair, and one step of the
//! KF-AUTO multi-target tracker over a scan with 50 clusters.

use criterion::{Criterion, criterion_group, criterion_main};
use patchflow_eval::{IcpParams, MultiTargetTracker, TrackerParams, align_icp};
use std::hint::black_box;

/// An L-shaped car outline of about 420 points (two visible sides, 1.5 cm spacing), moved by `t`,
/// with a deterministic sub-centimetre wobble so the sampling is not a perfect grid.
fn car_cluster(t: [f64; 2]) -> Vec<[f64; 2]> {
    let wobble = |i: usize| ((i as f64 * 12.9898).sin() * 43_758.545).fract() * 0.01;
    let mut points: Vec<[f64; 2]> = (0..300)
        .map(|i| [i as f64 * 0.015 + wobble(i), wobble(i + 7)])
        .collect();
    points.extend((1..120).map(|i| [4.5 + wobble(i + 3), i as f64 * 0.015]));
    points
        .iter()
        .map(|p| [p[0] + 20.0 + t[0], p[1] - 5.0 + t[1]])
        .collect()
}

fn bench_icp(c: &mut Criterion) {
    let source = car_cluster([0.0, 0.0]);
    let target = car_cluster([0.9, 0.2]);
    let params = IcpParams::default();
    c.bench_function("icp_car_cluster_420_points", |b| {
        b.iter(|| align_icp(black_box(&source), black_box(&target), &params))
    });
}

fn bench_tracker(c: &mut Criterion) {
    // 50 clusters on a 10 × 5 grid, 8 m apart, all moving at 5 m/s along +x; 20 warm-up scans.
    let centroids = |k: usize| -> Vec<[f64; 2]> {
        (0..50)
            .map(|i| {
                [
                    (i % 10) as f64 * 8.0 + 0.5 * k as f64,
                    (i / 10) as f64 * 8.0,
                ]
            })
            .collect()
    };
    let mut warm = MultiTargetTracker::new(TrackerParams::default()).expect("valid params");
    for k in 0..20 {
        warm.step(k, k as f64 * 0.1, &centroids(k))
            .expect("increasing stamps");
    }
    let next = centroids(20);
    c.bench_function("tracker_step_50_clusters", |b| {
        b.iter_batched(
            || warm.clone(),
            |mut tracker| tracker.step(20, 2.0, black_box(&next)),
            criterion::BatchSize::SmallInput,
        )
    });
}

criterion_group!(benches, bench_icp, bench_tracker);
criterion_main!(benches);
