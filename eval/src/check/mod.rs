//! Trained models read on targets of the user's own scenarios over several world draws, tallied
//! against the bar (issue 24's unseen targets): `patchflow check`.

pub(crate) mod check_markdown;
pub(crate) mod check_plan;
pub(crate) mod check_report;
pub(crate) mod run_checks;
pub(crate) mod target_reading;
