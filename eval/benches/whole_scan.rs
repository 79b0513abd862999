//! Criterion bench of the whole-scan perception (SPEC §8: a whole scan under 100 ms on 2 cores):
//! thesis Algorithm 3.1 on every object hypothesis of a scan of the dense random-traffic scene
//! (`scenarios/dense_traffic.toml`, its first sweeps generated in the setup), split into the
//! features (slice, maps, clusters) and one estimator's step (patches, GP prediction, merging).
//!
//! A last case times the whole learned scan of issue 27: features, one estimator's step, the
//! moving classifier, GP-KF and GP-ICP ([`LearnedPerception`], primed on the scan before).
//!
//! `cargo bench -p patchflow-eval --bench whole_scan`. The estimator is trained in the setup with
//! the default's 100 pseudo-inputs and 242 patch values (what prediction costs depend on) but few
//! iterations; `PATCHFLOW_BENCH_MODEL=<model.json>` loads a trained one instead (e.g.
//! `results/bench/models/spgp-het.json`), and `PATCHFLOW_BENCH_DATASET=<dir>` benches sweeps 60
//! and 61 (or the last two) of that dataset's first sequence instead of the dense scene.

use std::hint::black_box;
use std::path::PathBuf;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use patchflow_dataset::{Dataset, Sweep};
use patchflow_eval::{BaselineParams, DENSE_TRAFFIC_TOML, LearnedPerception};
use patchflow_learn::{
    ChangeEvidence, EstimatorParams, GpKind, HeightSlice, MotionEstimator, MovingClassifier,
    MovingParams, SweepFeatures,
};
use patchflow_sim::{GenerateOptions, ScenarioSource, Shard, generate_dataset};

/// The dataset to bench on: `PATCHFLOW_BENCH_DATASET`, or the dense scene's first four sweeps.
fn dataset(dir: &std::path::Path) -> Dataset {
    if let Some(path) = std::env::var_os("PATCHFLOW_BENCH_DATASET") {
        return Dataset::open(&PathBuf::from(path))
            .expect("PATCHFLOW_BENCH_DATASET is not a dataset");
    }
    let scenario = dir.join("dense_traffic.toml");
    std::fs::write(
        &scenario,
        DENSE_TRAFFIC_TOML.replace("sweeps = 30", "sweeps = 4"),
    )
    .expect("writing the scenario");
    let options = GenerateOptions {
        realism: None,
        out: dir.join("data"),
        seed: 7,
        shard: Shard::ALL,
        overwrite: false,
    };
    generate_dataset(&[ScenarioSource::File(scenario)], &options, &|_| {}).expect("generating");
    Dataset::open(&options.out).expect("opening the generated dataset")
}

/// Three consecutive sweeps: 59 to 61 of the first sequence, or its last three.
fn sweeps(dataset: &Dataset) -> (Sweep, Sweep, Sweep) {
    let info = dataset.sequences().first().expect("a sequence");
    let reader = dataset.sequence(&info.name).expect("sequence");
    let t = 61.min(reader.len() - 1);
    let read = |t| reader.read_sweep(t).expect("sweep");
    (read(t - 2), read(t - 1), read(t))
}

/// `PATCHFLOW_BENCH_MODEL`, or an SPGP-HET estimator of the default's size fitted briefly.
fn estimator(dataset: &Dataset) -> MotionEstimator {
    if let Some(path) = std::env::var_os("PATCHFLOW_BENCH_MODEL") {
        return MotionEstimator::load(&PathBuf::from(path)).expect("PATCHFLOW_BENCH_MODEL");
    }
    let params = EstimatorParams {
        gp: GpKind::SpgpHet,
        samples: 300,
        pseudo_inputs: 100,
        max_iters: 3,
        ..EstimatorParams::default()
    };
    MotionEstimator::train(dataset, &params).expect("training")
}

fn whole_scan(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let dataset = dataset(dir.path());
    let (before, prev, curr) = sweeps(&dataset);
    let estimator = estimator(&dataset);
    let moving = MovingClassifier::train(
        &dataset,
        estimator.feature_params(),
        &MovingParams::default(),
    )
    .expect("training the moving classifier");
    let params = estimator.feature_params().clone();
    let probe = estimator.estimate_scan(&prev, &curr).expect("scan");
    eprintln!(
        "scan: {} sliced points, {} clusters, {} hypotheses with {} points in {} map cells",
        probe.features.len(),
        probe.features.clusters().len(),
        probe.motion.timing.clusters,
        probe.motion.timing.points,
        probe.motion.timing.rows
    );
    let mut group = c.benchmark_group("whole_scan");
    group.sample_size(10);
    group.bench_function("features_slice_maps_clusters", |b| {
        b.iter(|| SweepFeatures::compute(black_box(&prev), black_box(&curr), &params))
    });
    group.bench_function("one_estimator_step_on_every_hypothesis", |b| {
        b.iter(|| estimator.estimate_features(black_box(&probe.features)))
    });
    group.bench_function("whole_scan_one_estimator", |b| {
        b.iter(|| estimator.estimate_scan(black_box(&prev), black_box(&curr)))
    });
    let earlier = SweepFeatures::compute(&before, &prev, &params).expect("features");
    let valid = params.check().expect("parameters");
    let slice = |s| HeightSlice::cut(s, &valid).expect("slice");
    let change_before = ChangeEvidence::build(&slice(&before), &slice(&prev), &valid);
    let (before_slice, curr_slice) = (slice(&before), slice(&curr));
    let primed = || {
        let mut perception =
            LearnedPerception::new(&estimator, Some(&moving), &BaselineParams::default())
                .expect("perception");
        perception
            .step(&earlier, &change_before, prev.stamp_secs)
            .expect("the scan before");
        perception
    };
    group.bench_function("whole_learned_scan_segmentation_gp_kf_gp_icp", |b| {
        b.iter_batched(
            primed,
            |mut perception| {
                let features = SweepFeatures::compute(black_box(&prev), black_box(&curr), &params)
                    .expect("features");
                // The observed change since the sweep before is per-scan work too.
                let change = ChangeEvidence::build(&before_slice, &curr_slice, &valid);
                perception
                    .step(&features, &change, curr.stamp_secs)
                    .expect("scan")
            },
            BatchSize::SmallInput,
        )
    });
    group.finish();
}

criterion_group!(benches, whole_scan);
criterion_main!(benches);
