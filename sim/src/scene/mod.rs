//! The Rapier scene: ground, static boxes, kinematic actors and the ego car.

mod actor_tree;
mod collider_tables;
mod instant_query;
mod rapier_scene;
mod ray_tree;
mod scene_actor;
mod scene_instant;
mod scene_queries;
mod static_obstacles;

pub use crate::world::{Glass, Material, Surface, SurfaceKind};
pub use instant_query::{HitPart, InstantQuery};
pub use rapier_scene::Scene;
pub use ray_tree::QueryTree;
pub use scene_actor::SceneActor;
pub use scene_instant::SceneInstant;
