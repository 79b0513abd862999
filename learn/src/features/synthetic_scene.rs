//! A world of boxes on flat ground scanned by an ideal spinning lidar: exact, hand-made sweeps for
//! tests, benchmarks and demos while no simulator is at hand. No noise, no rolling shutter.
//! `SyntheticWorld` puts the boxes on uneven ground (`SyntheticGround`) under tree canopies.

use nalgebra::Vector3;
use patchflow_dataset::ActorClass;

/// A box standing on the ground: a static structure or an actor moving at constant velocity.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneBox {
    /// Centre of the footprint, world x, y.
    pub centre_xy: [f64; 2],
    /// Yaw of the long axis, counter-clockwise from world +x.
    pub yaw_rad: f64,
    /// Length (along yaw), width, height, metres.
    pub size_m: [f64; 3],
    /// Ground-plane velocity, world frame.
    pub velocity_mps: [f64; 2],
    /// Actor id and class; `None` for static structure (labelled as building).
    pub actor: Option<(u16, ActorClass)>,
}

impl SceneBox {
    /// A static wall or building block.
    pub fn wall(centre_xy: [f64; 2], yaw_rad: f64, size_m: [f64; 3]) -> Self {
        Self {
            centre_xy,
            yaw_rad,
            size_m,
            velocity_mps: [0.0, 0.0],
            actor: None,
        }
    }

    /// A 4.5 m × 1.8 m × 1.5 m car driving along its yaw at `speed_mps`.
    pub fn car(id: u16, centre_xy: [f64; 2], yaw_rad: f64, speed_mps: f64) -> Self {
        Self {
            centre_xy,
            yaw_rad,
            size_m: [4.5, 1.8, 1.5],
            velocity_mps: [speed_mps * yaw_rad.cos(), speed_mps * yaw_rad.sin()],
            actor: Some((id, ActorClass::Car)),
        }
    }

    pub(crate) fn speed_mps(&self) -> f64 {
        self.velocity_mps[0].hypot(self.velocity_mps[1])
    }

    /// Distance along the ray `o + t·d` to the box, if it is hit.
    pub(crate) fn intersect(&self, o: &Vector3<f64>, d: &Vector3<f64>) -> Option<f64> {
        let (s, c) = self.yaw_rad.sin_cos();
        let (rx, ry) = (o.x - self.centre_xy[0], o.y - self.centre_xy[1]);
        let local_o = [c * rx + s * ry, -s * rx + c * ry, o.z];
        let local_d = [c * d.x + s * d.y, -s * d.x + c * d.y, d.z];
        let [l, w, h] = self.size_m;
        let bounds = [(-l / 2.0, l / 2.0), (-w / 2.0, w / 2.0), (0.0, h)];
        let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
        for k in 0..3 {
            let (lo, hi) = bounds[k];
            if local_d[k].abs() < 1e-12 {
                if local_o[k] < lo || local_o[k] > hi {
                    return None;
                }
                continue;
            }
            let (a, b) = (
                (lo - local_o[k]) / local_d[k],
                (hi - local_o[k]) / local_d[k],
            );
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        (t0 <= t1 && t0 > 0.0).then_some(t0)
    }
}

/// An ideal spinning lidar: one ray per channel and azimuth step, all at the same instant.
#[derive(Debug, Clone, PartialEq)]
pub struct SyntheticLidar {
    /// Elevation of every channel, degrees.
    pub elevations_deg: Vec<f64>,
    /// Azimuth steps per turn.
    pub azimuth_steps: usize,
    /// Longest range returned, metres.
    pub max_range_m: f64,
    /// Height of the sensor above the ground, metres.
    pub mount_height_m: f64,
}

impl SyntheticLidar {
    /// HDL-64E-like: 64 channels evenly from +2.0° to −24.8°, 1,800 steps, 120 m, 1.73 m high.
    pub fn hdl64e() -> Self {
        Self::with_resolution(64, 1800)
    }

