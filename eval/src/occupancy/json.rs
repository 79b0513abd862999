//! `occupancy.json` in the SPEC §7 shape: `{"scenarios": {name: {"methods": {"GPOM-RD":
//! {"auc_by_query_time": {"3": …, …}, "seconds_per_map": …, "training_points_per_map": …, …},
//! "GPOM-RD1": …, "GRID": …}, …}}, "seed": …, "version": …}`. Query times are seconds since the
//! sequence started (integers at the paper's 1 Hz). Keys are sorted at every level; an AUC that
//! does not exist (truth of one class only) is `null`.

use std::collections::BTreeMap;

use patchflow_occupancy::{MethodScores, SequenceScores};
use serde::Serialize;

use super::OccupancyReport;
use crate::error::EvalError;

#[derive(Serialize)]
struct OccupancyFile {
    query_spacing_m: f64,
    scans_per_map: usize,
    scenarios: BTreeMap<String, ScenarioEntry>,
    seed: u64,
    version: &'static str,
}

#[derive(Serialize)]
struct ScenarioEntry {
    methods: BTreeMap<String, MethodEntry>,
    occupied_points_by_query_time: BTreeMap<String, usize>,
    query_points_by_query_time: BTreeMap<String, usize>,
}

#[derive(Serialize)]
struct MethodEntry {
    auc_by_query_time: BTreeMap<String, Option<f64>>,
    mean_auc: Option<f64>,
    seconds_by_query_time: BTreeMap<String, f64>,
    seconds_per_map: f64,
    training_points_by_query_time: BTreeMap<String, usize>,
    training_points_per_map: f64,
}

/// The key of a query scan: its time in seconds, without decimals when it is a whole second.
pub(crate) fn query_time_key(scores: &SequenceScores, scan: usize) -> String {
    let t = scores.query_secs.get(&scan).copied().unwrap_or(scan as f64);
    if (t - t.round()).abs() < 1e-9 {
        format!("{t:.0}")
    } else {
        format!("{t:.3}")
    }
}

fn method_entry(scores: &SequenceScores, m: &MethodScores) -> MethodEntry {
    let scans: Vec<usize> = m.auc_by_query_scan.keys().copied().collect();
    let by_time = |values: Vec<f64>| -> BTreeMap<String, f64> {
        scans
            .iter()
            .map(|&t| query_time_key(scores, t))
            .zip(values)
            .collect()
    };
    let aucs: Vec<f64> = m.auc_by_query_scan.values().flatten().copied().collect();
    MethodEntry {
        auc_by_query_time: m
            .auc_by_query_scan
            .iter()
            .map(|(&t, &auc)| (query_time_key(scores, t), auc))
            .collect(),
        mean_auc: (!aucs.is_empty()).then(|| aucs.iter().sum::<f64>() / aucs.len() as f64),
        seconds_by_query_time: by_time(m.seconds_per_map.clone()),
        seconds_per_map: m.mean_seconds_per_map(),
        training_points_by_query_time: scans
            .iter()
            .map(|&t| query_time_key(scores, t))
            .zip(m.training_points_per_map.iter().copied())
            .collect(),
        training_points_per_map: m.mean_training_points(),
    }
}

/// The text of `occupancy.json` (pretty-printed, sorted keys, trailing newline).
pub fn occupancy_json(report: &OccupancyReport) -> Result<String, EvalError> {
    let scenarios = report
        .scenarios
        .iter()
        .map(|s| {
            let keyed = |counts: &BTreeMap<usize, usize>| -> BTreeMap<String, usize> {
                counts
                    .iter()
                    .map(|(&t, &n)| (query_time_key(s, t), n))
                    .collect()
            };
            let entry = ScenarioEntry {
                methods: s
                    .methods
                    .iter()
                    .map(|(name, m)| (name.clone(), method_entry(s, m)))
                    .collect(),
                occupied_points_by_query_time: keyed(&s.occupied_points),
                query_points_by_query_time: keyed(&s.query_points),
            };
            (s.name.clone(), entry)
        })
        .collect();
    let file = OccupancyFile {
        query_spacing_m: report.params.query_spacing_m,
        scans_per_map: report.params.scans_per_map,
        scenarios,
        seed: report.seed,
        version: env!("CARGO_PKG_VERSION"),
    };
    let mut text = serde_json::to_string_pretty(&file).map_err(|source| EvalError::Json {
        path: "occupancy.json".into(),
        source,
    })?;
    text.push('\n');
    Ok(text)
}
