//! How well the moving/static classifier segments the situations' scans (issue 27): trains it on
//! the training tracks of a `bench --keep-data` folder (as `bench` does: seed 7, the default
//! estimator's maps), then scores per point on every situation, as LiDAR-MOS does (every sliced
//! point of every scan; a point is predicted moving when its cluster is an object hypothesis
//! decided moving): the moving class's precision, recall and IoU at the classifier's own
//! threshold, the IoU at other thresholds, and the static points called moving by their
//! SemanticKITTI class.
//!
//! `cargo run --release -p patchflow-learn --example moving_check -- BENCH_OUT` (`SEED`,
//! `MAX_ROWS`, `MAX_SCANS`, `DRAWS` override the training parameters; `BELIEF=γ` smooths the
//! probabilities along the clusters' tracks, `TARGET=1` prints the target's per scan).
//! `MEMORIES=γ1,γ2,… SPLIT=train|situations [THRESHOLDS=t1,…]` instead scores every memory (and
//! threshold) in one pass over the split: how `BELIEF_MEMORY` was chosen on the training tracks.

use std::collections::BTreeMap;
use std::path::PathBuf;

use patchflow_dataset::Dataset;
use patchflow_learn::{
    ChangeEvidence, EstimatorParams, FeatureParams, MOVING_SPEED_MPS, MovingBelief,
    MovingClassifier, MovingParams, ScanStream,
};

type Failure = Box<dyn std::error::Error>;

/// One scored cluster: probability, moving points, static points, class of its first point.
type Scored = (f64, u64, u64, u16);

fn main() -> Result<(), Failure> {
    let root = PathBuf::from(
        std::env::args()
            .nth(1)
            .ok_or("usage: moving_check BENCH_OUT")?,
    );
    // The maps `bench` trains and runs the classifier on: the default estimator's.
    let params = EstimatorParams::default().features;
    let train = Dataset::open(&root.join("data/train"))?;
    let env = |name: &str, default: usize| {
        std::env::var(name)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let defaults = MovingParams::default();
    let moving_params = MovingParams {
        seed: env("SEED", 7) as u64,
        max_rows: env("MAX_ROWS", defaults.max_rows),
        max_scans: env("MAX_SCANS", defaults.max_scans),
        draws: env("DRAWS", defaults.draws),
    };
    let labelled = MovingClassifier::labelled_clusters(&train, &params, &moving_params)?;
    let classifier = &MovingClassifier::fit(labelled, &moving_params)?;
    println!(
        "fitted {} draws of (clusters, moving) {:?}; threshold {:.2}",
        moving_params.draws,
        classifier.training_rows(),
        classifier.threshold()
    );
    let threshold = classifier.threshold();
    if let Ok(list) = std::env::var("MEMORIES") {
        let memories: Vec<f64> = list.split(',').filter_map(|v| v.parse().ok()).collect();
        let split = std::env::var("SPLIT").unwrap_or_else(|_| "situations".into());
        return sweep_memories(
            classifier,
            &root.join("data").join(split),
            &params,
            &memories,
        );
    }
    // BELIEF=γ smooths the probabilities along the clusters' own tracks (MovingBelief).
    let memory: f64 = std::env::var("BELIEF")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0.0);
    println!("belief memory {memory}");
    let situations = Dataset::open(&root.join("data/situations"))?;
    let (mut scored, mut moving_total): (Vec<Scored>, u64) = (Vec::new(), 0);
    for info in situations.sequences() {
        let sequence = situations.sequence(&info.name)?;
        let mut stream = ScanStream::new(&sequence, vec![params.clone()])?;
        let (mut tp, mut fp, mut fn_) = (0u64, 0u64, 0u64);
        let mut belief = MovingBelief::new(memory);
        while let Some((_, sweep)) = stream.read_next()? {
            let features = stream.features_of(&sweep)?.remove(0);
            let change = ChangeEvidence::of_stream(&stream).ok_or("no slice")?;
            let probabilities = classifier.cluster_probabilities(&features, &change)?;
            let probabilities = belief.update_features(&features, &probabilities, sweep.stamp_secs);
            if std::env::var("TARGET").is_ok()
                && let Some(target) = sweep.target()
            {
                let mut counts: BTreeMap<usize, usize> = BTreeMap::new();
                for (i, p) in features.points().iter().enumerate() {
                    if sweep.labels[p.index].instance() == target.id {
                        *counts.entry(features.cluster_of(i)).or_default() += 1;
                    }
                }
                let c = counts.into_iter().max_by_key(|e| e.1).map(|e| e.0);
                let p = c.and_then(|c| probabilities[c]);
                let o = sweep.world_from_sensor.translation.vector;
                let range = (target.centre_m[0] - o[0]).hypot(target.centre_m[1] - o[1]);
                print!("{}:{:.2}@{range:.0} ", sweep.index, p.unwrap_or(-1.0));
            }
            let truly = |i: usize| {
                let v = sweep.flow_in_world_mps[features.points()[i].index];
                f64::from(v[0]).hypot(f64::from(v[1])) > MOVING_SPEED_MPS
            };
            for (c, p) in probabilities.iter().enumerate() {
                let members = features.clusters().members(c);
                let moving = members.iter().filter(|&&i| truly(i)).count() as u64;
                let total = members.len() as u64;
                moving_total += moving;
                let decided = p.is_some_and(|p| p > threshold);
                if decided {
                    (tp, fp) = (tp + moving, fp + total - moving);
                } else {
                    fn_ += moving;
                }
                if let (Some(p), Some(&i)) = (p, members.first()) {
                    let class = sweep.labels[features.points()[i].index].semantic();
                    scored.push((*p, moving, total - moving, class));
                }
            }
        }
        let iou = tp as f64 / (tp + fp + fn_).max(1) as f64;
        println!(
            "{:<24} points TP {tp:>7} FP {fp:>7} FN {fn_:>7}  IoU {iou:.3}",
            info.name
        );
    }
    let at = |t: f64| {
        let tp: u64 = scored.iter().filter(|s| s.0 > t).map(|s| s.1).sum();
        let fp: u64 = scored.iter().filter(|s| s.0 > t).map(|s| s.2).sum();
        (tp, fp)
    };
    let (tp, fp) = at(threshold);
    println!(
        "all situations at {:.2}: precision {:.3} recall {:.3} IoU {:.3}",
        threshold,
        tp as f64 / (tp + fp).max(1) as f64,
        tp as f64 / moving_total.max(1) as f64,
        tp as f64 / (moving_total + fp).max(1) as f64
    );
    for t in [0.5, 0.6, 0.7, 0.8, 0.9, 0.95] {
        let (tp, fp) = at(t);
        println!(
            "  threshold {t:.2}: IoU {:.3}",
            tp as f64 / (moving_total + fp).max(1) as f64
        );
    }
    let mut by_class: BTreeMap<u16, u64> = BTreeMap::new();
    for s in scored.iter().filter(|s| s.0 > threshold) {
        *by_class.entry(s.3).or_default() += s.2;
    }
    println!("static points called moving, by SemanticKITTI class: {by_class:?}");
    Ok(())
}

