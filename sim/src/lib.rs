//! The patchflow simulator: scenario files → Rapier scene → rolling-shutter spinning lidar →
//! labelled sweeps in the dataset format of SPEC §4.

pub use patchflow_dataset as dataset;
