//! The motion estimators the benchmark compares (thesis 3.2 and issue 27): what a method is
//! ([`method::Method`]), what it sees per scan ([`observation`]) and what it emits
//! ([`estimate::MotionEstimate`]); the baselines of thesis 3.2 and the GP-informed learned
//! perception, each stepped scan by scan.

pub(crate) mod baselines;
pub(crate) mod estimate;
pub(crate) mod learned;
pub(crate) mod method;
pub(crate) mod observation;
