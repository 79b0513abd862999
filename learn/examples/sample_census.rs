//! What the importance-weighted training draw (thesis 3.1.2) picks from a dataset: per sample the
//! actor's class, how many of its points the height slice holds in the sweep and in the previous
//! one (a patch whose actor the previous sweep barely saw shows new surface, not motion), the
//! range, the heading relative to the line of sight, the speed and the weight; printed as shares
//! of the draw per bin, with the mean weight of each bin.
//!
//! `cargo run --release -p patchflow-learn --example sample_census -- DATASET [SAMPLES] [SEED]`

use std::collections::{BTreeMap, HashMap};
use std::path::PathBuf;

use patchflow_dataset::{Dataset, Sweep};
use patchflow_learn::{FeatureKind, FeatureParams, HeightSlice, SampleSet, TrainingSample};

type Failure = Box<dyn std::error::Error>;

/// Sliced points of each actor in a sweep.
fn sliced_points_per_actor(
    sweep: &Sweep,
    params: &FeatureParams,
) -> Result<HashMap<u16, usize>, Failure> {
    let slice = HeightSlice::cut(sweep, params)?;
    let mut counts = HashMap::new();
    for p in &slice.points {
        if let Some(label) = sweep.labels.get(p.index) {
            *counts.entry(label.instance()).or_insert(0) += 1;
        }
    }
    Ok(counts)
}

/// Speed bins, m/s: upper edge and label.
const SPEED_BINS_MPS: &[(f64, &str)] = &[
    (0.5, "<0.5"),
    (2.0, "0.5-2"),
    (5.0, "2-5"),
    (8.0, "5-8"),
    (f64::INFINITY, "8+"),
];

/// Range bins, metres: upper edge and label.
const RANGE_BINS_M: &[(f64, &str)] = &[
    (10.0, "<10"),
    (20.0, "10-20"),
    (30.0, "20-30"),
    (f64::INFINITY, "30+"),
];

