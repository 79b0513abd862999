//! Exact ground-truth occupancy at any point and instant, from the dataset's truth alone: the
//! static obstacles (`static.json`) and the actors' boxes of every scan (`objects/`). Between
//! scans an actor is moved on from its last scan with its velocity and yaw rate (a constant turn),
//! which is exact at the scans and for actors driving straight at constant speed.

use patchflow_dataset::{ObjectTruth, StaticObstacle};

/// A box yawed about z, world frame: ground-plane footprint and vertical extent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrientedBox {
    /// Centre of the footprint, metres.
    pub centre_m: [f64; 2],
    /// Half the length (along the yaw) and half the width, metres.
    pub half_extents_m: [f64; 2],
    /// Yaw of the length axis, counter-clockwise from +x.
    pub yaw_rad: f64,
    /// Lowest and highest point of the box above the ground, metres.
    pub z_range_m: [f64; 2],
}

impl OrientedBox {
    /// The box of a static obstacle.
    pub fn of_obstacle(o: &StaticObstacle) -> Self {
        Self::from_parts(o.centre_m, o.size_m, o.yaw_rad)
    }

    /// The box of an actor as its truth gives it.
    pub fn of_object(o: &ObjectTruth) -> Self {
        Self::from_parts(o.centre_m, o.size_m, o.yaw_rad)
    }

    fn from_parts(centre_m: [f64; 3], size_m: [f64; 3], yaw_rad: f64) -> Self {
        Self {
            centre_m: [centre_m[0], centre_m[1]],
            half_extents_m: [size_m[0] / 2.0, size_m[1] / 2.0],
            yaw_rad,
            z_range_m: [centre_m[2] - size_m[2] / 2.0, centre_m[2] + size_m[2] / 2.0],
        }
    }

    /// True if the point at `xy_m`, `height_m` above the ground, lies inside the box.
    pub fn contains(&self, xy_m: [f64; 2], height_m: f64) -> bool {
        if height_m < self.z_range_m[0] || height_m > self.z_range_m[1] {
            return false;
        }
        let (s, c) = self.yaw_rad.sin_cos();
        let (dx, dy) = (xy_m[0] - self.centre_m[0], xy_m[1] - self.centre_m[1]);
        (c * dx + s * dy).abs() <= self.half_extents_m[0]
            && (c * dy - s * dx).abs() <= self.half_extents_m[1]
    }
}

impl OrientedBox {
    /// How far inside the footprint `xy_m` lies (distance to its nearest side), `None` outside.
    pub fn depth_m(&self, xy_m: [f64; 2]) -> Option<f64> {
        let (s, c) = self.yaw_rad.sin_cos();
        let (dx, dy) = (xy_m[0] - self.centre_m[0], xy_m[1] - self.centre_m[1]);
        let along = self.half_extents_m[0] - (c * dx + s * dy).abs();
        let across = self.half_extents_m[1] - (c * dy - s * dx).abs();
        (along >= 0.0 && across >= 0.0).then_some(along.min(across))
    }

    /// The point of the footprint's outline nearest to `xy_m` (a point inside moves out to its
    /// nearest side).
    pub fn nearest_outline_point(&self, xy_m: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.yaw_rad.sin_cos();
        let (dx, dy) = (xy_m[0] - self.centre_m[0], xy_m[1] - self.centre_m[1]);
        let mut local = [c * dx + s * dy, c * dy - s * dx];
        let h = self.half_extents_m;
        let clamped = [local[0].clamp(-h[0], h[0]), local[1].clamp(-h[1], h[1])];
        if clamped == local {
            // Inside: out through the nearer side.
            let axis = usize::from(h[1] - local[1].abs() < h[0] - local[0].abs());
            local[axis] = h[axis].copysign(local[axis]);
        } else {
            local = clamped;
        }
        [
            self.centre_m[0] + c * local[0] - s * local[1],
            self.centre_m[1] + s * local[0] + c * local[1],
        ]
    }

