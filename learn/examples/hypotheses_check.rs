//! What the object hypotheses of the whole-scan step (thesis Algorithm 3.1, step 1) hold on a
//! generated dataset, and whether a gate on the motion evidence around a cluster could keep the
//! static ones from the GPs: per group (clusters holding a moving actor's points, static ones by
//! their majority SemanticKITTI class) the clusters, points and map cells per scan, their size,
//! and two evidence measures, each the largest over the cluster's map cells of a patch-footprint
//! (11 × 11 cells) mean:
//!
//! - `|difference|`: the thesis' importance weight (3.1.2), mean |m_t − m_{t−1}|;
//! - `observed change`: the same over cells that both sweeps observed (some hit or miss arrived
//!   in each), leaving out cells that went from the prior to observed or back (the edges of the
//!   shadows behind obstacles, which move with the ego car, and surfaces coming into view).
//!   Computed from the maps at priors 0.5 and 0.01: a cell is unobserved where they differ.
//!
//! and, for thresholds on each, the share of moving-actor clusters kept and of static map cells
//! (the GP's work) kept.
//!
//! `cargo run --release -p patchflow-learn --example hypotheses_check -- DATASET [STEP]`
//! (`PATCHFLOW_TRUE_POSE=1` places the sweeps with the true instead of the estimated pose).

use std::collections::BTreeMap;
use std::path::PathBuf;

use patchflow_dataset::Dataset;
use patchflow_learn::{FeatureParams, GridMap, SweepFeatures};

type Failure = Box<dyn std::error::Error>;

/// One cluster: its group, map cells, points, length and width, and both evidence measures.
struct Row {
    group: String,
    cells: usize,
    points: usize,
    size_m: [f64; 2],
    evidence: [f64; 2],
}

/// Mean |value| of `values(col, row)` over the 11 × 11 cells around `(col, row)`.
fn patch_mean(col: usize, row: usize, value: &dyn Fn(i64, i64) -> f64) -> f64 {
    let mut sum = 0.0;
    for r in row as i64 - 5..=row as i64 + 5 {
        for c in col as i64 - 5..=col as i64 + 5 {
            sum += value(c, r).abs();
        }
    }
    sum / 121.0
}

/// m_t − m_{t−1} where both sweeps observed the cell, from the maps at two priors.
fn observed_change(a: &SweepFeatures, b: &SweepFeatures, col: i64, row: i64) -> f64 {
    let (ma, mb): (&GridMap, &GridMap) = (a.reflection_map(), b.reflection_map());
    let (da, db) = (a.difference_map(), b.difference_map());
    let (now_a, now_b) = (ma.get(col, row), mb.get(col, row));
    let (before_a, before_b) = (now_a - da.get(col, row), now_b - db.get(col, row));
    let seen = (now_a - now_b).abs() < 1e-9 && (before_a - before_b).abs() < 1e-9;
    if seen { da.get(col, row) } else { 0.0 }
}

fn quantiles(mut v: Vec<f64>) -> String {
    if v.is_empty() {
        return "-".into();
    }
    v.sort_by(f64::total_cmp);
    let q = |p: f64| v[((v.len() - 1) as f64 * p).round() as usize];
    format!(
        "{:.3} / {:.3} / {:.3} / {:.3}",
        q(0.05),
        q(0.25),
        q(0.5),
        q(0.75)
    )
}

