//! Truth of the static world: every static obstacle of a sequence (buildings, walls, fences,
//! poles, parked cars, ...) as a world-frame oriented box, written once per sequence as
//! `sequences/<name>/static.json`. With the per-sweep actor boxes (`objects/`) it gives exact
//! occupancy at any point without the scene code.

use serde::{Deserialize, Serialize};

/// One static obstacle: a box yawed about z, world frame (z up, metres, radians).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StaticObstacle {
    /// SemanticKITTI id of its points (50 building, 51 fence or wall, 80 pole, 10 parked car, ...).
    pub semantic: u16,
    /// Centre of the box.
    pub centre_m: [f64; 3],
    /// Size along its own axes: length (along yaw), width, height.
    pub size_m: [f64; 3],
    /// Yaw of the box's length axis, counter-clockwise from world +x.
    pub yaw_rad: f64,
    /// True if the box is the obstacle's exact shape; false if it only bounds it (a shape other
    /// than a box, given by its axis-aligned bounding box).
    pub exact: bool,
}

impl StaticObstacle {
    /// True if the world point `p` lies inside the box (faces included).
    ///
    /// ```
    /// use patchflow_dataset::StaticObstacle;
    /// let wall = StaticObstacle {
    ///     semantic: 51,
    ///     centre_m: [10.0, 0.0, 1.5],
    ///     size_m: [0.3, 40.0, 3.0],
    ///     yaw_rad: 0.0,
    ///     exact: true,
    /// };
    /// assert!(wall.contains([10.1, 19.0, 0.5]));
    /// assert!(!wall.contains([10.2, 0.0, 0.5]));
    /// ```
    pub fn contains(&self, p: [f64; 3]) -> bool {
        box_contains(self.centre_m, self.size_m, self.yaw_rad, p)
    }
}

/// True if the world point `p` lies inside the box of `centre_m`, `size_m` and yaw `yaw_rad`.
pub(crate) fn box_contains(
    centre_m: [f64; 3],
    size_m: [f64; 3],
    yaw_rad: f64,
    p: [f64; 3],
) -> bool {
    let (s, c) = yaw_rad.sin_cos();
    let (dx, dy, dz) = (p[0] - centre_m[0], p[1] - centre_m[1], p[2] - centre_m[2]);
    let along = c * dx + s * dy;
    let across = -s * dx + c * dy;
    along.abs() <= size_m[0] / 2.0 && across.abs() <= size_m[1] / 2.0 && dz.abs() <= size_m[2] / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_yawed_box_contains_points_along_its_own_axes() {
        // A 4 × 2 m box turned by 90°: its length runs along world y.
        let obstacle = StaticObstacle {
            semantic: 10,
            centre_m: [5.0, 5.0, 0.75],
            size_m: [4.0, 2.0, 1.5],
            yaw_rad: std::f64::consts::FRAC_PI_2,
            exact: true,
        };
        assert!(obstacle.contains([5.0, 6.9, 0.5]));
        assert!(obstacle.contains([5.9, 5.0, 0.5]));
        assert!(!obstacle.contains([6.9, 5.0, 0.5]));
        assert!(!obstacle.contains([5.0, 5.0, 1.6]));
    }
}
