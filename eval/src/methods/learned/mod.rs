//! The learned perception of issue 27: the GP-informed trackers (GP-KF, GP-ICP) stepped scan by
//! scan beside the baselines, and the whole learned scan as a car would run it.

pub(crate) mod learned_perception;
pub(crate) mod learned_step;
pub(crate) mod learned_target;
pub(crate) mod plausible_motion;
