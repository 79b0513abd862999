//! The per-scan scene scoring (thesis 4.1, 4.4 and the whole scene): every sequence replayed scan
//! by scan as a car would run it, each method's estimates against the truth at that scan, the
//! per-target metrics (Eq. 4.1), the scene flow and moving-object IoU over every scored point,
//! every actor's scores, and what each scan's perception cost.

pub(crate) mod cpu_time;
pub(crate) mod flow_export;
pub(crate) mod method_flows;
pub(crate) mod metrics;
pub(crate) mod moving_iou;
pub(crate) mod objects;
pub(crate) mod oracle;
pub(crate) mod perception_timing;
pub(crate) mod result;
pub(crate) mod scan_scoring;
pub(crate) mod scene_evaluation;
pub(crate) mod scene_flow;
pub(crate) mod scene_point;
pub(crate) mod target_columns;
pub(crate) mod truth_at_scan;
