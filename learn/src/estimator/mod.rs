//! The motion estimator of thesis 3.1: per-point GP predictions from map patches, merged per cluster.

mod merge;

pub use merge::{Gaussian, HeadingVote, MergeRule, MergedHeading, merge_heading, merge_scalar};
