//! The Rapier scene: ground, static boxes, kinematic actors and the ego car.

mod scene;
mod surface;

pub use scene::{Scene, SceneActor};
pub use surface::Surface;