    /// Distance from `origin_m` along the unit direction `dir` (ground plane) to where the ray
    /// enters the footprint; 0 if `origin_m` is inside, `None` if the ray misses it.
    pub fn ray_entry_m(&self, origin_m: [f64; 2], dir: [f64; 2]) -> Option<f64> {
        let (s, c) = self.yaw_rad.sin_cos();
        let (dx, dy) = (
            origin_m[0] - self.centre_m[0],
            origin_m[1] - self.centre_m[1],
        );
        // Origin and direction in the box's own frame; then the slab test on both axes.
        let o = [c * dx + s * dy, c * dy - s * dx];
        let d = [c * dir[0] + s * dir[1], c * dir[1] - s * dir[0]];
        let (mut enter, mut exit) = (0.0f64, f64::INFINITY);
        for axis in 0..2 {
            let h = self.half_extents_m[axis];
            if d[axis].abs() < 1e-15 {
                if o[axis].abs() > h {
                    return None;
                }
                continue;
            }
            let (t0, t1) = ((-h - o[axis]) / d[axis], (h - o[axis]) / d[axis]);
            enter = enter.max(t0.min(t1));
            exit = exit.min(t0.max(t1));
        }
        (enter <= exit).then_some(enter)
    }
}

/// The truth of one sequence: static boxes, and the actors at every scan.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundTruth {
    statics: Vec<OrientedBox>,
    /// (scan time, actors then), in time order.
    scans: Vec<(f64, Vec<ObjectTruth>)>,
}

impl GroundTruth {
    /// Truth from the static obstacles and `(scan time, actors)` of every scan (any order).
    pub fn new(statics: &[StaticObstacle], mut scans: Vec<(f64, Vec<ObjectTruth>)>) -> Self {
        scans.sort_by(|a, b| a.0.total_cmp(&b.0));
        Self {
            statics: statics.iter().map(OrientedBox::of_obstacle).collect(),
            scans,
        }
    }

    /// The static obstacles' boxes.
    pub fn static_boxes(&self) -> &[OrientedBox] {
        &self.statics
    }

    /// The actors at every scan: (scan time, actors then), in time order.
    pub fn actors_by_scan(&self) -> &[(f64, Vec<ObjectTruth>)] {
        &self.scans
    }

    /// Every box at instant `t_secs`: the static ones and each actor, moved on from the latest
    /// scan at or before `t_secs` (or back from the first scan if `t_secs` is earlier).
    pub fn boxes_at(&self, t_secs: f64) -> Vec<OrientedBox> {
        let latest = self.scans.partition_point(|(t, _)| *t <= t_secs);
        let actors = match self.scans.get(latest.saturating_sub(1)) {
            Some((t, objects)) => objects.iter().map(|o| moved(o, t_secs - t)).collect(),
            None => Vec::new(),
        };
        self.statics.iter().copied().chain(actors).collect()
    }

    /// Occupancy of each point of `points_m` (`height_m` above the ground) at `t_secs`.
    ///
    /// ```
    /// use patchflow_dataset::StaticObstacle;
    /// use patchflow_occupancy::GroundTruth;
    /// let wall = StaticObstacle {
    ///     semantic: 51,
    ///     centre_m: [0.0, 10.0, 1.5],
    ///     size_m: [20.0, 1.0, 3.0],
    ///     yaw_rad: 0.0,
    ///     exact: true,
    /// };
    /// let truth = GroundTruth::new(&[wall], Vec::new());
    /// assert_eq!(truth.occupancy(&[[0.0, 10.2], [0.0, 5.0]], 0.5, 3.0), [true, false]);
    /// ```
    pub fn occupancy(&self, points_m: &[[f64; 2]], height_m: f64, t_secs: f64) -> Vec<bool> {
        let boxes = self.boxes_at(t_secs);
        points_m
            .iter()
            .map(|&p| boxes.iter().any(|b| b.contains(p, height_m)))
            .collect()
    }
}

/// The box of `object` after `dt_secs` more of a constant turn at its speed and yaw rate.
fn moved(object: &ObjectTruth, dt_secs: f64) -> OrientedBox {
    let mut b = OrientedBox::of_object(object);
    let (v, w, h) = (object.speed_mps, object.yaw_rate_radps, object.heading_rad);
    let (dx, dy) = if (w * dt_secs).abs() < 1e-9 {
        (v * h.cos() * dt_secs, v * h.sin() * dt_secs)
    } else {
        let r = v / w;
        (
            r * ((h + w * dt_secs).sin() - h.sin()),
            r * (h.cos() - (h + w * dt_secs).cos()),
        )
    };
    b.centre_m = [b.centre_m[0] + dx, b.centre_m[1] + dy];
    b.yaw_rad += w * dt_secs;
    b
}

