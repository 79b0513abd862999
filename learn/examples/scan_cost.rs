//! What a whole scan costs per stage on a generated dataset, in CPU time: the features (the new
//! sweep's slice, maps, clusters; sweeps streamed in order as `evaluate` does) and each model's
//! whole-scan step (hypotheses, patches, GP prediction, merging), with the hypotheses' points
//! and map cells, every STEP-th scan. Runs on one thread (a one-thread rayon pool), so a loaded
//! machine hardly changes the figures; a scan's latency on two idle cores is at least half the
//! total.
//!
//! `cargo run --release -p patchflow-learn --example scan_cost -- DATASET STEP MODEL...`

use std::path::PathBuf;
use std::time::Instant;

use patchflow_dataset::Dataset;
use patchflow_learn::{MotionEstimator, ScanStream};

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

fn main() -> Result<(), Failure> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
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
    let mut step_s = Vec::new();
    pool.install(|| -> Result<(), Failure> {
        for info in dataset.sequences() {
            let reader = dataset.sequence(&info.name)?;
            // As `evaluate` runs: each sweep read and cut once, its slice kept for the next scan.
            let mut stream = ScanStream::new(&reader, vec![first.feature_params().clone()])?;
            while let Some((index, sweep)) = stream.read_next()? {
                let start = cpu_secs();
                let mut scans = stream.features_of(&sweep)?;
                let f = cpu_secs() - start;
                if index % step != 0 {
                    continue;
                }
                let features = scans.remove(0);
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
            }
        }
        Ok(())
    })?;
    println!(
        "{} scans, {} models, CPU ms (one thread):",
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
    println!("hypothesis cells                 {}", spread(&mut cells));
    println!("hypothesis points                {}", spread(&mut points));
    Ok(())
}
