//! The tables of one cross-validation run (thesis Tables 4.1-4.4) as data: one row per feature,
//! prior and GP, averaged over the folds. `report` writes them to `cv.json` and `cv.md`.

use serde::{Deserialize, Serialize};

/// Input feature of the GPs (thesis 2.2.2-2.2.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CvFeature {
    /// 242-value difference-map and reflection-map patches.
    Patch,
    /// 16 Gabor filter responses.
    Gabor,
}

/// Which sparse GP (thesis 3.1.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub enum CvGp {
    /// SPGP / FITC.
    #[serde(rename = "SPGP")]
    Spgp,
    /// SPGP with one noise variance per pseudo-input.
    #[serde(rename = "SPGP-HET")]
    SpgpHet,
}

impl CvGp {
    pub(crate) fn name(self) -> &'static str {
        match self {
            Self::Spgp => "SPGP",
            Self::SpgpHet => "SPGP-HET",
        }
    }
}

impl CvFeature {
    pub(crate) fn name(self) -> &'static str {
        match self {
            Self::Patch => "patch",
            Self::Gabor => "gabor",
        }
    }
}

/// One cross-validation configuration, averaged over the folds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CvRow {
    /// Feature.
    pub feature: CvFeature,
    /// Map prior (0.01 or 0.5 in the thesis).
    pub prior: f64,
    /// GP.
    pub gp: CvGp,
    /// Heading RMSE over all test patches, degrees.
    pub heading_rmse_deg: f64,
    /// Heading RMSE over the low-variance test patches, degrees.
    pub heading_rmse_low_var_deg: Option<f64>,
    /// Speed RMSE over all test patches, m/s (the thesis only reports patch features, prior 0.5).
    pub speed_rmse_mps: Option<f64>,
    /// Speed RMSE over the low-variance test patches, m/s.
    pub speed_rmse_low_var_mps: Option<f64>,
    /// Test patches over all folds.
    pub n_test: usize,
    /// Low-variance test patches over all folds.
    pub n_low_var: usize,
}

/// A cross-validation run.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct CvReport {
    /// Number of folds.
    pub folds: usize,
    /// One row per configuration.
    pub rows: Vec<CvRow>,
    /// Notes for `cv.md`.
    pub notes: Vec<String>,
}
