//! A synthetic world with the ground the perception must estimate: the boxes of a
//! [`SyntheticScene`] standing on [`SyntheticGround`], under tree canopies that return some rays
//! and let the rest through, scanned by the ideal [`SyntheticLidar`].

use nalgebra::{Translation3, UnitQuaternion, Vector3};
use patchflow_dataset::{
    GOLDEN_GAMMA, ObjectTruth, PointLabel, Pose, SemanticClass, Sweep, splitmix64_finalize,
};

use super::synthetic_canopy::SyntheticCanopy;
use super::synthetic_ground::SyntheticGround;
use super::synthetic_scene::{SceneBox, SyntheticLidar, SyntheticScene};

/// SemanticKITTI's vegetation class (canopy returns).
const VEGETATION: u16 = 70;

/// Boxes on uneven ground under tree canopies. Every box stands on the ground at its centre.
///
/// ```
/// use patchflow_learn::synthetic::*;
/// let world = SyntheticWorld {
///     scene: SyntheticScene { boxes: vec![SceneBox::car(1, [12.0, 0.0], 0.0, 5.0)] },
///     ground: SyntheticGround { base_m: 1.0, grade: [0.03, 0.0], ..SyntheticGround::default() },
///     canopies: vec![SyntheticCanopy::street_tree([0.0, 8.0])],
/// };
/// let sweep = world.scan(&SyntheticLidar::with_resolution(32, 720), [0.0, 0.0], 0.0, 0);
/// assert!((sweep.world_from_sensor.translation.z - 2.73).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SyntheticWorld {
    /// Boxes and actors.
    pub scene: SyntheticScene,
    /// The ground they stand on.
    pub ground: SyntheticGround,
    /// Tree crowns.
    pub canopies: Vec<SyntheticCanopy>,
}

/// What a ray hit.
#[derive(Debug, Clone, Copy)]
enum Surface {
    Ground { on_road: bool },
    Box(usize),
    Canopy,
}

impl SyntheticWorld {
    /// The world `dt_secs` later: every box moved by its velocity.
    pub fn advanced(&self, dt_secs: f64) -> Self {
        Self {
            scene: self.scene.advanced(dt_secs),
            ..self.clone()
        }
    }