#[cfg(test)]
mod tests {
    use super::*;
    use patchflow_dataset::ActorClass;

    /// A 4 × 2 × 1.5 m car at (10, 5) yawed 90° (its length along +y), driving +y at 2 m/s.
    fn car(yaw_rate_radps: f64) -> ObjectTruth {
        ObjectTruth {
            id: 1,
            name: "car".into(),
            class: ActorClass::Car,
            target: false,
            moving: true,
            centre_m: [10.0, 5.0, 0.75],
            size_m: [4.0, 2.0, 1.5],
            yaw_rad: std::f64::consts::FRAC_PI_2,
            velocity_mps: [0.0, 2.0, 0.0],
            speed_mps: 2.0,
            heading_rad: std::f64::consts::FRAC_PI_2,
            yaw_rate_radps,
            point_count: 10,
        }
    }

    #[test]
    fn a_known_box_is_occupied_inside_its_footprint_and_height_only() {
        let truth = GroundTruth::new(&[], vec![(2.0, vec![car(0.0)])]);
        let points = [
            [10.0, 6.9],
            [10.9, 5.0],
            [11.1, 5.0],
            [10.0, 7.1],
            [10.0, 5.0],
        ];
        assert_eq!(
            truth.occupancy(&points, 0.5, 2.0),
            [true, true, false, false, true]
        );
        assert_eq!(truth.occupancy(&[[10.0, 5.0]], 1.6, 2.0), [false]);
    }

    #[test]
    fn a_ray_enters_a_yawed_box_where_its_face_is() {
        let b = OrientedBox::of_object(&car(0.0));
        // The car spans x 9 … 11, y 3 … 7: a ray along +x from (0, 5) enters at x = 9.
        let entry = b.ray_entry_m([0.0, 5.0], [1.0, 0.0]).unwrap();
        assert!((entry - 9.0).abs() < 1e-9, "{entry}");
        assert_eq!(b.ray_entry_m([0.0, 8.0], [1.0, 0.0]), None);
        assert_eq!(b.ray_entry_m([20.0, 5.0], [1.0, 0.0]), None);
        assert_eq!(b.ray_entry_m([10.0, 5.0], [0.0, 1.0]), Some(0.0));
        assert!((b.depth_m([10.5, 4.0]).unwrap() - 0.5).abs() < 1e-12);
        let q = b.nearest_outline_point([10.5, 4.0]);
        assert!(
            (q[0] - 11.0).abs() < 1e-12 && (q[1] - 4.0).abs() < 1e-12,
            "{q:?}"
        );
        assert_eq!(b.depth_m([11.5, 4.0]), None);
    }

    #[test]
    fn between_scans_a_straight_driving_car_has_moved_by_its_velocity() {
        let truth = GroundTruth::new(&[], vec![(2.0, vec![car(0.0)]), (3.0, vec![])]);
        // At t = 2.5 the car's centre is at (10, 6): its rear end at y = 4, its front at y = 8.
        let occupied = truth.occupancy(
            &[[10.0, 3.9], [10.0, 4.1], [10.0, 7.9], [10.0, 8.1]],
            0.5,
            2.5,
        );
        assert_eq!(occupied, [false, true, true, false]);
    }

    #[test]
    fn a_turning_car_is_moved_along_its_arc() {
        // Yaw rate 0.5 rad/s at 2 m/s: a 4 m radius turn to the left, centred at (6, 5).
        let truth = GroundTruth::new(&[], vec![(0.0, vec![car(0.5)])]);
        let quarter = std::f64::consts::PI;
        let b = truth.boxes_at(quarter)[0];
        assert!(
            (b.centre_m[0] - 6.0).abs() < 1e-9 && (b.centre_m[1] - 9.0).abs() < 1e-9,
            "{b:?}"
        );
        assert!((b.yaw_rad - std::f64::consts::PI).abs() < 1e-9);
    }
}
