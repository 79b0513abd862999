//! The Rapier scene: ground, static boxes, kinematic actors and the ego car.

mod collider_tables;
mod rapier_scene;
mod ray_tree;
mod scene_actor;
mod surface;

pub use rapier_scene::Scene;
pub use ray_tree::QueryTree;
pub use scene_actor::SceneActor;
pub use surface::Surface;
