//! The learned motion map (DGPOM paper, Section 2.3): the motion clusters of every pair of
//! consecutive scans of a training run (stationary only where the run never saw a change,
//! `ChangedCells`), a mean velocity field Υ(x) regressed from a subset of their cells (the paper
//! uses 500 points; both components, one GP each), and an error field ε(x) regressed from how far
//! Υ misses the velocities of the clusters of held-out scan pairs (`VelocitySamples`). The fields are
//! sampled on a lattice ([`FieldRaster`]) over what the run observed, and the map is the
//! [`MotionField`] of DGPOM's kernel.

use nalgebra::{DMatrix, DVector};
use patchflow_gp::{GpKind, GpModel, GpParams, MotionField};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use crate::changed_cells::ChangedCells;
use crate::cluster_pairing::PairScans;
use crate::motion_clusters::motion_clusters;
use crate::scan_cells::ScanCells;
use crate::velocity_samples::{Sample, VelocitySamples};
use crate::{
    FieldRaster, MotionAccuracy, MotionCluster, MotionClusterParams, OccupancyError,
    OccupancySequence, Result,
};

/// Settings of the motion map.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MotionMapParams {
    /// How motion clusters are found.
    pub clusters: MotionClusterParams,
    /// Cells the velocity regressor is trained on (paper: 500).
    pub velocity_points: usize,
    /// Held-out cells the error regressor is trained on.
    pub error_points: usize,
    /// Share of the scan pairs whose clusters are held out from the velocity regressor for the
    /// error field (every ⌈1/share⌉-th pair, whole).
    pub held_out_fraction: f64,
    /// Smallest error the map reports, m/s (ε^(−1/b) stays bounded where Υ fits exactly).
    pub min_error_mps: f64,
    /// Spacing of the lattice the fields are sampled on, metres.
    pub raster_m: f64,
    /// Iteration limit of each regressor's marginal-likelihood maximisation.
    pub max_iters: usize,
    /// Seed of the subsets drawn where a kind has more cells than its half of the draw.
    pub seed: u64,
}

impl Default for MotionMapParams {
    fn default() -> Self {
        Self {
            clusters: MotionClusterParams::default(),
            velocity_points: 500,
            error_points: 500,
            held_out_fraction: 0.3,
            min_error_mps: 0.05,
            raster_m: 0.5,
            max_iters: 60,
            seed: 7,
        }
    }
}

/// Largest number of raster nodes; a wider area gets a coarser lattice.
const MAX_RASTER_NODES: usize = 250_000;
/// Margin of the raster around what the training run observed, metres.
const RASTER_MARGIN_M: f64 = 4.0;
/// Points per prediction batch (bounds the k(X, x*) matrix).
const BATCH: usize = 8192;

/// Field indices in the raster.
const VX: usize = 0;
const VY: usize = 1;
const ERROR: usize = 2;

/// A mean velocity field and its error field, learned from a training run.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionMap {
    /// Every motion cluster of the training run, with its velocity (Figure 5a).
    pub clusters: Vec<MotionCluster>,
    /// Υ_x, Υ_y and ε sampled on a lattice.
    pub raster: FieldRaster,
    /// Cells the velocity regressor was trained on.
    pub velocity_points: usize,
    /// Held-out cells the error regressor was trained on.
    pub error_points: usize,
    /// What the regressors learned, one line.
    pub summary: String,
    /// Υ against the training run's actors, on the lanes and off them.
    pub accuracy: MotionAccuracy,
    min_error_mps: f64,
}