fn main() -> Result<(), Failure> {
    let mut args = std::env::args().skip(1);
    let root = PathBuf::from(
        args.next()
            .ok_or("usage: hypotheses_check DATASET [STEP]")?,
    );
    let step: usize = args.next().map_or(Ok(5), |s| s.parse())?;
    let true_pose = std::env::var_os("PATCHFLOW_TRUE_POSE").is_some();
    let dataset = Dataset::open(&root)?;
    let params = FeatureParams::default().check()?;
    let other_prior = FeatureParams::with_prior(0.01).check()?;
    let (mut rows, mut scans) = (Vec::new(), 0usize);
    for info in dataset.sequences() {
        let reader = dataset.sequence(&info.name)?;
        let mut t = 1;
        while t < reader.len() {
            let (mut prev, mut curr) = (reader.read_sweep(t - 1)?, reader.read_sweep(t)?);
            if true_pose {
                prev.estimated_world_from_sensor = None;
                curr.estimated_world_from_sensor = None;
            }
            let features = SweepFeatures::compute_checked(&prev, &curr, &params)?;
            let low = SweepFeatures::compute_checked(&prev, &curr, &other_prior)?;
            let window = *features.difference_map().window();
            scans += 1;
            for c in features.object_hypotheses() {
                let members = features.clusters().members(c);
                let mut classes: BTreeMap<u16, usize> = BTreeMap::new();
                let mut moving = 0;
                for &i in members {
                    let label = curr.labels[features.points()[i].index];
                    *classes.entry(label.semantic()).or_default() += 1;
                    moving += usize::from(label.is_moving());
                }
                let group = if moving >= 3 {
                    "moving actor".to_owned()
                } else {
                    let major = classes
                        .iter()
                        .max_by_key(|(_, n)| **n)
                        .map_or(0, |(k, _)| *k);
                    format!("static {major}")
                };
                let mut cells: Vec<(usize, usize)> = members
                    .iter()
                    .filter_map(|&i| {
                        window.cell_of(features.points()[i].x_m, features.points()[i].y_m)
                    })
                    .collect();
                cells.sort_unstable();
                cells.dedup();
                let difference = |col, row| features.difference_map().get(col, row);
                let observed = |col, row| observed_change(&features, &low, col, row);
                let best = |value: &dyn Fn(i64, i64) -> f64| {
                    cells
                        .iter()
                        .map(|&(col, row)| patch_mean(col, row, value))
                        .fold(0.0, f64::max)
                };
                let shape = features.cluster_shape(c);
                rows.push(Row {
                    group,
                    cells: cells.len(),
                    points: members.len(),
                    size_m: [shape.length_m, shape.width_m],
                    evidence: [best(&difference), best(&observed)],
                });
            }
            t += step;
        }
    }
    report(&rows, scans);
    Ok(())
}

fn report(rows: &[Row], scans: usize) {
    let per = |n: usize| n as f64 / scans.max(1) as f64;
    let mut groups: BTreeMap<&str, Vec<&Row>> = BTreeMap::new();
    for r in rows {
        groups.entry(&r.group).or_default().push(r);
    }
    println!("{scans} scans; width and evidence quantiles q05 / q25 / q50 / q75");
    println!(
        "| group | clusters/scan | points/scan | cells/scan | width (m) | |difference| | observed change |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (group, g) in &groups {
        let of = |k: usize| g.iter().map(|r| r.evidence[k]).collect::<Vec<f64>>();
        println!(
            "| {group} | {:.1} | {:.0} | {:.0} | {} | {} | {} |",
            per(g.len()),
            per(g.iter().map(|r| r.points).sum()),
            per(g.iter().map(|r| r.cells).sum()),
            quantiles(g.iter().map(|r| r.size_m[1]).collect()),
            quantiles(of(0)),
            quantiles(of(1)),
        );
    }
    let moving: Vec<&Row> = rows.iter().filter(|r| r.group == "moving actor").collect();
    let fixed: Vec<&Row> = rows.iter().filter(|r| r.group != "moving actor").collect();
    let static_cells = fixed.iter().map(|r| r.cells).sum::<usize>().max(1) as f64;
    println!(
        "\n| gate: evidence at least | |difference|: moving clusters kept, static cells kept | observed change: the same |"
    );
    println!("|---|---|---|");
    for threshold in [0.01, 0.02, 0.03, 0.05, 0.08] {
        let kept = |k: usize| {
            let m = moving.iter().filter(|r| r.evidence[k] >= threshold).count();
            let s: usize = fixed
                .iter()
                .filter(|r| r.evidence[k] >= threshold)
                .map(|r| r.cells)
                .sum();
            format!(
                "{m}/{} , {:.0} %",
                moving.len(),
                100.0 * s as f64 / static_cells
            )
        };
        println!("| {threshold} | {} | {} |", kept(0), kept(1));
    }
}
