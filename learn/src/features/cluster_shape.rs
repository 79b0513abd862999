//! The ground-plane extent of a cluster along its principal axes, and the rule that decides which
//! clusters are object hypotheses (thesis 3.1, step 1).
//!
//! The thesis takes every cluster as a dynamic-object hypothesis. In a street most sliced points
//! belong to building fronts, walls and fences, clusters far longer than any road user; treating
//! them as hypotheses costs a GP prediction per point and cannot find an object. At the other
//! end, a cluster of a handful of points (a car barely out from behind a parked car, half a ring
//! across a far car's front, a post) holds too few cells of the difference map to show which way
//! it moves, and the merged vote of a few such points is a guess however confident each point
//! is. A cluster is an object hypothesis when it is at most [`MAX_OBJECT_LENGTH_M`] long along
//! its major axis and has at least [`MIN_OBJECT_POINTS`] points, as lidar clustering pipelines
//! bound a cluster's size from both sides (PCL's and Autoware's minimum cluster size).

/// Longest cluster taken as one object, metres: the simulator's truck (9 m) seen with the
/// rolling-shutter smear of a fast car (up to 1.5 m in a 0.1 s sweep) and a margin for a car
/// passing close to a pole or a parked car, which single-link clustering joins to it.
pub const MAX_OBJECT_LENGTH_M: f64 = 12.0;

/// Fewest sliced points of one object: one ring across the narrowest side of a car at the
/// situations' farthest range (a 1.8 m front at 40 m spans 13 columns of 0.2°; thesis 4.4's
/// targets had about 200). On `urban`, clusters below it were a tenth of the target's scans in
/// situation 5 and 85 % of its squared heading error (docs/results.md, earlier results).
pub const MIN_OBJECT_POINTS: usize = 10;

/// A cluster's extent along its principal axes (the eigenvectors of its point covariance).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClusterShape {
    /// Number of points.
    pub points: usize,
    /// Mean of the points, world x, y.
    pub centroid_xy: [f64; 2],
    /// Extent along the major axis, metres.
    pub length_m: f64,
    /// Extent along the minor axis, metres.
    pub width_m: f64,
}

impl ClusterShape {
    /// The shape of a point set (zero extents for fewer than two points).
    ///
    /// ```
    /// use patchflow_learn::ClusterShape;
    /// // A 4 m by 2 m rectangle outline, turned by 30°.
    /// let (s, c) = 30f64.to_radians().sin_cos();
    /// let corners = [[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]];
    /// let shape = ClusterShape::of(corners.iter().map(|p| [c * p[0] - s * p[1], s * p[0] + c * p[1]]));
    /// assert!((shape.length_m - 4.0).abs() < 1e-9 && (shape.width_m - 2.0).abs() < 1e-9);
    /// assert!(shape.is_object_sized());
    /// ```
    pub fn of(points_xy: impl Iterator<Item = [f64; 2]> + Clone) -> Self {
        let (n, sx, sy) = points_xy
            .clone()
            .fold((0usize, 0.0, 0.0), |(n, sx, sy), p| {
                (n + 1, sx + p[0], sy + p[1])
            });
        if n == 0 {
            return Self {
                points: 0,
                centroid_xy: [0.0, 0.0],
                length_m: 0.0,
                width_m: 0.0,
            };
        }
        let (mx, my) = (sx / n as f64, sy / n as f64);
        let (cxx, cxy, cyy) = points_xy.clone().fold((0.0, 0.0, 0.0), |(a, b, c), p| {
            let (dx, dy) = (p[0] - mx, p[1] - my);
            (a + dx * dx, b + dx * dy, c + dy * dy)
        });
        // Major axis of the 2 × 2 covariance: angle ½·atan2(2 c_xy, c_xx − c_yy).
        let (s, c) = (0.5 * (2.0 * cxy).atan2(cxx - cyy)).sin_cos();
        let range = |axis: [f64; 2]| {
            let (lo, hi) =
                points_xy
                    .clone()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                        let t = (p[0] - mx) * axis[0] + (p[1] - my) * axis[1];
                        (lo.min(t), hi.max(t))
                    });
            hi - lo
        };
        Self {
            points: n,
            centroid_xy: [mx, my],
            length_m: range([c, s]),
            width_m: range([-s, c]),
        }
    }

    /// Whether a cluster this long can be one road user (`MAX_OBJECT_LENGTH_M`).
    pub fn is_object_sized(&self) -> bool {
        self.length_m <= MAX_OBJECT_LENGTH_M
    }

    /// Whether the cluster is an object hypothesis: object-sized and with at least
    /// [`MIN_OBJECT_POINTS`] points.
    pub fn is_object_hypothesis(&self) -> bool {
        self.is_object_sized() && self.points >= MIN_OBJECT_POINTS
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_wall_is_no_object_but_a_truck_seen_as_an_l_is() {
        let wall = (0..200).map(|k| [f64::from(k) * 0.1, 3.0 + f64::from(k) * 0.01]);
        assert!(!ClusterShape::of(wall).is_object_sized());
        // The two visible sides of a 9 m × 2.5 m truck, at 45° to the axes.
        let (s, c) = std::f64::consts::FRAC_PI_4.sin_cos();
        let sides = (0..90)
            .map(|k| [f64::from(k) * 0.1, 0.0])
            .chain((0..25).map(|k| [9.0, f64::from(k) * 0.1]));
        let truck = ClusterShape::of(sides.map(|p| [c * p[0] - s * p[1], s * p[0] + c * p[1]]));
        assert!(truck.is_object_sized(), "{truck:?}");
        assert!((truck.length_m - 9.0).abs() < 0.6, "{truck:?}");
    }

    #[test]
    fn a_few_points_are_no_object_hypothesis_but_one_ring_across_a_far_car_is() {
        let across = |n: u32| ClusterShape::of((0..n).map(|k| [40.0, f64::from(k) * 0.14]));
        assert!(!across(MIN_OBJECT_POINTS as u32 - 1).is_object_hypothesis());
        assert!(across(13).is_object_hypothesis(), "{:?}", across(13));
        let long_wall = ClusterShape::of((0..200).map(|k| [f64::from(k) * 0.1, 3.0]));
        assert!(!long_wall.is_object_hypothesis());
    }

    #[test]
    fn single_points_have_no_extent() {
        let one = ClusterShape::of([[2.0, -1.0]].into_iter());
        assert_eq!((one.length_m, one.width_m, one.points), (0.0, 0.0, 1));
        assert_eq!(one.centroid_xy, [2.0, -1.0]);
        assert_eq!(ClusterShape::of(std::iter::empty()).points, 0);
    }
}