    /// Scans the world from a sensor mounted `lidar.mount_height_m` above the ground at
    /// `sensor_xy` with yaw `sensor_yaw_rad`; the sweep gets number `index` and time stamp
    /// `index / 10` s.
    pub fn scan(
        &self,
        lidar: &SyntheticLidar,
        sensor_xy: [f64; 2],
        sensor_yaw_rad: f64,
        index: u32,
    ) -> Sweep {
        let ground_z = self.ground.height_m(sensor_xy[0], sensor_xy[1]);
        let origin = Vector3::new(sensor_xy[0], sensor_xy[1], ground_z + lidar.mount_height_m);
        let rotation = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), sensor_yaw_rad);
        let mut sweep = Sweep {
            index,
            stamp_secs: f64::from(index) * 0.1,
            world_from_sensor: Pose::from_parts(
                Translation3::new(origin.x, origin.y, origin.z),
                rotation,
            ),
            ..Sweep::default()
        };
        let boxes = &self.scene.boxes;
        let floors: Vec<f64> = boxes
            .iter()
            .map(|b| self.ground.height_m(b.centre_xy[0], b.centre_xy[1]))
            .collect();
        let mut counts = vec![0u32; boxes.len()];
        let channels = lidar.elevations_deg.len();
        for step in 0..lidar.azimuth_steps {
            let azimuth = std::f64::consts::TAU * step as f64 / lidar.azimuth_steps as f64;
            for (channel, elevation) in lidar.elevations_deg.iter().enumerate() {
                let el = elevation.to_radians();
                let dir_sensor =
                    Vector3::new(el.cos() * azimuth.cos(), el.cos() * azimuth.sin(), el.sin());
                let dir = rotation * dir_sensor;
                let ray = (step * channels + channel) as u64;
                let Some((t, surface)) = self.first_hit(&origin, &dir, &floors, lidar, ray) else {
                    continue;
                };
                let p = dir_sensor * t;
                sweep
                    .points_in_sensor
                    .push([p.x as f32, p.y as f32, p.z as f32]);
                sweep.intensities.push(0.5);
                sweep.time_in_sweep_secs.push(0.0);
                let (label, flow) = match surface {
                    Surface::Ground { on_road: true } => {
                        (PointLabel::new(SemanticClass::Road, 0), [0.0; 3])
                    }
                    Surface::Ground { on_road: false } => {
                        (PointLabel::new(SemanticClass::Sidewalk, 0), [0.0; 3])
                    }
                    Surface::Canopy => (PointLabel::from_parts(VEGETATION, 0), [0.0; 3]),
                    Surface::Box(k) => {
                        counts[k] += 1;
                        box_label(&boxes[k])
                    }
                };
                sweep.labels.push(label);
                sweep.flow_in_world_mps.push(flow);
            }
        }
        sweep.objects = objects(boxes, &floors, &counts);
        sweep
    }

    /// The nearest surface along the unit ray within the lidar's range; ray number `ray` decides
    /// which canopy entries return.
    fn first_hit(
        &self,
        origin: &Vector3<f64>,
        dir: &Vector3<f64>,
        floors: &[f64],
        lidar: &SyntheticLidar,
        ray: u64,
    ) -> Option<(f64, Surface)> {
        let mut best = (lidar.max_range_m, None);
        if let Some(hit) = self.ground.intersect(origin, dir, best.0) {
            best = (
                hit.t,
                Some(Surface::Ground {
                    on_road: hit.on_road,
                }),
            );
        }
        for (k, (b, floor)) in self.scene.boxes.iter().zip(floors).enumerate() {
            let raised = Vector3::new(origin.x, origin.y, origin.z - floor);
            if let Some(t) = b.intersect(&raised, dir)
                && t < best.0
            {
                best = (t, Some(Surface::Box(k)));
            }
        }
        for (k, canopy) in self.canopies.iter().enumerate() {
            let floor = self
                .ground
                .height_m(canopy.centre_xy[0], canopy.centre_xy[1]);
            if let Some(t) = canopy.entry(origin, dir, floor)
                && t < best.0
                && unit_hash(ray, k as u64) < canopy.density
            {
                best = (t, Some(Surface::Canopy));
            }
        }
        let (t, surface) = best;
        surface.map(|s| (t, s))
    }
}

/// Label and flow of a return from box `b`.
fn box_label(b: &SceneBox) -> (PointLabel, [f32; 3]) {
    let flow = [b.velocity_mps[0] as f32, b.velocity_mps[1] as f32, 0.0];
    match b.actor {
        None => (PointLabel::new(SemanticClass::Building, 0), flow),
        Some((id, class)) => (
            PointLabel::new(class.semantic(b.speed_mps() >= 0.05), id),
            flow,
        ),
    }
}

/// Truth of every actor box standing on `floors` with `counts` returns.
fn objects(boxes: &[SceneBox], floors: &[f64], counts: &[u32]) -> Vec<ObjectTruth> {
    boxes
        .iter()
        .zip(floors.iter().zip(counts))
        .filter_map(|(b, (&floor, &point_count))| {
            let (id, class) = b.actor?;
            let speed_mps = b.speed_mps();
            let moving = speed_mps >= 0.05;
            Some(ObjectTruth {
                id,
                name: format!("actor{id}"),
                class,
                target: false,
                moving,
                centre_m: [b.centre_xy[0], b.centre_xy[1], floor + b.size_m[2] / 2.0],
                size_m: b.size_m,
                yaw_rad: b.yaw_rad,
                velocity_mps: [b.velocity_mps[0], b.velocity_mps[1], 0.0],
                speed_mps,
                heading_rad: if moving {
                    b.velocity_mps[1].atan2(b.velocity_mps[0])
                } else {
                    b.yaw_rad
                },
                yaw_rate_radps: 0.0,
                point_count,
            })
        })
        .collect()
}

