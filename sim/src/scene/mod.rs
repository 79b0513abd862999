//! The Rapier scene: ground, static boxes, kinematic actors and the ego car.

mod collider_tables;
mod rapier_scene;
mod surface;

pub use rapier_scene::{Scene, SceneActor};
pub use surface::Surface;
