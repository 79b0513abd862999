//! What a whole scan costs per stage on a generated dataset, in CPU time: the features (the new
//! sweep's slice, maps, clusters; sweeps streamed in order as `evaluate` does) and each model's
//! whole-scan step (hypotheses, patches, GP prediction, merging), with the hypotheses' points
//! and map cells, every STEP-th scan. Runs on one thread (a one-thread rayon pool), so a loaded
//! machine hardly changes the figures; a scan's latency on two idle cores is at least half the
//! total.
//!
//! On the first scan it also checks the whole-scan step's batched GP prediction
//! (`GpModel::predict_rows`) against the matrix path (`GpModel::predict`) on that scan's heading
//! rows, for each GP of each model, and prints the largest relative difference.
//!
//! `SCAN_COST_THREADS=2` runs the pool with two threads instead, to see the wall time a scan
//! takes on two cores (meaningful on idle cores only); CPU times then include both threads.
//!
//! `cargo run --release -p patchflow-learn --example scan_cost -- DATASET STEP MODEL...`

use std::path::PathBuf;
use std::time::Instant;

use nalgebra::DMatrix;
use patchflow_dataset::Dataset;
use patchflow_learn::{GpPrediction, MotionEstimator, ScanStream, SweepFeatures};

type Failure = Box<dyn std::error::Error + Send + Sync>;

/// CPU seconds of this process's threads (Linux `/proc/self/task/*/schedstat`).
fn cpu_secs() -> f64 {
    let mut nanos = 0u64;
    for task in std::fs::read_dir("/proc/self/task")
        .into_iter()
        .flatten()
        .flatten()
    {
        if let Ok(text) = std::fs::read_to_string(task.path().join("schedstat")) {
            nanos += text
                .split_whitespace()
                .next()
                .and_then(|v| v.parse().ok())
                .unwrap_or(0);
        }
    }
    nanos as f64 * 1e-9
}

fn spread(v: &mut [f64]) -> String {
    if v.is_empty() {
        return "-".into();
    }
    v.sort_by(f64::total_cmp);
    format!(
        "median {:7.1} worst {:7.1}",
        v[v.len() / 2] * 1e3,
        v[v.len() - 1] * 1e3
    )
}

/// Largest differences between two predictions: of the means relative to the larger of the
/// mean and the predictive standard deviation (a mean near zero is a sum of terms that cancel,
/// so its own magnitude is no scale for rounding), of the latent and noisy variances relative to
/// their values.
fn worst_relative(a: &GpPrediction, b: &GpPrediction) -> [f64; 3] {
    let relative = |u: f64, v: f64, scale: f64| (u - v).abs() / u.abs().max(v.abs()).max(scale);
    let worst = |values: &mut dyn Iterator<Item = f64>| values.fold(0.0, f64::max);
    let mean = (0..a.mean.len()).map(|i| relative(a.mean[i], b.mean[i], a.var_y[i].sqrt()));
    let latent = (0..a.mean.len()).map(|i| relative(a.var_latent[i], b.var_latent[i], 1e-300));
    let noisy = (0..a.mean.len()).map(|i| relative(a.var_y[i], b.var_y[i], 1e-300));
    [
        worst(&mut { mean }),
        worst(&mut { latent }),
        worst(&mut { noisy }),
    ]
}

/// The batched prediction against the matrix path on the heading rows of every hypothesis cell.
fn check_batched(model: &MotionEstimator, features: &SweepFeatures) -> Result<[f64; 3], Failure> {
    let mut rows = Vec::new();
    for c in features.object_hypotheses() {
        for &xy in &features
            .cell_samples(features.clusters().members(c))
            .positions
        {
            rows.extend(features.patch_at(xy, features.bearing_at(xy)).values);
        }
    }
    let n = rows.len() / patchflow_learn::PATCH_LEN;
    let x = DMatrix::from_row_slice(n, patchflow_learn::PATCH_LEN, &rows);
    let mut worst = [0.0_f64; 3];
    for gp in model.gps() {
        let w = worst_relative(&gp.predict_rows(&rows)?, &gp.predict(&x)?);
        for (a, b) in worst.iter_mut().zip(w) {
            *a = a.max(b);
        }
    }
    Ok(worst)
}

