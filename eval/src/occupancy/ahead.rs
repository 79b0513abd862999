//! DGPOM's predictions ahead of the last scan (DGPOM paper, Figure 10) on every scenario of an
//! occupancy run that has a motion map: the AUC against the time since the last observation.

use std::collections::BTreeMap;
use std::sync::Arc;

use patchflow_dataset::Dataset;
use patchflow_occupancy::{AheadParams, DgpomMethod, evaluate_ahead};
use rayon::prelude::*;

use super::dgpom::dgpom_method;
use super::run::OccupancyReport;
use super::sequence_kind::load_sequence;
use crate::error::EvalError;

/// Scores DGPOM's predictions ahead (Figure 10) on every scenario of `report` with a motion map;
/// `on_start` is called after each start time. The start times are independent fits (none is
/// timed) and run in parallel; their scores are merged in start order.
pub fn predict_ahead(
    dataset: &Dataset,
    report: &mut OccupancyReport,
    params: &AheadParams,
    on_start: &(dyn Fn() + Sync),
) -> Result<(), EvalError> {
    predict_ahead_with(dataset, report, params, on_start, &BTreeMap::new())
}

/// [`predict_ahead`] with the DGPOM methods that made the run's maps, by scenario name: a start
/// time that is also a query time reuses that map's fit (the same scans carried to the same
/// time) instead of fitting again. A scenario without one gets a fresh method.
pub fn predict_ahead_with(
    dataset: &Dataset,
    report: &mut OccupancyReport,
    params: &AheadParams,
    on_start: &(dyn Fn() + Sync),
    methods: &BTreeMap<String, DgpomMethod>,
) -> Result<(), EvalError> {
    for (name, map) in &report.motion_maps {
        let (sequence, kind) = load_sequence(dataset, name)?;
        let method = match methods.get(name) {
            Some(method) => method.clone(),
            None => dgpom_method(&kind.sample_params(report.seed), Arc::clone(map)),
        };
        let parts = params
            .start_scans
            .par_iter()
            .map(|&start| {
                let one = AheadParams {
                    start_scans: vec![start],
                    ..params.clone()
                };
                let part = evaluate_ahead(&sequence, &method, &one);
                on_start();
                part
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut scores = None;
        for part in parts {
            scores = Some(match scores {
                None => part,
                Some(mut all) => {
                    merge(&mut all, part);
                    all
                }
            });
        }
        if let Some(scores) = scores {
            report.ahead.insert(name.clone(), scores);
        }
    }
    Ok(())
}

/// Adds the start time of `part` to `all` (the mean time ahead weighted by the start times).
fn merge(all: &mut patchflow_occupancy::AheadScores, part: patchflow_occupancy::AheadScores) {
    all.start_scans.extend(part.start_scans);
    for (h, aucs) in part.auc.into_iter().enumerate() {
        let secs = part.seconds_ahead[h];
        if h >= all.auc.len() {
            all.auc.push(Vec::new());
            all.seconds_ahead.push(0.0);
        }
        let n = all.auc[h].len() as f64;
        let m = aucs.len() as f64;
        if n + m > 0.0 {
            all.seconds_ahead[h] = (all.seconds_ahead[h] * n + secs * m) / (n + m);
        }
        all.auc[h].extend(aucs);
    }
}