impl MotionMap {
    /// Learns the motion map from every pair of consecutive scans of `training`.
    pub fn learn(training: &OccupancySequence, params: &MotionMapParams) -> Result<Self> {
        let degenerate = |reason: String| OccupancyError::Degenerate {
            method: "DGPOM motion map".into(),
            scan: 0,
            reason: format!("{}: {reason}", training.dir.display()),
        };
        // Motion clusters of consecutive scans (Figure 3).
        let cells: Vec<ScanCells> = training
            .scans
            .iter()
            .map(|s| ScanCells::from_scan(s, params.clusters.cell_m))
            .collect();
        let clusters: Vec<MotionCluster> = (1..cells.len())
            .flat_map(|k| {
                let scans = PairScans {
                    first: &cells[k - 1],
                    second: &cells[k],
                    before: k.checked_sub(2).map(|i| &cells[i]),
                    after: cells.get(k + 1),
                };
                motion_clusters(&scans, training.scans[k].index, &params.clusters)
            })
            .collect();
        // Stillness only where the run never saw a change (`ChangedCells`).
        let changed = ChangedCells::of_run(&cells);
        let clusters: Vec<MotionCluster> = clusters
            .into_iter()
            .filter_map(|c| changed.evidence(c))
            .collect();
        // Υ's cells and the held-out pairs' cells for ε (`VelocitySamples`).
        let mut rng = ChaCha8Rng::seed_from_u64(params.seed);
        let VelocitySamples {
            fitted: velocity_samples,
            held_out: held_samples,
        } = VelocitySamples::draw(
            &clusters,
            (params.velocity_points, params.error_points),
            params.held_out_fraction,
            &mut rng,
        );
        if velocity_samples.len() < 10 || held_samples.len() < 10 {
            return Err(degenerate(format!(
                "{} motion clusters give {} training and {} held-out cells; at least 10 of each are needed",
                clusters.len(),
                velocity_samples.len(),
                held_samples.len()
            )));
        }
        // Υ(x): one regressor per component.
        let fit = |samples: &[Sample], component: usize| -> Result<GpModel> {
            let x = DMatrix::from_fn(samples.len(), 2, |i, d| samples[i].0[d]);
            let y = DVector::from_fn(samples.len(), |i, _| samples[i].1[component]);
            GpParams::new(GpKind::Full)
                .max_iters(params.max_iters)
                .fit(&x, &y)
                .map_err(|e| degenerate(e.to_string()))
        };
        let (vx, vy) = (fit(&velocity_samples, 0)?, fit(&velocity_samples, 1)?);
        // ε(x): how far Υ misses the held-out clusters' velocities.
        let held_points: Vec<[f64; 2]> = held_samples.iter().map(|s| s.0).collect();
        let (ux, uy) = (predict(&vx, &held_points)?, predict(&vy, &held_points)?);
        let errors: Vec<Sample> = held_samples
            .iter()
            .enumerate()
            .map(|(i, (p, v))| (*p, [(v[0] - ux[i]).hypot(v[1] - uy[i]), 0.0]))
            .collect();
        let error = fit(&errors, 0)?;
        // Sample the three fields over what the training run observed.
        let (lo, hi) = observed_box(training);
        let area = (hi[0] - lo[0]) * (hi[1] - lo[1]);
        let step = params.raster_m.max((area / MAX_RASTER_NODES as f64).sqrt());
        let (mut raster, nodes) = FieldRaster::lattice(lo, hi, step);
        raster.values = vec![
            predict(&vx, &nodes)?,
            predict(&vy, &nodes)?,
            predict(&error, &nodes)?,
        ];
        let describe = |name: &str, m: &GpModel| {
            let l = m.lengthscales();
            let spread = m.fit_report();
            format!(
                "{name}: {} evaluations, σ² {:.3}, ℓ (standardised) {:.2}/{:.2}",
                spread.evals,
                m.noise_variance(),
                l[0],
                l[1]
            )
        };
        let summary = format!(
            "{} motion clusters; Υ from {} cells, ε from {} held-out cells; {}; {}; {}",
            clusters.len(),
            velocity_samples.len(),
            errors.len(),
            describe("Υx", &vx),
            describe("Υy", &vy),
            describe("ε", &error)
        );
        let mut map = Self {
            clusters,
            raster,
            velocity_points: velocity_samples.len(),
            error_points: errors.len(),
            summary,
            accuracy: MotionAccuracy::default(),
            min_error_mps: params.min_error_mps,
        };
        map.accuracy = MotionAccuracy::of(&map, training, params.clusters.cell_m);
        Ok(map)
    }
}

impl MotionField for MotionMap {
    fn velocity_mps(&self, xy_m: [f64; 2]) -> [f64; 2] {
        [self.raster.at(VX, xy_m), self.raster.at(VY, xy_m)]
    }

    fn error_mps(&self, xy_m: [f64; 2]) -> f64 {
        self.raster.at(ERROR, xy_m).max(self.min_error_mps)
    }
}

/// The regressor's mean at `points`, in batches.
fn predict(model: &GpModel, points: &[[f64; 2]]) -> Result<Vec<f64>> {
    let mut out = Vec::with_capacity(points.len());
    for batch in points.chunks(BATCH) {
        let x = DMatrix::from_fn(batch.len(), 2, |i, d| batch[i][d]);
        let p = model.predict(&x).map_err(|e| OccupancyError::Degenerate {
            method: "DGPOM motion map".into(),
            scan: 0,
            reason: e.to_string(),
        })?;
        out.extend(p.mean.iter());
    }
    Ok(out)
}

/// The box around every sensor position and beam end of `training`, with a margin.
fn observed_box(training: &OccupancySequence) -> ([f64; 2], [f64; 2]) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for scan in &training.scans {
        for p in std::iter::once(scan.sensor_m).chain(scan.beams.iter().map(|b| b.end_m)) {
            for d in 0..2 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
    }
    (
        [lo[0] - RASTER_MARGIN_M, lo[1] - RASTER_MARGIN_M],
        [hi[0] + RASTER_MARGIN_M, hi[1] + RASTER_MARGIN_M],
    )
}
