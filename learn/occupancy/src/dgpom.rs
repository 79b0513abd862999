//! DGPOM, the dynamic GP occupancy map (O'Callaghan & Ramos, Sections 2-3): the GPOM classifier
//! (probabilistic least squares, α and β by leave-one-out) with the motion-adapted kernel of
//! `patchflow-gp` ([`MotionAdapted`], eqs. 2-6) reading a motion map learned beforehand from a
//! training run ([`MotionMap`], Section 2.3). The window's observations are carried along the
//! motion map to the query time, so a car hidden at the query time is still predicted where the
//! flow has taken its earlier returns; ℓ, s, a and b are learned per map by maximising the
//! marginal likelihood.

use std::collections::BTreeMap;
use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::sync::{Arc, Mutex};

use nalgebra::DMatrix;
use patchflow_gp::{MotionAdapted, PlsClassifier, PlsParams};
use serde::{Deserialize, Serialize};

use crate::{
    GpSolver, MapMethod, MapMethodId, MapOutput, MotionMap, OccupancyError, Result, SampleParams,
    ScanWindow, TEMPORAL_RANGE_SECS, window_samples,
};

/// Settings of DGPOM (the motion map is learned separately and shared).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DgpomParams {
    /// How training samples are drawn from each scan.
    pub samples: SampleParams,
    /// Exact GP up to a few thousand training points, SPGP above.
    pub solver: GpSolver,
    /// Iteration limit of the marginal-likelihood maximisation.
    pub max_iters: usize,
    /// Step of the flow-line integration (eq. 4), seconds.
    pub step_secs: f64,
    /// Range l_t(x) is held in, seconds: what a window of four scans 1 s apart can identify
    /// (below about a quarter of the scan interval the scans decorrelate completely; above ten
    /// times the window's 3 s span the Matérn 3/2 across it stays above 0.98, "no decay").
    pub temporal_range_secs: [f64; 2],
}

impl Default for DgpomParams {
    fn default() -> Self {
        Self {
            samples: SampleParams::default(),
            solver: GpSolver::default(),
            // With the exact GP, 25 iterations give the AUC of 50 (T-junction, seed 7: 0.882
            // both) at half the CPU: the fits wander along a flat direction of a and b.
            max_iters: 25,
            step_secs: 0.1,
            temporal_range_secs: TEMPORAL_RANGE_SECS,
        }
    }
}

/// The errors ε (m/s) at which the report states the learned l_t(ε) = a·ε^(−1/b).
pub const LT_ERRORS_MPS: [f64; 5] = [0.1, 0.25, 0.5, 1.0, 2.0];

/// DGPOM as a map method. Clones share the fits already made (see [`DgpomMethod::new`]).
#[derive(Debug, Clone)]
pub struct DgpomMethod {
    /// The settings.
    pub params: DgpomParams,
    /// The motion map learned from the training run.
    pub motion_map: Arc<MotionMap>,
    fits: FitCache,
}

type Classifier = PlsClassifier<MotionAdapted<MotionMap>>;

/// A fit and its (training, drawn) point counts.
type Fit = Arc<(Classifier, [usize; 2])>;

/// Fits already made, by what determines them: the window's scans and the reference time.
/// Predicting ahead from start time t fits exactly the map of query time t (the same scans
/// carried to the same time), so that fit is made once.
#[derive(Debug, Clone, Default)]
struct FitCache(Arc<Mutex<BTreeMap<u64, Fit>>>);

impl FitCache {
    /// The key of a fit: a hash of every beam and stamp of the window and the reference time.
    fn key(window: &ScanWindow<'_>, reference_secs: f64) -> u64 {
        let mut h = DefaultHasher::new();
        reference_secs.to_bits().hash(&mut h);
        for scan in window.scans {
            (scan.index, scan.stamp_secs.to_bits(), scan.beams.len()).hash(&mut h);
            for b in &scan.beams {
                (
                    b.start_m.map(f64::to_bits),
                    b.end_m.map(f64::to_bits),
                    b.hit,
                )
                    .hash(&mut h);
            }
        }
        h.finish()
    }

    fn get(&self, key: u64) -> Option<Fit> {
        self.0.lock().ok()?.get(&key).cloned()
    }

    fn put(&self, key: u64, fit: Fit) {
        if let Ok(mut fits) = self.0.lock() {
            fits.insert(key, fit);
        }
    }
}

impl DgpomMethod {
    /// DGPOM with `params` on `motion_map`. The method keeps the fits it makes (a few per
    /// sequence, each holding its N×N Cholesky factor), so predicting ahead of a query time
    /// reuses that time's fit; clones share them.
    pub fn new(params: DgpomParams, motion_map: Arc<MotionMap>) -> Self {
        Self {
            params,
            motion_map,
            fits: FitCache::default(),
        }
    }

    /// How many fits the method (and its clones) keep.
    pub fn fits_kept(&self) -> usize {
        self.fits.0.lock().map_or(0, |fits| fits.len())
    }

