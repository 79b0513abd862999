//! Cross-validation of the GP features (thesis 4.3, Tables 4.1-4.4): its settings, one fold, the
//! whole run and its tables (written by `report`).

pub(crate) mod cross_validation;
pub(crate) mod cv_fold;
pub(crate) mod cv_params;
pub(crate) mod cv_report;
