//! `occupancy.json` in the SPEC §7 shape: `{"scenarios": {name: {"methods": {"GPOM-RD":
//! {"auc_by_query_time": {"3": …, …}, "seconds_per_map": …, "training_points_per_map": …, …},
//! "GPOM-RD1": …, "GRID": …}, …}}, "seed": …, "version": …}`. Query times are seconds since the
//! sequence started (integers at the paper's 1 Hz). Keys are sorted at every level; an AUC that
//! does not exist (truth of one class only) is `null`.

use std::collections::BTreeMap;

use patchflow_occupancy::{
    AheadScores, ClusterKind, MethodScores, MotionAccuracy, MotionMap, SequenceScores,
};
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
    /// How the scenario was observed (`planar scanner`, `3-D lidar, height slice`).
    #[serde(skip_serializing_if = "Option::is_none")]
    observed_by: Option<&'static str>,
    /// DGPOM's motion map, if the scenario has a training run.
    #[serde(skip_serializing_if = "Option::is_none")]
    motion_map: Option<MotionMapEntry>,
    occupied_points_by_query_time: BTreeMap<String, usize>,
    query_points_by_query_time: BTreeMap<String, usize>,
    /// DGPOM's predictions ahead (Figure 10), if the scenario has a training run.
    #[serde(skip_serializing_if = "Option::is_none")]
    predict_ahead: Option<AheadEntry>,
}

#[derive(Serialize)]
struct MotionMapEntry {
    /// Υ against the training run's actors (RMSE on and off the lanes).
    accuracy: MotionAccuracy,
    arrived_clusters: usize,
    error_points: usize,
    stationary_clusters: usize,
    summary: String,
    vacated_clusters: usize,
    velocity_points: usize,
}

#[derive(Serialize)]
struct AheadEntry {
    auc_by_start: Vec<Vec<f64>>,
    auc_mean: Vec<f64>,
    auc_std: Vec<f64>,
    method: String,
    seconds_ahead: Vec<f64>,
    start_scans: Vec<usize>,
}

fn motion_map_entry(map: &MotionMap) -> MotionMapEntry {
    let count = |k: ClusterKind| map.clusters.iter().filter(|c| c.kind == k).count();
    MotionMapEntry {
        accuracy: map.accuracy,
        arrived_clusters: count(ClusterKind::Arrived),
        error_points: map.error_points,
        stationary_clusters: count(ClusterKind::Stationary),
        summary: map.summary.clone(),
        vacated_clusters: count(ClusterKind::Vacated),
        velocity_points: map.velocity_points,
    }
}

fn ahead_entry(a: &AheadScores) -> AheadEntry {
    let stats = a.mean_std();
    AheadEntry {
        auc_by_start: a.auc.clone(),
        auc_mean: stats.iter().map(|s| s.0).collect(),
        auc_std: stats.iter().map(|s| s.1).collect(),
        method: a.method.to_string(),
        seconds_ahead: a.seconds_ahead.clone(),
        start_scans: a.start_scans.clone(),
    }
}

#[derive(Serialize)]
struct MethodEntry {
    auc_by_query_time: BTreeMap<String, Option<f64>>,
    /// CPU seconds per map (mean, all threads), where the run measured them.
    #[serde(skip_serializing_if = "Option::is_none")]
    cpu_seconds_per_map: Option<f64>,
    /// Training points per map before thinning (equal to `training_points_per_map` unthinned).
    drawn_points_per_map: f64,
    mean_auc: Option<f64>,
    seconds_by_query_time: BTreeMap<String, f64>,
    seconds_per_map: f64,
    /// The GP each map solved (`exact`, `SPGP M`), by query time; absent without a GP.
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    solver_by_query_time: BTreeMap<String, String>,
    /// The learned temporal length-scale by query time: (ε m/s, l_t s) pairs, ε 0 where l_t does
    /// not depend on it; absent for a method without one.
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    temporal_lengthscale_by_query_time: BTreeMap<String, Vec<[f64; 2]>>,
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

fn method_entry(scores: &SequenceScores, m: &MethodScores, cpu: Option<&Vec<f64>>) -> MethodEntry {
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
        cpu_seconds_per_map: cpu.map(|c| mean(c)),
        drawn_points_per_map: m.mean_drawn_points(),
        mean_auc: (!aucs.is_empty()).then(|| aucs.iter().sum::<f64>() / aucs.len() as f64),
        seconds_by_query_time: by_time(m.seconds_per_map.clone()),
        seconds_per_map: m.mean_seconds_per_map(),
        solver_by_query_time: scans
            .iter()
            .map(|&t| query_time_key(scores, t))
            .zip(m.solver_per_map.iter())
            .filter_map(|(t, s)| s.clone().map(|s| (t, s)))
            .collect(),
        temporal_lengthscale_by_query_time: scans
            .iter()
            .map(|&t| query_time_key(scores, t))
            .zip(m.temporal_lengthscales_per_map.iter())
            .filter(|(_, l)| !l.is_empty())
            .map(|(t, l)| (t, l.clone()))
            .collect(),
        training_points_by_query_time: scans
            .iter()
            .map(|&t| query_time_key(scores, t))
            .zip(m.training_points_per_map.iter().copied())
            .collect(),
        training_points_per_map: m.mean_training_points(),
    }
}

/// Mean of `values` (0 for none).
pub(crate) fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len().max(1) as f64
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
                    .map(|(name, m)| {
                        let cpu = report
                            .cpu_seconds
                            .get(&s.name)
                            .and_then(|c| c.get(name.name()));
                        (name.to_string(), method_entry(s, m, cpu))
                    })
                    .collect(),
                motion_map: report.motion_maps.get(&s.name).map(|m| motion_map_entry(m)),
                observed_by: report.kinds.get(&s.name).map(|k| k.label()),
                occupied_points_by_query_time: keyed(&s.occupied_points),
                query_points_by_query_time: keyed(&s.query_points),
                predict_ahead: report.ahead.get(&s.name).map(ahead_entry),
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
