//! Actor motion: smooth paths, speed profiles, and the exact state at any time.

mod path;
mod speed_profile;
mod trajectory;

pub use path::{Path, PathPoint};
pub use speed_profile::{ProfileState, SpeedProfile};
pub use trajectory::{MOVING_SPEED_MPS, MotionState, Trajectory};
