//! The static world as plain truth: every fixed collider of the scene but the ground, as a
//! world-frame box (`static.json` of the dataset). Read from the scene's own colliders, so
//! whatever static structure the scene holds is in the truth: cuboids exactly, any other shape
//! as its axis-aligned bounding box (marked inexact). The street world's one collider stands
//! for its pieces: each non-ground piece is an obstacle of its own, in piece order.

use patchflow_dataset::StaticObstacle;
use rapier3d::prelude::*;

use super::Scene;

/// SemanticKITTI ids of ground surfaces (road, parking, sidewalk, other ground, terrain): not
/// obstacles, and their slabs span the whole scene.
const GROUND_IDS: [u16; 5] = [40, 44, 48, 49, 72];

impl Scene {
    /// Every fixed collider that is not ground, as a world-frame box, in collider order.
    pub fn static_obstacles(&self) -> Vec<StaticObstacle> {
        let mut fixed: Vec<(ColliderHandle, &Collider)> = self
            .colliders
            .iter()
            .filter(|(_, c)| c.parent().is_none())
            .collect();
        fixed.sort_by_key(|(h, _)| h.into_raw_parts());
        let street_index = self.street.as_ref().map(|s| s.collider);
        let mut obstacles = Vec::new();
        for (handle, collider) in fixed {
            if Some(handle.into_raw_parts().0) == street_index {
                obstacles.extend(self.street_obstacles());
                continue;
            }
            let Some(surface) = self.surface(handle) else {
                continue;
            };
            let semantic = surface.semantic.id();
            if !GROUND_IDS.contains(&semantic) {
                obstacles.push(obstacle(semantic, collider));
            }
        }
        obstacles
    }

    /// Every non-ground piece of the street world, as a world-frame box, in piece order.
    fn street_obstacles(&self) -> Vec<StaticObstacle> {
        let Some(street) = &self.street else {
            return Vec::new();
        };
        let pieces = street.shape.pieces();
        (0..pieces.len() as u32)
            .filter_map(|k| {
                let surface = self
                    .surfaces
                    .get((street.first_piece_surface + k) as usize)?;
                let semantic = surface.semantic.id();
                if GROUND_IDS.contains(&semantic) {
                    return None;
                }
                let (centre_m, size_m, yaw_rad, exact) = pieces.piece(k)?.world_box();
                Some(StaticObstacle {
                    semantic,
                    centre_m,
                    size_m,
                    yaw_rad,
                    exact,
                })
            })
            .collect()
    }
}

/// The box of one fixed collider.
fn obstacle(semantic: u16, collider: &Collider) -> StaticObstacle {
    let pose = collider.position();
    if let Some(cuboid) = collider.shape().as_cuboid() {
        let h = cuboid.half_extents;
        let length_axis = pose.rotation * Vector::X;
        let t = pose.translation;
        return StaticObstacle {
            semantic,
            centre_m: [f64::from(t.x), f64::from(t.y), f64::from(t.z)],
            size_m: [
                2.0 * f64::from(h.x),
                2.0 * f64::from(h.y),
                2.0 * f64::from(h.z),
            ],
            yaw_rad: f64::from(length_axis.y).atan2(f64::from(length_axis.x)),
            exact: true,
        };
    }
    let aabb = collider.compute_aabb();
    let (lo, hi) = (aabb.mins, aabb.maxs);
    StaticObstacle {
        semantic,
        centre_m: [
            f64::from(lo.x + hi.x) / 2.0,
            f64::from(lo.y + hi.y) / 2.0,
            f64::from(lo.z + hi.z) / 2.0,
        ],
        size_m: [
            f64::from(hi.x - lo.x),
            f64::from(hi.y - lo.y),
            f64::from(hi.z - lo.z),
        ],
        yaw_rad: 0.0,
        exact: false,
    }
}

#[cfg(test)]
mod tests {
    use crate::{Scenario, Scene};

    #[test]
    fn every_structure_box_is_an_exact_obstacle_and_the_ground_is_not() {
        let text = "sweeps = 1\nrealism = \"ideal\"\n[ego]\npath_m = [[0.0, 0.0], [1.0, 0.0]]\nspeed_mps = 0.0\n[[structures]]\nkind = \"parked_car\"\ncentre_m = [8.0, -4.0]\nyaw_deg = 30.0\n[[structures]]\nkind = \"pole\"\ncentre_m = [0.0, 5.0]\nrepeat_to_m = [10.0, 5.0]\nspacing_m = 5.0\n[[structures]]\nkind = \"sidewalk\"\ncentre_m = [0.0, -8.0]\n";
        let scenario = Scenario::from_toml(text, "static.toml", "static").unwrap();
        let scene = Scene::build(&scenario, &scenario.actors).unwrap();
        let obstacles = scene.static_obstacles();
        // The parked car and three poles; the sidewalk is ground like the road slab.
        assert_eq!(obstacles.len(), 4, "{obstacles:?}");
        let car = &obstacles[0];
        assert_eq!(car.semantic, 10);
        assert!(car.exact);
        assert!((car.yaw_rad - 30f64.to_radians()).abs() < 1e-6);
        assert!((car.centre_m[0] - 8.0).abs() < 1e-6 && (car.centre_m[2] - 0.725).abs() < 1e-6);
        assert!((car.size_m[0] - 4.5).abs() < 1e-6 && (car.size_m[1] - 1.8).abs() < 1e-6);
        let pole_xs: Vec<f64> = obstacles[1..].iter().map(|o| o.centre_m[0]).collect();
        assert_eq!(pole_xs, [0.0, 5.0, 10.0]);
    }

    #[test]
    fn every_non_ground_piece_of_a_street_world_is_an_obstacle() {
        let text = "sweeps = 1\nrealism = \"urban\"\n[ego]\npath_m = [[-40.0, 0.0], [40.0, 0.0]]\nspeed_mps = 5.0\n";
        let scenario = Scenario::from_toml(text, "street.toml", "street").unwrap();
        let scene = Scene::build(&scenario, &scenario.actors).unwrap();
        let pieces = scene.street_piece_count();
        assert!(pieces > 20, "{pieces} pieces");
        let obstacles = scene.static_obstacles();
        // Sidewalk slabs and curbs are ground; façades, clutter and vegetation are not.
        assert!(
            obstacles.len() > 10 && obstacles.len() <= pieces,
            "{} obstacles of {pieces} pieces",
            obstacles.len()
        );
        assert!(
            obstacles
                .iter()
                .all(|o| !super::GROUND_IDS.contains(&o.semantic))
        );
        // Trees (vegetation) and poles, at least.
        assert!(
            obstacles.iter().any(|o| o.semantic == 70)
                && obstacles.iter().any(|o| o.semantic == 80)
        );
        assert!(obstacles.iter().any(|o| o.exact) && obstacles.iter().all(|o| o.size_m[2] > 0.0));
    }
}