    /// The HDL-64E field of view with fewer channels or steps (for small tests).
    pub fn with_resolution(channels: usize, azimuth_steps: usize) -> Self {
        let step = 26.8 / (channels.max(2) - 1) as f64;
        Self {
            elevations_deg: (0..channels).map(|k| 2.0 - step * k as f64).collect(),
            azimuth_steps,
            max_range_m: 120.0,
            mount_height_m: 1.73,
        }
    }
}

/// A set of boxes on the ground plane z = 0.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SyntheticScene {
    /// The boxes.
    pub boxes: Vec<SceneBox>,
}

impl SyntheticScene {
    /// The scene `dt_secs` later: every box moved by its velocity.
    pub fn advanced(&self, dt_secs: f64) -> Self {
        let mut next = self.clone();
        for b in &mut next.boxes {
            b.centre_xy[0] += b.velocity_mps[0] * dt_secs;
            b.centre_xy[1] += b.velocity_mps[1] * dt_secs;
        }
        next
    }

    /// The scene rotated by `angle_rad` about `pivot_xy` (boxes, yaws and velocities).
    pub fn rotated(&self, pivot_xy: [f64; 2], angle_rad: f64) -> Self {
        let mut next = self.clone();
        for b in &mut next.boxes {
            b.centre_xy = rotate_about(b.centre_xy, pivot_xy, angle_rad);
            b.yaw_rad += angle_rad;
            b.velocity_mps = rotate_about(b.velocity_mps, [0.0, 0.0], angle_rad);
        }
        next
    }
}

/// `p` rotated by `angle_rad` about `pivot`.
pub fn rotate_about(p: [f64; 2], pivot: [f64; 2], angle_rad: f64) -> [f64; 2] {
    let (s, c) = angle_rad.sin_cos();
    let (dx, dy) = (p[0] - pivot[0], p[1] - pivot[1]);
    [pivot[0] + c * dx - s * dy, pivot[1] + s * dx + c * dy]
}

#[cfg(test)]
mod tests {
    use super::*;
    use patchflow_dataset::SemanticClass;

    #[test]
    fn a_wall_ahead_returns_points_at_its_face_and_the_ground_elsewhere() {
        let scene = SyntheticScene {
            boxes: vec![SceneBox::wall([10.5, 0.0], 0.0, [1.0, 20.0, 3.0])],
        };
        let sweep = scene.scan(
            &SyntheticLidar::with_resolution(16, 360),
            [0.0, 0.0],
            0.0,
            0,
        );
        sweep.check_lengths().unwrap();
        let ahead: Vec<_> = (0..sweep.len())
            .filter(|&i| sweep.labels[i].semantic() == SemanticClass::Building.id())
            .map(|i| sweep.point_in_world(i))
            .collect();
        assert!(!ahead.is_empty());
        assert!(
            ahead.iter().all(|p| (p.x - 10.0).abs() < 1e-4),
            "hits lie on the face x = 10"
        );
        let ground = (0..sweep.len()).filter(|&i| sweep.labels[i].semantic() == 40);
        assert!(
            ground
                .map(|i| sweep.point_in_world(i).z)
                .all(|z| z.abs() < 1e-4)
        );
    }

    #[test]
    fn a_moving_car_is_labelled_moving_with_its_truth() {
        let scene = SyntheticScene {
            boxes: vec![SceneBox::car(3, [8.0, 4.0], 0.5, 5.0)],
        };
        let sweep = scene.scan(
            &SyntheticLidar::with_resolution(32, 720),
            [0.0, 0.0],
            0.3,
            2,
        );
        let on_car = sweep
            .labels
            .iter()
            .filter(|l| l.is_moving() && l.instance() == 3)
            .count();
        assert!(on_car > 10);
        assert_eq!(sweep.objects.len(), 1);
        assert_eq!(sweep.objects[0].point_count as usize, on_car);
        assert!((sweep.objects[0].heading_rad - 0.5).abs() < 1e-12);
    }
}
