//! Criterion bench of one occupancy map (fit and prediction over the query lattice, SPEC §8) of
//! each method on the DGPOM T-junction at query time t = 5 (the scans at t = 2 … 5), with the
//! bench's settings; DGPOM on the motion map learned from the training run `dgpom_tjunction_train`
//! (learned once, outside the timing). Prints the training and query points per map first.

use criterion::{Criterion, criterion_group, criterion_main};
use patchflow_dataset::Dataset;
use patchflow_eval::{learn_motion_map, occupancy_methods};
use patchflow_occupancy::{OccupancyParams, OccupancySequence, QueryGrid, ScanWindow};
use patchflow_sim::{GenerateOptions, ScenarioSource, Shard, generate_dataset};
use std::hint::black_box;
use std::sync::Arc;

/// The generated T-junction and its training run (seed 7), in a temporary folder kept for the
/// bench's lifetime.
fn tjunction() -> (tempfile::TempDir, OccupancySequence, OccupancySequence) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let sources = ["dgpom_tjunction", "dgpom_tjunction_train"]
        .map(|n| ScenarioSource::from_argument(std::path::Path::new(n)).expect("embedded"));
    let options = GenerateOptions {
        realism: None,
        out: dir.path().to_owned(),
        seed: 7,
        shard: Shard::ALL,
        overwrite: false,
    };
    generate_dataset(&sources, &options, &|_| {}).expect("generates");
    let dataset = Dataset::open(dir.path()).expect("opens");
    let load = |name: &str| {
        OccupancySequence::load(&dataset.sequence(name).expect("sequence")).expect("loads")
    };
    let (sequence, training) = (load("dgpom_tjunction"), load("dgpom_tjunction_train"));
    (dir, sequence, training)
}

fn bench_one_map(c: &mut Criterion) {
    let (_dir, sequence, training) = tjunction();
    let motion_map = learn_motion_map(&training).expect("learns the motion map");
    let params = OccupancyParams::default();
    let t = 5;
    let window = ScanWindow {
        scans: &sequence.scans[t + 1 - params.scans_per_map..=t],
        query_secs: sequence.scans[t].stamp_secs,
    };
    let grid = QueryGrid::observed_by(
        &sequence.scans[t],
        &sequence.sensor,
        params.query_spacing_m,
        &sequence.truth,
        sequence.scan_height_m(),
    );
    let mut group = c.benchmark_group("occupancy_map_tjunction_t5");
    group.sample_size(10);
    let samples = patchflow_eval::SequenceKind::Planar.sample_params(7);
    // A fresh method per iteration: DGPOM keeps its fits, and the bench times one fit each.
    let fresh = |i: usize| occupancy_methods(&samples, Some(Arc::clone(&motion_map))).remove(i);
    let count = occupancy_methods(&samples, Some(Arc::clone(&motion_map))).len();
    for i in 0..count {
        let method = fresh(i);
        let output = method.map(&window, &grid.points_m).expect("maps");
        println!(
            "{}: {} training points, {} query points; {}",
            method.id().name(),
            output.training_points,
            grid.len(),
            output.summary
        );
        group.bench_function(method.id().name(), |b| {
            b.iter_batched(
                || fresh(i),
                |m| m.map(black_box(&window), black_box(&grid.points_m)),
                criterion::BatchSize::PerIteration,
            )
        });
    }
    group.finish();
}

criterion_group!(benches, bench_one_map);
criterion_main!(benches);
