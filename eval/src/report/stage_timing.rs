//! Seconds spent in one stage of a run, wall clock and CPU: the rows of the report's timing
//! table (`pipeline::progress::StageTimer` records them).

use serde::{Deserialize, Serialize};

/// Seconds spent in one named stage.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StageTiming {
    /// Stage name, e.g. `generate`, `train SPGP-HET`, `evaluate situation3`.
    pub stage: String,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// CPU seconds of the process over the stage, all threads together, where the system reports
    /// them: on a shared machine the wall time grows with the load, the CPU time hardly, and CPU
    /// over wall shows how many cores the stage kept busy.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cpu_seconds: Option<f64>,
}
