//! The baselines of thesis 3.2: ICP on consecutive clusters (`icp`, `rigid_fit`, `rigid_motion`),
//! the constant-velocity Kalman filter (`kalman`, `innovation`, `velocity_measurement`), their
//! self-associating forms over every cluster (`tracker` and `track_filter` for KF-AUTO, with
//! `gp_trust_filter` for GP-KF; `cluster_association` for ICP-AUTO), and the step that runs them
//! all scan by scan (`baseline_step`, `baseline_method`).

pub(crate) mod baseline_method;
pub(crate) mod baseline_params;
pub(crate) mod baseline_step;
pub(crate) mod box_reference;
pub(crate) mod cluster_association;
pub(crate) mod gp_trust_filter;
pub(crate) mod icp;
pub(crate) mod innovation;
pub(crate) mod kalman;
pub(crate) mod reference_point;
pub(crate) mod rigid_fit;
pub(crate) mod rigid_motion;
pub(crate) mod track_filter;
pub(crate) mod tracker;
pub(crate) mod velocity_measurement;
