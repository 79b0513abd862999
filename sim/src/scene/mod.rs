//! The Rapier scene: ground, static boxes, kinematic actors and the ego car.

mod collider_tables;
mod rapier_scene;
mod ray_tree;
mod surface;

pub use rapier_scene::{QueryTree, Scene, SceneActor};
pub use surface::Surface;
