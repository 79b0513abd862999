//! The bar the README holds the GP estimator to (issue #9): SPGP-HET-ALL's heading RMSE under 25°
//! and its speed RMSE under 1.5 m/s in a situation. Where a run misses it, the rows say from the
//! run's own data what kind of miss it is: a few outlier scans or a spread misreading, the scans
//! right after the target was hidden, the scans that saw it through a gap, the range that carries
//! the error, a speed bias, and whether the same models meet the bar on the `ideal` rung (then the
//! world breaks them, not the training); `bar_markdown.rs` writes them into the report. The
//! causes found by ablation are in docs/investigations.md, "Why the GPs lost accuracy on
//! `urban`".

use std::collections::BTreeMap;

use patchflow_sim::Realism;

use crate::error::EvalError;
use crate::methods::method::Method;
use crate::report::SituationMetrics;
use crate::scene::metrics::{MIN_SCORED_SPEED_MPS, MethodMetrics, heading_error_deg, rmse};
use crate::scene::result::SituationResult;
use crate::study::{Scores, StudyReport};

/// Heading RMSE the GP estimator must stay under, degrees.
pub const BAR_HEADING_DEG: f64 = 25.0;
/// Speed RMSE the GP estimator must stay under, m/s.
pub const BAR_SPEED_MPS: f64 = 1.5;
/// The method held to the bar.
pub(super) const HELD: Method = Method::SpgpHetAll;
/// Share of the scored scans counted as "the worst" (at least one scan).
const WORST_SHARE: f64 = 0.1;
/// Range bins of the squared heading error (as the report's breakdown).
const RANGE_BINS: [(&str, f64); 3] = [
    ("under 15 m", 15.0),
    ("15-30 m", 30.0),
    ("30 m and more", f64::INFINITY),
];

/// One situation against the bar.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BarRow {
    /// Situation name.
    pub situation: String,
    /// Heading RMSE, degrees.
    pub heading_rmse_deg: Option<f64>,
    /// Speed RMSE, m/s.
    pub speed_rmse_mps: Option<f64>,
    /// Both under the bar.
    pub met: bool,
    /// Scans whose heading was scored.
    pub scored_scans: usize,
    /// Share of the squared heading error in the worst tenth of the scored scans.
    pub worst_tenth_share: f64,
    /// Heading RMSE without the worst tenth, degrees.
    pub heading_rmse_without_worst_deg: Option<f64>,
    /// Scored scans whose previous scan saw no point of the target (its motion cannot show in
    /// the difference map), and their share of the squared heading error.
    pub after_hidden_scans: usize,
    /// See `after_hidden_scans`.
    pub after_hidden_share: f64,
    /// Scored scans that saw the target through a gap (both ends of its cluster hidden by nearer
    /// objects, so its motion along itself cannot show), and their share of the squared heading
    /// error.
    pub through_gap_scans: usize,
    /// See `through_gap_scans`.
    pub through_gap_share: f64,
    /// The range bin carrying most of the squared heading error, and its share.
    pub worst_range: Option<(String, f64)>,
    /// Mean signed speed error (estimate − truth), m/s.
    pub speed_bias_mps: Option<f64>,
    /// Share of the squared speed error in the worst tenth of the scans with an estimate.
    pub speed_worst_tenth_share: f64,
    /// The same models on the `ideal` rung (the realism study), when it covered the situation.
    pub ideal: Option<Scores>,
}

/// Every situation with estimates of the held method, against the bar; `scored` holds the
/// report's metrics of each situation (scored once, read here), `ideal` maps situation names to
/// the held method's scores on the `ideal` rung.
pub fn bar_rows(
    situations: &[SituationResult],
    scored: &[SituationMetrics],
    ideal: &BTreeMap<String, Scores>,
) -> Vec<BarRow> {
    situations
        .iter()
        .filter_map(|s| {
            let (_, _, metrics) = scored.iter().find(|(name, _, _)| *name == s.name)?;
            row(s, metrics.get(&HELD)?, ideal.get(&s.name).cloned())
        })
        .collect()
}

