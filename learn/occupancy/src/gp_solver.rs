//! Which GP the occupancy maps solve (issue 25): the exact GP (Cholesky of the full N×N kernel,
//! jitter retried, a failure an error value) for maps up to a few thousand training points, the
//! DGPOM paper's scale, and SPGP with pseudo-inputs held at a seeded subset of the training points
//! above that. 50 random pseudo-inputs cost the T-junction's maps about 0.09 AUC and 750 raised
//! the 3-D slice's DGPOM from 0.882 to 0.919, so sparsity is used only where the exact GP's
//! O(N³) cost and O(N²) memory would not fit.

use patchflow_gp::{FULL_GP_MAX_SAMPLES, GpKind, GpParams};
use serde::{Deserialize, Serialize};

/// The range a temporal length-scale is fitted in, seconds: what a window of four scans 1 s apart
/// can identify. Below about a quarter of the scan interval the scans decorrelate completely;
/// above ten times the window's 3 s span the kernel across it stays above 0.98 ("no decay"), and
/// unbounded fits landed anywhere from 30 s to 10^7 s (issue 25). DGPOM's l_t(ε) and
/// `GPOM-RD1`'s ℓt are both held in it.
pub const TEMPORAL_RANGE_SECS: [f64; 2] = [0.25, 30.0];

/// The switch between the exact GP and SPGP.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GpSolver {
    /// Maps with at most this many training points fit the exact GP (at most
    /// [`FULL_GP_MAX_SAMPLES`]); 0 always fits SPGP.
    pub exact_up_to: usize,
    /// Pseudo-inputs of the SPGP used above `exact_up_to`.
    pub pseudo_inputs: usize,
    /// Smallest noise variance of the regression on the ±1 labels, in the standardised labels'
    /// units (their variance is 1). Left free, the marginal likelihood of the exact GP drives it
    /// to 0 on the T-junction (σ² = 0.000 in every DGPOM fit): the regression interpolates every
    /// label, returns and free samples 0.3 m apart included, and the sub-metre length-scales it
    /// then picks cost DGPOM 0.03 AUC (issue 25; docs/occupancy.md). The exact GP's only: on
    /// the busy intersection's SPGP maps the same floor cost DGPOM 0.009 (0.864 to 0.855).
    pub noise_floor: f64,
}

impl Default for GpSolver {
    fn default() -> Self {
        Self {
            exact_up_to: FULL_GP_MAX_SAMPLES,
            pseudo_inputs: 250,
            noise_floor: 0.05,
        }
    }
}

impl GpSolver {
    /// Whether a map of `n` training points fits the exact GP.
    pub fn is_exact(&self, n: usize) -> bool {
        n <= self.exact_up_to.min(FULL_GP_MAX_SAMPLES)
    }

    /// The GP parameters for a map of `n` training points (`seed` places the pseudo-inputs).
    pub fn params(&self, n: usize, seed: u64) -> GpParams {
        if self.is_exact(n) {
            GpParams::new(GpKind::Full).noise_floor(self.noise_floor)
        } else {
            GpParams::new(GpKind::Spgp)
                .pseudo_inputs(self.pseudo_inputs)
                .optimise_pseudo_inputs(false)
                .seed(seed)
        }
    }

    /// The path a map of `n` training points takes, for reports: `exact` or `SPGP M`.
    pub fn path(&self, n: usize) -> String {
        if self.is_exact(n) {
            "exact".into()
        } else {
            format!("SPGP {}", self.pseudo_inputs.min(n))
        }
    }

    /// The switch in words, for the report.
    pub fn describe(&self) -> String {
        let up_to = self.exact_up_to.min(FULL_GP_MAX_SAMPLES);
        format!(
            "the exact GP (Cholesky of the full kernel matrix, jitter retried) for maps of up to {up_to} training points, SPGP with {} pseudo-inputs held at a seeded subset of the training points above that; the exact GP's noise variance of the regression on the ±1 labels is held at or above {} of the standardised labels' variance",
            self.pseudo_inputs, self.noise_floor
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn maps_up_to_the_threshold_are_exact_and_larger_ones_sparse() {
        let solver = GpSolver {
            exact_up_to: 1000,
            pseudo_inputs: 50,
            ..GpSolver::default()
        };
        assert!(solver.is_exact(1000));
        assert!(!solver.is_exact(1001));
        assert_eq!(solver.path(10), "exact");
        assert_eq!(solver.path(5000), "SPGP 50");
    }

    #[test]
    fn exact_maps_hold_the_noise_floor_and_sparse_ones_keep_the_gp_default() {
        let solver = GpSolver::default();
        let exact = solver.params(100, 7).check().expect("valid");
        assert_eq!(exact.noise_floor(), solver.noise_floor);
        let sparse = solver.params(10_000, 7).check().expect("valid");
        let default = GpParams::new(GpKind::Spgp).check().expect("valid");
        assert_eq!(sparse.noise_floor(), default.noise_floor());
        assert!(solver.describe().contains("0.05"));
    }

    #[test]
    fn the_threshold_never_exceeds_what_the_exact_gp_accepts() {
        let solver = GpSolver {
            exact_up_to: usize::MAX,
            pseudo_inputs: 50,
            ..GpSolver::default()
        };
        assert!(!solver.is_exact(FULL_GP_MAX_SAMPLES + 1));
    }
}
