//! What an occupancy evaluation does, with the DGPOM paper's protocol as the default (Section 3.1,
//! Table 1, Figure 6): query times t = 3 … 9, each map from the scan at the query time and the
//! three before, figures at t = 3 and t = 5.

use serde::{Deserialize, Serialize};

use crate::{OccupancyError, Result};

/// Parameters of [`crate::evaluate_sequence`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OccupancyParams {
    /// Query scans (the scan index is the paper's t in seconds at its 1 Hz).
    pub query_scans: Vec<usize>,
    /// Scans per map: the query scan and the `scans_per_map − 1` before it.
    pub scans_per_map: usize,
    /// Spacing of the lattice of query points over the observed area, metres.
    pub query_spacing_m: f64,
    /// Query scans whose maps are kept for figures (Figure 6: t = 3 and t = 5).
    pub figure_scans: Vec<usize>,
    /// Maps built side by side, each alone on its thread; 0 is one per thread of rayon's pool
    /// (one per core unless `RAYON_NUM_THREADS` says otherwise). The scores do not depend on it.
    pub workers: usize,
}

impl Default for OccupancyParams {
    fn default() -> Self {
        Self {
            query_scans: (3..=9).collect(),
            scans_per_map: 4,
            query_spacing_m: 0.5,
            figure_scans: vec![3, 5],
            workers: 0,
        }
    }
}

impl OccupancyParams {
    /// Checks the parameters; an error names the bad field.
    pub fn validate(&self) -> Result<()> {
        let bad =
            |name: &'static str, reason: String| Err(OccupancyError::BadParameter { name, reason });
        if self.query_scans.is_empty() {
            return bad("OccupancyParams.query_scans", "no query scan".into());
        }
        if self.scans_per_map == 0 {
            return bad("OccupancyParams.scans_per_map", "must be at least 1".into());
        }
        if !(self.query_spacing_m.is_finite() && self.query_spacing_m >= 0.05) {
            return bad(
                "OccupancyParams.query_spacing_m",
                format!("must be at least 0.05 m, got {}", self.query_spacing_m),
            );
        }
        if let Some(t) = self
            .figure_scans
            .iter()
            .find(|t| !self.query_scans.contains(t))
        {
            return bad(
                "OccupancyParams.figure_scans",
                format!("scan {t} is not a query scan"),
            );
        }
        Ok(())
    }

    /// The number of maps built side by side: `workers`, or one per thread of rayon's pool.
    pub fn worker_count(&self) -> usize {
        match self.workers {
            0 => rayon::current_num_threads(),
            n => n,
        }
    }
}