fn row(
    situation: &SituationResult,
    metrics: &MethodMetrics,
    ideal: Option<Scores>,
) -> Option<BarRow> {
    let estimates = situation.methods.get(&HELD)?;
    // Squared heading errors with what each scan was like.
    let mut scans = Vec::new();
    let mut speed_errors = Vec::new();
    for (k, (truth, estimate)) in situation.truth.iter().zip(estimates).enumerate() {
        let Some(e) = estimate else { continue };
        speed_errors.push(e.speed_mps - truth.speed_mps);
        if truth.speed_mps < MIN_SCORED_SPEED_MPS {
            continue;
        }
        let error = heading_error_deg(e.heading_rad, truth.heading_rad);
        let hidden_before = k > 0 && situation.truth[k - 1].target_points == Some(0);
        let through_gap = truth.target_hidden_ends == Some(2);
        scans.push((error * error, hidden_before, through_gap, truth.range_m));
    }
    let total: f64 = scans.iter().map(|s| s.0).sum();
    // `+ 0.0` turns an empty sum's −0 into 0.
    let share = |part: f64| if total > 0.0 { part / total + 0.0 } else { 0.0 };
    let squared = worst_first(scans.iter().map(|s| s.0));
    let worst = worst_count(squared.len());
    let rest: Vec<f64> = squared[worst..].iter().map(|s| s.sqrt()).collect();
    let speed_squared = worst_first(speed_errors.iter().map(|e| e * e));
    let speed_total: f64 = speed_squared.iter().sum();
    let speed_worst: f64 = speed_squared[..worst_count(speed_squared.len())]
        .iter()
        .sum();
    let hidden: Vec<f64> = scans.iter().filter(|s| s.1).map(|s| s.0).collect();
    let through_gap: Vec<f64> = scans.iter().filter(|s| s.2).map(|s| s.0).collect();
    let mut by_range = [0.0; 3];
    for (sq, _, _, range) in &scans {
        if let Some(bin) = range.and_then(|r| RANGE_BINS.iter().position(|(_, edge)| r < *edge)) {
            by_range[bin] += sq;
        }
    }
    let worst_range = (0..3)
        .max_by(|&a, &b| by_range[a].total_cmp(&by_range[b]))
        .filter(|&b| by_range[b] > 0.0)
        .map(|b| (RANGE_BINS[b].0.to_owned(), share(by_range[b])));
    Some(BarRow {
        situation: situation.name.clone(),
        heading_rmse_deg: metrics.heading_rmse_deg,
        speed_rmse_mps: metrics.speed_rmse_mps,
        met: heading_under_bar(metrics.heading_rmse_deg) && speed_under_bar(metrics.speed_rmse_mps),
        scored_scans: scans.len(),
        worst_tenth_share: share(squared[..worst].iter().sum()),
        heading_rmse_without_worst_deg: rmse(&rest),
        after_hidden_scans: hidden.len(),
        after_hidden_share: share(hidden.iter().sum()),
        through_gap_scans: through_gap.len(),
        through_gap_share: share(through_gap.iter().sum()),
        worst_range,
        speed_bias_mps: (!speed_errors.is_empty())
            .then(|| speed_errors.iter().sum::<f64>() / speed_errors.len() as f64),
        speed_worst_tenth_share: if speed_total > 0.0 {
            speed_worst / speed_total
        } else {
            0.0
        },
        ideal,
    })
}

/// Squared errors, largest first.
fn worst_first(squared: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut v: Vec<f64> = squared.collect();
    v.sort_by(|a, b| b.total_cmp(a));
    v
}

/// How many of `n` scans are "the worst tenth" (at least one where there is one).
fn worst_count(n: usize) -> usize {
    ((n as f64 * WORST_SHARE).ceil() as usize).min(n)
}

/// Whether a heading RMSE (degrees) is under the bar.
pub(crate) fn heading_under_bar(rmse_deg: Option<f64>) -> bool {
    rmse_deg.is_some_and(|h| h < BAR_HEADING_DEG)
}

/// Whether a speed RMSE (m/s) is under the bar.
pub(crate) fn speed_under_bar(rmse_mps: Option<f64>) -> bool {
    rmse_mps.is_some_and(|s| s < BAR_SPEED_MPS)
}

/// Whether scores are under the bar.
pub(super) fn meets(scores: &Scores) -> bool {
    heading_under_bar(scores.heading_rmse_deg) && speed_under_bar(scores.speed_rmse_mps)
}

/// The held method's scores per situation on the `ideal` rung of a realism study.
pub fn ideal_scores(realism: Option<&StudyReport>) -> BTreeMap<String, Scores> {
    let Some(ideal) =
        realism.and_then(|r| r.points.iter().find(|p| p.label == Realism::Ideal.name()))
    else {
        return BTreeMap::new();
    };
    ideal
        .situations
        .iter()
        .filter_map(|(name, methods)| Some((name.clone(), methods.get(HELD.name())?.clone())))
        .collect()
}

/// `metrics.json`'s `bar` entry: the bar and every situation's row.
pub fn bar_entry(rows: &[BarRow]) -> Result<serde_json::Map<String, serde_json::Value>, EvalError> {
    let value = serde_json::json!({
        "method": HELD.name(),
        "heading_rmse_deg": BAR_HEADING_DEG,
        "speed_rmse_mps": BAR_SPEED_MPS,
        "met": rows.iter().filter(|r| r.met).count(),
        "situations": serde_json::to_value(rows).map_err(|e| EvalError::BadResult {
            situation: "-".into(),
            reason: format!("bar rows: {e}"),
        })?,
    });
    let mut entries = serde_json::Map::new();
    entries.insert("bar".into(), value);
    Ok(entries)
}

#[cfg(test)]
#[path = "bar_check_tests.rs"]
mod tests;