fn bin(value: f64, edges: &[(f64, &'static str)]) -> &'static str {
    edges
        .iter()
        .find(|(edge, _)| value < *edge)
        .map_or("?", |(_, name)| name)
}

/// (count, sum of weights) per bin of one attribute.
type Census = BTreeMap<(&'static str, &'static str), (usize, f64)>;

fn main() -> Result<(), Failure> {
    let mut args = std::env::args().skip(1);
    let root = PathBuf::from(
        args.next()
            .ok_or("usage: sample_census DATASET [SAMPLES] [SEED]")?,
    );
    let n: usize = args.next().map_or(Ok(1600), |s| s.parse())?;
    let seed: u64 = args.next().map_or(Ok(7), |s| s.parse())?;
    let dataset = Dataset::open(&root)?;
    let params = FeatureParams::default();
    let set = SampleSet::collect(&dataset, &params, FeatureKind::Patch, n, seed)?;
    println!(
        "{}: {} samples from a pool of {}",
        root.display(),
        set.samples.len(),
        set.pool_size
    );
    // Samples grouped by sweep so each sweep pair is read once.
    let mut by_sweep: BTreeMap<(String, u32), Vec<&TrainingSample>> = BTreeMap::new();
    for s in &set.samples {
        by_sweep
            .entry((s.sequence.clone(), s.scan))
            .or_default()
            .push(s);
    }
    let mut census = Census::new();
    let mut add = |attr: &'static str, b: &'static str, w: f64| {
        let e = census.entry((attr, b)).or_insert((0, 0.0));
        e.0 += 1;
        e.1 += w;
    };
    for ((sequence, scan), samples) in &by_sweep {
        let reader = dataset.sequence(sequence)?;
        let curr = reader.read_sweep(*scan as usize)?;
        let prev = reader.read_sweep(*scan as usize - 1)?;
        let (now, before) = (
            sliced_points_per_actor(&curr, &params)?,
            sliced_points_per_actor(&prev, &params)?,
        );
        let third = (3 * *scan as usize) / reader.len().max(1);
        for s in samples {
            let truth = curr
                .objects
                .iter()
                .find(|o| o.id == s.actor)
                .ok_or("no truth")?;
            let w = s.weight;
            add(
                "class",
                match format!("{:?}", truth.class).as_str() {
                    "Car" => "car",
                    "Truck" => "truck",
                    "Pedestrian" => "pedestrian",
                    "Cyclist" => "cyclist",
                    _ => "other",
                },
                w,
            );
            let pts = [
                (0.5, "0"),
                (10.0, "1-9"),
                (30.0, "10-29"),
                (100.0, "30-99"),
                (f64::INFINITY, "100+"),
            ];
            add(
                "sliced pts now",
                bin(*now.get(&s.actor).unwrap_or(&0) as f64, &pts),
                w,
            );
            add(
                "sliced pts prev",
                bin(*before.get(&s.actor).unwrap_or(&0) as f64, &pts),
                w,
            );
            let before_share = *before.get(&s.actor).unwrap_or(&0) as f64
                / (*now.get(&s.actor).unwrap_or(&1)).max(1) as f64;
            add(
                "prev/now pts",
                bin(
                    before_share,
                    &[
                        (0.25, "<0.25"),
                        (0.5, "0.25-0.5"),
                        (0.8, "0.5-0.8"),
                        (1.25, "0.8-1.25"),
                        (f64::INFINITY, ">=1.25"),
                    ],
                ),
                w,
            );
            let p = curr.points_in_sensor[s.point];
            let range = f64::from(p[0]).hypot(f64::from(p[1]));
            add("range m", bin(range, RANGE_BINS_M), w);
            let rel = s.sin_rel.atan2(s.cos_rel).to_degrees().abs();
            add(
                "|heading-bearing| deg",
                bin(
                    rel,
                    &[
                        (30.0, "0-30 away"),
                        (60.0, "30-60"),
                        (120.0, "60-120 crossing"),
                        (150.0, "120-150"),
                        (181.0, "150-180 towards"),
                    ],
                ),
                w,
            );
            if (60.0..120.0).contains(&rel) {
                add("crossing: speed m/s", bin(s.speed_mps, SPEED_BINS_MPS), w);
                add("crossing: range m", bin(range, RANGE_BINS_M), w);
                add(
                    "crossing: class",
                    if s.speed_mps > 2.0 {
                        "vehicle"
                    } else {
                        "pedestrian-ish"
                    },
                    w,
                );
                if s.speed_mps > 2.0 {
                    add(
                        "crossing vehicle: sliced pts now",
                        bin(*now.get(&s.actor).unwrap_or(&0) as f64, &pts),
                        w,
                    );
                    add("crossing vehicle: range m", bin(range, RANGE_BINS_M), w);
                }
            }
            let speed_bin = bin(s.speed_mps, SPEED_BINS_MPS);
            add(
                [
                    "track third 1: speed m/s",
                    "track third 2: speed m/s",
                    "track third 3: speed m/s",
                ][third.min(2)],
                speed_bin,
                w,
            );
            if (60.0..120.0).contains(&rel) && s.speed_mps > 2.0 {
                add(
                    "crossing vehicle: track third",
                    ["1", "2", "3"][third.min(2)],
                    w,
                );
            }
            add("speed m/s", bin(s.speed_mps, SPEED_BINS_MPS), w);
            add(
                "weight",
                bin(
                    w,
                    &[
                        (0.02, "<0.02"),
                        (0.05, "0.02-0.05"),
                        (0.1, "0.05-0.1"),
                        (0.2, "0.1-0.2"),
                        (f64::INFINITY, "0.2+"),
                    ],
                ),
                w,
            );
        }
    }
    let total = set.samples.len().max(1) as f64;
    let mut last = "";
    for ((attr, b), (count, wsum)) in &census {
        if *attr != last {
            println!("{attr}:");
            last = attr;
        }
        println!(
            "  {b:>18}: {:5.1} %  (n {count:4}, mean weight {:.3})",
            100.0 * *count as f64 / total,
            wsum / *count as f64
        );
    }
    Ok(())
}
