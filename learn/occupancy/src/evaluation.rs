//! Scoring map methods on a sequence (DGPOM paper, Section 3.1, Table 1): at every query scan,
//! each method builds one map from the scan at the query time and the ones before it, predicts
//! over the lattice of query points the sensor observes, and is scored by ROC AUC against the
//! exact occupancy at the query time. One map (fit and prediction) is timed as a unit, in wall
//! and CPU seconds, alone on its thread (the maps run side by side, one per core).

use std::collections::BTreeMap;

use crate::{
    MapMethod, MapMethodId, MapOutput, OccupancyError, OccupancyParams, OccupancySequence,
    PlanarScan, QueryGrid, Result, ScanWindow, roc_auc,
};

use crate::map_jobs::run_jobs;

/// One method's scores over the query scans.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MethodScores {
    /// ROC AUC at each query scan (`None` if the truth there holds one class only).
    pub auc_by_query_scan: BTreeMap<usize, Option<f64>>,
    /// Wall-clock seconds of each map (fit and prediction over the query points).
    pub seconds_per_map: Vec<f64>,
    /// CPU seconds of each map (its thread's; `None` where the system does not report it).
    pub cpu_seconds_per_map: Vec<Option<f64>>,
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
/// The maps (query scan × method) are independent and run side by side on
/// [`OccupancyParams::worker_count`] threads, each alone on its thread (see `map_jobs.rs`), the
/// methods' maps in the order given (put the costliest first); the scores are the same for any
/// number of workers.
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
    let scans = params
        .query_scans
        .iter()
        .map(|&t| QueryScan::new(sequence, params, t))
        .collect::<Result<Vec<_>>>()?;
    let jobs: Vec<(usize, usize)> = (0..methods.len())
        .flat_map(|m| (0..scans.len()).map(move |s| (m, s)))
        .collect();
    // One map: fit and prediction over the query points, timed together on its own thread.
    let maps = run_jobs(jobs.len(), params.worker_count(), &|j| {
        let (m, s) = jobs[j];
        let output = methods[m].map(&scans[s].window(sequence), &scans[s].grid.points_m);
        if output.is_ok() {
            on_map(methods[m].id().name(), scans[s].t);
        }
        output
    });
    let mut by_scan: Vec<BTreeMap<MapMethodId, MapOutput>> = vec![BTreeMap::new(); scans.len()];
    for (&(m, s), map) in jobs.iter().zip(maps) {
        let output = map.value?;
        let scan = &scans[s];
        // Score: ROC AUC of the probability of occupancy against the truth (Table 1).
        let auc = roc_auc(&output.probability, &scan.truth);
        let entry = scores.methods.entry(methods[m].id()).or_default();
        entry.auc_by_query_scan.insert(scan.t, auc);
        entry.seconds_per_map.push(map.wall_secs);
        entry.cpu_seconds_per_map.push(map.cpu_secs);
        entry.training_points_per_map.push(output.training_points);
        entry.drawn_points_per_map.push(output.drawn_points);
        entry.summaries.push(output.summary.clone());
        entry.solver_per_map.push(output.solver.clone());
        entry
            .temporal_lengthscales_per_map
            .push(output.temporal_lengthscales.clone());
        by_scan[s].insert(methods[m].id(), output);
    }
    for (scan, maps) in scans.into_iter().zip(by_scan) {
        let t = scan.t;
        scores.query_secs.insert(t, sequence.scans[t].stamp_secs);
        scores.query_points.insert(t, scan.grid.len());
        scores
            .occupied_points
            .insert(t, scan.truth.iter().filter(|&&o| o).count());
        if params.figure_scans.contains(&t) {
            scores.figures.push(MapFigure {
                query_scan: t,
                grid: scan.grid,
                truth: scan.truth,
                scan: sequence.scans[t].clone(),
                maps,
            });
        }
    }
    Ok(scores)
}

/// One query scan: its window's first scan, the lattice the sensor observes and the exact
/// occupancy there at the query time.
struct QueryScan {
    t: usize,
    first: usize,
    grid: QueryGrid,
    truth: Vec<bool>,
}

impl QueryScan {
    fn new(sequence: &OccupancySequence, params: &OccupancyParams, t: usize) -> Result<Self> {
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
        Ok(Self {
            t,
            first,
            grid,
            truth,
        })
    }

    /// The scans the map is built from: the query scan and the ones before it.
    fn window<'a>(&self, sequence: &'a OccupancySequence) -> ScanWindow<'a> {
        ScanWindow {
            scans: &sequence.scans[self.first..=self.t],
            query_secs: sequence.scans[self.t].stamp_secs,
        }
    }
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    if n == 0 { 0.0 } else { sum / n as f64 }
}
