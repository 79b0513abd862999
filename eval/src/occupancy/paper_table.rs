//! The DGPOM paper's Table 1 (O'Callaghan & Ramos, Section 3.1): ROC AUC at query times t = 3 … 9
//! on their simulated T-junction, each map from the scan at the query time and the three before.
//! Reports print these beside ours, labelled as the paper's.

use patchflow_occupancy::MapMethodId;

/// One algorithm's row of the paper's Table 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperRow {
    /// Our method (`DGPOM`, `GPOM-RD`, `GPOM-RD1`).
    pub method: MapMethodId,
    /// The paper's label.
    pub label: &'static str,
    /// AUC at t = 3 … 9.
    pub auc: [f64; 7],
}

/// The query times of the paper's Table 1, seconds (scans at 1 Hz).
pub const PAPER_QUERY_TIMES: [u32; 7] = [3, 4, 5, 6, 7, 8, 9];

/// The paper's Table 1, row by row as printed.
pub const PAPER_TABLE_1: [PaperRow; 3] = [
    PaperRow {
        method: MapMethodId::Dgpom,
        label: "DGPOM ℜ^{D+1}",
        auc: [0.9497, 0.9301, 0.9300, 0.9288, 0.9480, 0.9372, 0.9435],
    },
    PaperRow {
        method: MapMethodId::GpomRd,
        label: "GPOM ℜ^D",
        auc: [0.7736, 0.8040, 0.8248, 0.8227, 0.8364, 0.8376, 0.8850],
    },
    PaperRow {
        method: MapMethodId::GpomRd1,
        label: "GPOM ℜ^{D+1}",
        auc: [0.8383, 0.8773, 0.8903, 0.8954, 0.9267, 0.8922, 0.8974],
    },
];