/// MEMORIES=γ1,γ2,… (SPLIT=train|situations): the moving IoU per point over a split's sequences
/// for each belief memory, from one pass of the classifier.
fn sweep_memories(
    classifier: &MovingClassifier,
    folder: &std::path::Path,
    params: &FeatureParams,
    memories: &[f64],
) -> Result<(), Failure> {
    let data = Dataset::open(folder)?;
    // THRESHOLDS=t1,t2,… besides the classifier's own; per memory and threshold: TP, FP, FN.
    let mut thresholds = vec![classifier.threshold()];
    if let Ok(list) = std::env::var("THRESHOLDS") {
        thresholds.extend(list.split(',').filter_map(|v| v.parse::<f64>().ok()));
    }
    let mut tallies = vec![vec![[0u64; 3]; thresholds.len()]; memories.len()];
    for info in data.sequences() {
        let sequence = data.sequence(&info.name)?;
        let mut stream = ScanStream::new(&sequence, vec![params.clone()])?;
        let mut beliefs: Vec<MovingBelief> =
            memories.iter().map(|&m| MovingBelief::new(m)).collect();
        while let Some((_, sweep)) = stream.read_next()? {
            let features = stream.features_of(&sweep)?.remove(0);
            let change = ChangeEvidence::of_stream(&stream).ok_or("no slice")?;
            let raw = classifier.cluster_probabilities(&features, &change)?;
            let truly = |i: usize| {
                let v = sweep.flow_in_world_mps[features.points()[i].index];
                f64::from(v[0]).hypot(f64::from(v[1])) > MOVING_SPEED_MPS
            };
            let counts: Vec<(u64, u64)> = (0..raw.len())
                .map(|c| {
                    let members = features.clusters().members(c);
                    let moving = members.iter().filter(|&&i| truly(i)).count() as u64;
                    (moving, members.len() as u64)
                })
                .collect();
            for (belief, per_threshold) in beliefs.iter_mut().zip(&mut tallies) {
                let p = belief.update_features(&features, &raw, sweep.stamp_secs);
                for (t, tally) in thresholds.iter().zip(per_threshold.iter_mut()) {
                    for (c, &(moving, total)) in counts.iter().enumerate() {
                        if p[c].is_some_and(|p| p > *t) {
                            tally[0] += moving;
                            tally[1] += total - moving;
                        } else {
                            tally[2] += moving;
                        }
                    }
                }
            }
        }
        print!(".");
    }
    println!();
    for (m, per_threshold) in memories.iter().zip(&tallies) {
        for (threshold, t) in thresholds.iter().zip(per_threshold) {
            let iou = t[0] as f64 / (t[0] + t[1] + t[2]).max(1) as f64;
            println!(
                "memory {m:.2} threshold {threshold:.2}: TP {} FP {} FN {} IoU {iou:.3}",
                t[0], t[1], t[2]
            );
        }
    }
    Ok(())
}
