//! Per-sweep feature pipeline on a realistic HDL-64E sweep pair (SPEC §8: perception per scan
//! under 50 ms with GP prediction; the feature part targets under 30 ms on 2 cores), and the
//! one-pass training-sample collection for two priors.
//!
//! The `ground` group times the ground estimate of one sweep and the sweep's height slice above
//! the flat and the estimated ground.
//!
//! `cargo bench -p patchflow-learn --bench features` runs on a synthetic street. With
//! `PATCHFLOW_BENCH_DATASET=<dir>` (e.g. the output of
//! `patchflow generate scenarios/train01.toml --out /tmp/t1 --seed 7`) the pipeline runs on
//! sweeps 60 and 61 of its first sequence instead, and `collect_priors` draws 1,600 samples for
//! the priors 0.01 and 0.5 from the whole dataset.

use std::hint::black_box;
use std::path::PathBuf;

use criterion::{Criterion, criterion_group, criterion_main};
use patchflow_dataset::{Dataset, Sweep};
use patchflow_learn::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
use patchflow_learn::{
    FeatureKind, FeatureParams, GroundGrid, GroundMode, HeightSlice, SampleSet, SweepFeatures,
};

/// The dataset named by `PATCHFLOW_BENCH_DATASET`, if any.
fn bench_dataset() -> Option<Dataset> {
    let dir = PathBuf::from(std::env::var_os("PATCHFLOW_BENCH_DATASET")?);
    Some(Dataset::open(&dir).expect("PATCHFLOW_BENCH_DATASET is not a dataset"))
}

/// Sweeps 60 and 61 (or the last two) of the dataset's first sequence.
fn dataset_sweeps(dataset: &Dataset) -> (Sweep, Sweep) {
    let info = dataset.sequences().first().expect("a sequence");
    let reader = dataset.sequence(&info.name).expect("sequence");
    let t = 61.min(reader.len() - 1);
    let read = |t| reader.read_sweep(t).expect("sweep");
    (read(t - 1), read(t))
}

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
    let dataset = bench_dataset();
    let (prev, curr) = dataset.as_ref().map_or_else(street_sweeps, dataset_sweeps);
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
    group.bench_function("maps_and_clusters_without_patches", |b| {
        b.iter(|| SweepFeatures::compute(black_box(&prev), black_box(&curr), &params))
    });
    group.bench_function("2000_heading_patches", |b| {
        b.iter(|| black_box(probe.heading_patches(&indices)))
    });
    group.finish();
    ground(c, &curr, &params);
    if let Some(dataset) = dataset {
        let mut group = c.benchmark_group("samples");
        group.sample_size(10);
        group.bench_function("collect_priors_1600_for_0.01_and_0.5", |b| {
            b.iter(|| {
                SampleSet::collect_priors(
                    &dataset,
                    &params,
                    &[0.01, 0.5],
                    FeatureKind::Patch,
                    1600,
                    1,
                    &|_, _| {},
                )
                .expect("samples")
            })
        });
        group.finish();
    }
}

/// The ground estimate of one sweep, and one sweep's height slice above the flat and above the
/// estimated ground (the estimate included).
fn ground(c: &mut Criterion, sweep: &Sweep, params: &FeatureParams) {
    let flat = FeatureParams {
        ground: GroundMode::Flat,
        ..params.clone()
    };
    let estimated = FeatureParams {
        ground: GroundMode::Estimated,
        ..params.clone()
    };
    let mut group = c.benchmark_group("ground");
    group.sample_size(30);
    group.bench_function("ground_estimate", |b| {
        b.iter(|| GroundGrid::estimate(black_box(sweep), params.half_extent_m).expect("ground"))
    });
    group.bench_function("slice_above_flat_ground", |b| {
        b.iter(|| HeightSlice::cut(black_box(sweep), &flat).expect("slice"))
    });
    group.bench_function("slice_above_estimated_ground", |b| {
        b.iter(|| HeightSlice::cut(black_box(sweep), &estimated).expect("slice"))
    });
    group.finish();
}

criterion_group!(benches, pipeline);
criterion_main!(benches);
