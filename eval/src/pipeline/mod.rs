//! The benchmark's pipeline, stage by stage: the plan, the generated data, the training samples,
//! cross-validation, the evaluation of every sequence, the further seeds' target tables and the
//! occupancy maps, each with its progress bar. `bench` and `study` run these stages, and so do the
//! binary's single-stage commands (`generate`, `cv`, `evaluate`, `occupancy`).

pub(crate) mod data_folders;
pub(crate) mod dataset_evaluation;
pub(crate) mod plan;
pub(crate) mod progress;
pub(crate) mod short_tracks;
pub(crate) mod stages;
pub(crate) mod target_runs;
