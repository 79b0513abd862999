//! Scoring map methods on a sequence (DGPOM paper, Section 3.1, Table 1): at every query scan,
//! each method builds one map from the scan at the query time and the ones before it, predicts
//! over the lattice of query points the sensor observes, and is scored by ROC AUC against the
//! exact occupancy at the query time. One map (fit and prediction) is timed as a unit, alone on
//! the machine (maps run one after the other).

use std::collections::BTreeMap;
use std::time::Instant;

use crate::{
    MapMethod, MapMethodId, MapOutput, OccupancyError, OccupancyParams, OccupancySequence,
    PlanarScan, QueryGrid, Result, ScanWindow, roc_auc,
};

/// One method's scores over the query scans.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MethodScores {
    /// ROC AUC at each query scan (`None` if the truth there holds one class only).
    pub auc_by_query_scan: BTreeMap<usize, Option<f64>>,
    /// Wall-clock seconds of each map (fit and prediction over the query points).
    pub seconds_per_map: Vec<f64>,
    /// Training points of each map.
    pub training_points_per_map: Vec<usize>,
    /// Training points of each map drawn before thinning (the same as above where none is).
    pub drawn_points_per_map: Vec<usize>,
    /// What each map's fit learned, one line per map.
    pub summaries: Vec<String>,
    /// The GP each map solved (`exact`, `SPGP M`; `None` without a GP).
    pub solver_per_map: Vec<Option<String>>,
    /// Each map's learned temporal length-scale as (ε m/s, l_t s) pairs (ε 0 where l_t does not
    /// depend on it); empty for a method without one.
    pub temporal_lengthscales_per_map: Vec<Vec<[f64; 2]>>,
}

impl MethodScores {
    /// Mean seconds per map.
    pub fn mean_seconds_per_map(&self) -> f64 {
        mean(self.seconds_per_map.iter().copied())
    }

    /// Mean training points per map.
    pub fn mean_training_points(&self) -> f64 {
        mean(self.training_points_per_map.iter().map(|&n| n as f64))
    }

    /// Mean training points per map before thinning.
    pub fn mean_drawn_points(&self) -> f64 {
        mean(self.drawn_points_per_map.iter().map(|&n| n as f64))
    }
}

/// One query scan kept for figures: its lattice, truth, scan and every method's map.
#[derive(Debug, Clone, PartialEq)]
pub struct MapFigure {
    /// The query scan.
    pub query_scan: usize,
    /// The query points.
    pub grid: QueryGrid,
    /// True occupancy at each query point.
    pub truth: Vec<bool>,
    /// The scan at the query time (its beams are drawn over the truth).
    pub scan: PlanarScan,
    /// Each method's map, by method name.
    pub maps: BTreeMap<MapMethodId, MapOutput>,
}

/// Every method's scores on one sequence.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SequenceScores {
    /// Sequence name.
    pub name: String,
    /// Time of each query scan, seconds since the sequence started (the paper's t).
    pub query_secs: BTreeMap<usize, f64>,
    /// Query points per query scan.
    pub query_points: BTreeMap<usize, usize>,
    /// Occupied query points per query scan (truth).
    pub occupied_points: BTreeMap<usize, usize>,
    /// Scores by method name.
    pub methods: BTreeMap<MapMethodId, MethodScores>,
    /// The maps kept for figures.
    pub figures: Vec<MapFigure>,
}

/// Scores `methods` on `sequence`; `on_map(method, query_scan)` is called after every map.
pub fn evaluate_sequence(
    sequence: &OccupancySequence,
    methods: &[&dyn MapMethod],
    params: &OccupancyParams,
    on_map: &(dyn Fn(&str, usize) + Sync),
) -> Result<SequenceScores> {
    params.validate()?;
    let mut scores = SequenceScores {
        name: sequence.name.clone(),
        ..SequenceScores::default()
    };
    // One query scan after the other, so a map's seconds are its own (the GP parallelises inside).
    let per_scan = params
        .query_scans
        .iter()
        .map(|&t| score_query_scan(sequence, methods, params, t, on_map))
        .collect::<Result<Vec<_>>>()?;
    for scan in per_scan {
        let t = scan.query_scan;
        scores.query_secs.insert(t, scan.query_secs);
        scores.query_points.insert(t, scan.figure.grid.len());
        scores
            .occupied_points
            .insert(t, scan.figure.truth.iter().filter(|&&o| o).count());
        for (name, (auc, seconds, output)) in &scan.maps {
            let entry = scores.methods.entry(*name).or_default();
            entry.auc_by_query_scan.insert(t, *auc);
            entry.seconds_per_map.push(*seconds);
            entry.training_points_per_map.push(output.training_points);
            entry.drawn_points_per_map.push(output.drawn_points);
            entry.summaries.push(output.summary.clone());
            entry.solver_per_map.push(output.solver.clone());
            entry
                .temporal_lengthscales_per_map
                .push(output.temporal_lengthscales.clone());
        }
        if params.figure_scans.contains(&t) {
            let mut figure = scan.figure;
            figure.maps = scan
                .maps
                .into_iter()
                .map(|(name, (_, _, output))| (name, output))
                .collect();
            scores.figures.push(figure);
        }
    }
    Ok(scores)
}

/// Every method's map at one query scan: AUC, seconds and output by method, and the lattice,
/// truth and scan (the figure without its maps).
struct QueryScanScores {
    query_scan: usize,
    query_secs: f64,
    maps: BTreeMap<MapMethodId, (Option<f64>, f64, MapOutput)>,
    figure: MapFigure,
}

fn score_query_scan(
    sequence: &OccupancySequence,
    methods: &[&dyn MapMethod],
    params: &OccupancyParams,
    t: usize,
    on_map: &(dyn Fn(&str, usize) + Sync),
) -> Result<QueryScanScores> {
    let first = (t + 1)
        .checked_sub(params.scans_per_map)
        .filter(|_| t < sequence.scans.len());
    let Some(first) = first else {
        return Err(OccupancyError::Unsupported {
            path: sequence.dir.clone(),
            reason: format!(
                "query scan {t} needs scans {} to {t}, the sequence has {}",
                t as i64 + 1 - params.scans_per_map as i64,
                sequence.scans.len()
            ),
        });
    };
    let query = &sequence.scans[t];
    let window = ScanWindow {
        scans: &sequence.scans[first..=t],
        query_secs: query.stamp_secs,
    };
    // The lattice the sensor observes and the exact occupancy there at the query time.
    let grid = QueryGrid::observed_by(
        query,
        &sequence.sensor,
        params.query_spacing_m,
        &sequence.truth,
        sequence.scan_height_m(),
    );
    let truth =
        sequence
            .truth
            .occupancy(&grid.points_m, sequence.scan_height_m(), query.stamp_secs);
    let mut maps = BTreeMap::new();
    for method in methods {
        // One map: fit and prediction over the query points, timed together.
        let start = Instant::now();
        let output = method.map(&window, &grid.points_m)?;
        let seconds = start.elapsed().as_secs_f64();
        // Score: ROC AUC of the probability of occupancy against the truth (Table 1).
        let auc = roc_auc(&output.probability, &truth);
        on_map(method.id().name(), t);
        maps.insert(method.id(), (auc, seconds, output));
    }
    Ok(QueryScanScores {
        query_scan: t,
        query_secs: query.stamp_secs,
        maps,
        figure: MapFigure {
            query_scan: t,
            grid,
            truth,
            scan: query.clone(),
            maps: BTreeMap::new(),
        },
    })
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    if n == 0 { 0.0 } else { sum / n as f64 }
}
