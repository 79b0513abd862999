//! The seam between the map methods and their evaluation: a method builds one map from a window
//! of scans (DGPOM paper, 3.1: the scan at the query time and the three before it) and predicts
//! the probability of occupancy, and its predictive variance where it has one, at query points at
//! the query time. The occupancy grid, GPOM in R^D and GPOM in R^{D+1} implement it here; DGPOM
//! (a motion-adapted kernel with a learned velocity field) implements it as one more method,
//! learned beforehand from a training run and carried inside the method value.

use crate::{MapMethodId, PlanarScan, Result};

/// The scans one map is built from.
#[derive(Debug, Clone, Copy)]
pub struct ScanWindow<'a> {
    /// The scans, oldest first; the last is the scan at the query time.
    pub scans: &'a [PlanarScan],
    /// The query time, seconds since the sequence started.
    pub query_secs: f64,
}

impl ScanWindow<'_> {
    /// The scan at the query time.
    pub fn query_scan(&self) -> Option<&PlanarScan> {
        self.scans.last()
    }
}

/// What one map gives at the query points.
#[derive(Debug, Clone, PartialEq)]
pub struct MapOutput {
    /// Probability of occupancy at each query point.
    pub probability: Vec<f64>,
    /// Predictive variance of the latent function at each query point, if the method has one.
    pub variance: Option<Vec<f64>>,
    /// Training points the map was built from (samples for a GP; beams for a grid).
    pub training_points: usize,
    /// Training points drawn before thinning (equal to `training_points` if none was thinned).
    pub drawn_points: usize,
    /// What the fit learned, for the report (hyperparameters, squashing), one line.
    pub summary: String,
    /// The GP the map solved (`exact` or `SPGP M`); `None` for a method without a GP.
    pub solver: Option<String>,
    /// The temporal length-scale the fit learned, (ε m/s or 0 for one without ε, l_t s) pairs;
    /// empty for a method without one.
    pub temporal_lengthscales: Vec<[f64; 2]>,
}

/// A way of building occupancy maps (GRID, GPOM-RD, GPOM-RD1, DGPOM).
pub trait MapMethod: Send + Sync {
    /// The method's id, whose name reports show (`GRID`, `GPOM-RD`, `GPOM-RD1`, `DGPOM`).
    fn id(&self) -> MapMethodId;

    /// Builds the map of `window` and predicts at `points_m` (world frame) at the window's query
    /// time: one map, fit and prediction, the unit the evaluation times.
    fn map(&self, window: &ScanWindow<'_>, points_m: &[[f64; 2]]) -> Result<MapOutput>;

    /// Predicts ahead with no newer scan (DGPOM paper, Figure 10): the map of `window`'s scans
    /// at `points_m` at each of `times_secs` (at or after the last scan). The default builds one
    /// map per time; methods whose fit does not depend on the query time fit once.
    fn map_ahead(
        &self,
        window: &ScanWindow<'_>,
        points_m: &[[f64; 2]],
        times_secs: &[f64],
    ) -> Result<Vec<MapOutput>> {
        times_secs
            .iter()
            .map(|&t| {
                let at = ScanWindow {
                    query_secs: t,
                    ..*window
                };
                self.map(&at, points_m)
            })
            .collect()
    }
}