fn main() -> Result<(), Failure> {
    let threads = std::env::var("SCAN_COST_THREADS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let mut args = std::env::args().skip(1);
    let root = PathBuf::from(
        args.next()
            .ok_or("usage: scan_cost DATASET STEP MODEL...")?,
    );
    let step: usize = args.next().ok_or("STEP")?.parse()?;
    let models: Vec<MotionEstimator> = args
        .map(|m| MotionEstimator::load(&PathBuf::from(m)))
        .collect::<Result<_, _>>()?;
    let first = models.first().ok_or("give at least one model")?;
    let dataset = Dataset::open(&root)?;
    let (mut features_s, mut whole_s, mut cells, mut points) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut stages: [Vec<f64>; 4] = Default::default();
    let (mut step_s, mut wall_s) = (Vec::new(), Vec::new());
    pool.install(|| -> Result<(), Failure> {
        for info in dataset.sequences() {
            let reader = dataset.sequence(&info.name)?;
            // As `evaluate` runs: each sweep read and cut once, its slice kept for the next scan.
            let mut stream = ScanStream::new(&reader, vec![first.feature_params().clone()])?;
            while let Some((index, sweep)) = stream.read_next()? {
                let (start, scan_wall) = (cpu_secs(), Instant::now());
                let mut scans = stream.features_of(&sweep)?;
                let f = cpu_secs() - start;
                if index % step != 0 {
                    continue;
                }
                let features = scans.remove(0);
                if whole_s.is_empty() {
                    let patch_models = models
                        .iter()
                        .filter(|m| m.feature_kind() == patchflow_learn::FeatureKind::Patch);
                    for model in patch_models {
                        let [mean, latent, noisy] = check_batched(model, &features)?;
                        println!(
                            "batched vs matrix GP prediction, largest relative difference: mean {mean:.1e} (of the larger of mean and predictive sd), latent variance {latent:.1e}, variance with noise {noisy:.1e}"
                        );
                    }
                }
                let mut whole = f;
                for (k, model) in models.iter().enumerate() {
                    let (cpu, wall) = (cpu_secs(), Instant::now());
                    let motion = model.estimate_features(&features)?;
                    let (cpu, wall) = (cpu_secs() - cpu, wall.elapsed().as_secs_f64());
                    let tm = motion.timing;
                    whole += cpu;
                    if k == 0 {
                        // The step's CPU time shared out by the stages' wall times.
                        for (s, v) in stages.iter_mut().zip([
                            tm.hypotheses_secs,
                            tm.patches_secs,
                            tm.gp_secs,
                            tm.merge_secs,
                        ]) {
                            s.push(v / wall * cpu);
                        }
                        cells.push(tm.rows as f64 / 1e3);
                        points.push(tm.points as f64 / 1e3);
                        step_s.push(cpu);
                    }
                }
                features_s.push(f);
                whole_s.push(whole);
                wall_s.push(scan_wall.elapsed().as_secs_f64());
            }
        }
        Ok(())
    })?;
    println!(
        "{} scans, {} models, CPU ms ({threads} thread(s)):",
        whole_s.len(),
        models.len()
    );
    println!(
        "features (new slice, maps, clusters) {}",
        spread(&mut features_s)
    );
    for (name, v) in ["hypotheses", "patches", "GP", "merge"]
        .iter()
        .zip(stages.iter_mut())
    {
        println!("first model {name:<22} {}", spread(v));
    }
    println!("first model step                 {}", spread(&mut step_s));
    println!("whole scan, every model          {}", spread(&mut whole_s));
    println!("whole scan, wall                 {}", spread(&mut wall_s));
    println!("hypothesis cells                 {}", spread(&mut cells));
    println!("hypothesis points                {}", spread(&mut points));
    Ok(())
}