/// A deterministic number in [0, 1) from a ray and a canopy (SplitMix64 finaliser).
fn unit_hash(ray: u64, canopy: u64) -> f64 {
    let z = splitmix64_finalize(
        ray.wrapping_mul(GOLDEN_GAMMA)
            .wrapping_add(canopy.wrapping_mul(0xD1B5_4A32_D192_ED03)),
    );
    (z >> 11) as f64 / (1u64 << 53) as f64
}

impl SyntheticScene {
    /// Scans the scene on the flat ground z = 0 from a sensor at `sensor_xy` with yaw
    /// `sensor_yaw_rad`; the sweep gets number `index` and time stamp `index / 10` s. See
    /// [`SyntheticWorld`] for uneven ground and tree canopies.
    pub fn scan(
        &self,
        lidar: &SyntheticLidar,
        sensor_xy: [f64; 2],
        sensor_yaw_rad: f64,
        index: u32,
    ) -> Sweep {
        let world = SyntheticWorld {
            scene: self.clone(),
            ..SyntheticWorld::default()
        };
        world.scan(lidar, sensor_xy, sensor_yaw_rad, index)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_canopy_returns_about_its_density_of_the_rays_entering_it_and_ground_shows_below() {
        // A low crown: the top channel (+2°) climbs only 0.35 m in 10 m.
        let world = SyntheticWorld {
            canopies: vec![SyntheticCanopy {
                bottom_m: 1.9,
                ..SyntheticCanopy::street_tree([15.0, 0.0])
            }],
            ..SyntheticWorld::default()
        };
        let sweep = world.scan(
            &SyntheticLidar::with_resolution(64, 1800),
            [0.0, 0.0],
            0.0,
            0,
        );
        let leaves: Vec<_> = (0..sweep.len())
            .filter(|&i| sweep.labels[i].semantic() == VEGETATION)
            .map(|i| sweep.point_in_world(i))
            .collect();
        // Rays entering the crown: channels above 0.33°, over about 23° of azimuth.
        let entering = 4.0 * 1800.0 * 23.0 / 360.0;
        let share = leaves.len() as f64 / entering;
        assert!(
            (0.3..1.0).contains(&share),
            "{} canopy returns",
            leaves.len()
        );
        assert!(
            leaves
                .iter()
                .all(|p| p.z >= 1.9 - 1e-6 && p.z <= 7.0 + 1e-6)
        );
        let under = (0..sweep.len())
            .map(|i| sweep.point_in_world(i))
            .filter(|p| (p.x - 15.0).hypot(p.y) < 2.5 && p.z.abs() < 1e-6)
            .count();
        assert!(under > 20, "{under} ground returns under the crown");
    }

    #[test]
    fn a_box_stands_on_the_raised_ground_at_its_centre() {
        let world = SyntheticWorld {
            scene: SyntheticScene {
                boxes: vec![SceneBox::car(4, [12.0, 0.0], 0.0, 0.0)],
            },
            ground: SyntheticGround {
                base_m: 1.0,
                ..SyntheticGround::default()
            },
            canopies: Vec::new(),
        };
        let sweep = world.scan(
            &SyntheticLidar::with_resolution(64, 720),
            [0.0, 0.0],
            0.0,
            0,
        );
        let car_z: Vec<f64> = (0..sweep.len())
            .filter(|&i| sweep.labels[i].instance() == 4)
            .map(|i| sweep.point_in_world(i).z)
            .collect();
        assert!(car_z.len() > 10);
        assert!(car_z.iter().all(|z| (1.0 - 1e-6..=2.5 + 1e-6).contains(z)));
        assert!((sweep.objects[0].centre_m[2] - 1.75).abs() < 1e-12);
    }
}
