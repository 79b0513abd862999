//! Criterion benches of the baselines: ICP on a car-sized cluster pair.

use criterion::{Criterion, criterion_group, criterion_main};
use patchflow_eval::{IcpParams, align_icp};
use std::hint::black_box;

/// An L-shaped car outline of about 300 points (two visible sides, 1.5 cm spacing), moved by `t`.
fn car_cluster(t: [f64; 2]) -> Vec<[f64; 2]> {
    let mut points: Vec<[f64; 2]> = (0..300).map(|i| [i as f64 * 0.015, 0.0]).collect();
    points.extend((1..120).map(|i| [4.5, i as f64 * 0.015]));
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

criterion_group!(benches, bench_icp);
criterion_main!(benches);