    /// The fit of `window` with its observations carried to `reference_secs`, made once.
    fn fit_once(&self, window: &ScanWindow<'_>, reference_secs: f64) -> Result<Fit> {
        let key = FitCache::key(window, reference_secs);
        if let Some(fit) = self.fits.get(key) {
            return Ok(fit);
        }
        let fit = Arc::new(self.fit(window, reference_secs)?);
        self.fits.put(key, Arc::clone(&fit));
        Ok(fit)
    }

    /// Fits the classifier to the window's samples, observations carried to `reference_secs`.
    fn fit(
        &self,
        window: &ScanWindow<'_>,
        reference_secs: f64,
    ) -> Result<(Classifier, [usize; 2])> {
        self.params.samples.validate()?;
        let scan = window.query_scan().map_or(0, |s| s.index);
        // Training data: returns occupied, free space along the beams, each at its scan's time
        // (thinned for dense scans).
        let (samples, drawn) = window_samples(window.scans, &self.params.samples);
        let x = DMatrix::from_fn(samples.len(), 3, |i, d| match d {
            0 | 1 => samples[i].xy_m[d],
            _ => samples[i].t_secs,
        });
        let labels: Vec<bool> = samples.iter().map(|s| s.occupied).collect();
        // The motion-adapted kernel (eqs. 2-6) in the exact GP (SPGP with fixed pseudo-inputs for large maps), squashed by
        // probabilistic least squares as GPOM.
        let kernel = MotionAdapted::new(Arc::clone(&self.motion_map), reference_secs)
            .step_secs(self.params.step_secs)
            .temporal_range_secs(
                self.params.temporal_range_secs[0],
                self.params.temporal_range_secs[1],
            )
            .map_err(|e| self.degenerate(scan, e.to_string()))?;
        let gp = self
            .params
            .solver
            .params(samples.len(), self.params.samples.seed ^ scan as u64)
            .max_iters(self.params.max_iters)
            .kernel(kernel);
        let classifier = PlsParams::new(gp)
            .fit(&x, &labels)
            .map_err(|e| self.degenerate(scan, e.to_string()))?;
        Ok((classifier, [samples.len(), drawn]))
    }

    /// The map of the fitted classifier at `points_m` at `t_secs`.
    fn predict(
        &self,
        classifier: &Classifier,
        points_m: &[[f64; 2]],
        t_secs: f64,
        [training_points, drawn_points]: [usize; 2],
        scan: usize,
    ) -> Result<MapOutput> {
        let query = DMatrix::from_fn(points_m.len(), 3, |i, d| match d {
            0 | 1 => points_m[i][d],
            _ => t_secs,
        });
        let prediction = classifier
            .predict(&query)
            .map_err(|e| self.degenerate(scan, e.to_string()))?;
        let kernel = classifier.regression().kernel();
        let [lx, ly] = kernel.lengthscales_m();
        let s = classifier.squashing();
        Ok(MapOutput {
            probability: prediction.probability.iter().copied().collect(),
            variance: Some(prediction.regression.var_latent.iter().copied().collect()),
            training_points,
            drawn_points,
            summary: format!(
                "ℓx {lx:.2} m, ℓy {ly:.2} m, a {:.2}, b {:.2} (l_t {:.2} s at ε = 0.5 m/s), σ² = {:.3}, α = {:.2}, β = {:.2}, {} evaluations",
                kernel.time_scale_a(),
                kernel.decay_b(),
                kernel.temporal_lengthscale_secs(0.5),
                classifier.regression().noise_variance(),
                s.alpha,
                s.beta,
                classifier.regression().fit_report().evals
            ),
            solver: Some(self.params.solver.path(training_points)),
            temporal_lengthscales: LT_ERRORS_MPS
                .iter()
                .map(|&e| [e, kernel.temporal_lengthscale_secs(e)])
                .collect(),
        })
    }

    fn degenerate(&self, scan: usize, reason: String) -> OccupancyError {
        OccupancyError::Degenerate {
            method: MapMethodId::Dgpom.name().into(),
            scan,
            reason,
        }
    }
}

impl MapMethod for DgpomMethod {
    fn id(&self) -> MapMethodId {
        MapMethodId::Dgpom
    }

    fn map(&self, window: &ScanWindow<'_>, points_m: &[[f64; 2]]) -> Result<MapOutput> {
        let scan = window.query_scan().map_or(0, |s| s.index);
        let fit = self.fit_once(window, window.query_secs)?;
        self.predict(&fit.0, points_m, window.query_secs, fit.1, scan)
    }

    /// One fit with the observations carried to the last scan, then predictions at each later
    /// time (the query points carried back along the motion map to the last scan).
    fn map_ahead(
        &self,
        window: &ScanWindow<'_>,
        points_m: &[[f64; 2]],
        times_secs: &[f64],
    ) -> Result<Vec<MapOutput>> {
        let scan = window.query_scan().map_or(0, |s| s.index);
        let last = window
            .query_scan()
            .map_or(window.query_secs, |s| s.stamp_secs);
        let fit = self.fit_once(window, last)?;
        times_secs
            .iter()
            .map(|&t| self.predict(&fit.0, points_m, t, fit.1, scan))
            .collect()
    }
}
