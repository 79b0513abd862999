//! The query points a map is scored on (DGPOM paper, Table 1): a regular lattice over the area
//! the sensor observes: within its maximum range, inside its field of view, and not hidden behind
//! static structure (a point at most one lattice step inside an obstacle still counts, so its
//! faces are scored, but not a building's interior, which no scan can ever see). What moving actors hide
//! stays in: reasoning about it is what the maps are compared on. The lattice is aligned to the
//! world origin, so maps of one sequence share their points, and it keeps its rows and columns so
//! maps can be drawn as images.

use patchflow_dataset::SensorInfo;

use crate::{GroundTruth, OrientedBox, PlanarScan};

/// Lattice points over a sensor's observed area.
#[derive(Debug, Clone, PartialEq)]
pub struct QueryGrid {
    /// Distance between neighbouring points, metres.
    pub spacing_m: f64,
    /// World position of lattice cell (0, 0), metres.
    pub origin_m: [f64; 2],
    /// Columns (along world x) and rows (along world y) of the lattice.
    pub size: [usize; 2],
    /// The query points, world frame, row by row from the lowest y.
    pub points_m: Vec<[f64; 2]>,
    /// Lattice cell `row * columns + column` of each point.
    pub cells: Vec<usize>,
}

impl QueryGrid {
    /// The lattice points with spacing `spacing_m` that `scan`'s sensor observes: within
    /// `sensor.max_range_m` of it, inside the fan of its beams, and in front of the static
    /// obstacles of `truth` that reach the scan height `height_m` (or at most one step inside one).
    ///
    /// ```
    /// use patchflow_dataset::{SensorInfo, SensorKind};
    /// use patchflow_occupancy::{PlanarScan, QueryGrid};
    /// let sensor = SensorInfo {
    ///     kind: SensorKind::Planar,
    ///     rate_hz: 1.0,
    ///     max_range_m: 20.0,
    ///     mount_height_m: 0.5,
    ///     columns: 70,
    ///     first_azimuth_deg: 90.0,
    ///     azimuth_step_deg: -180.0 / 69.0,
    ///     elevations_deg: vec![0.0],
    /// };
    /// let scan = PlanarScan { index: 0, stamp_secs: 0.0, sensor_m: [0.0, 0.0], yaw_rad: 0.0, beams: vec![] };
    /// let open_field = patchflow_occupancy::GroundTruth::new(&[], Vec::new());
    /// let grid = QueryGrid::observed_by(&scan, &sensor, 1.0, &open_field, 0.5);
    /// // Half a disc of radius 20 m: about π · 20² / 2 ≈ 628 points.
    /// assert!((600..660).contains(&grid.points_m.len()));
    /// ```
    pub fn observed_by(
        scan: &PlanarScan,
        sensor: &SensorInfo,
        spacing_m: f64,
        truth: &GroundTruth,
        height_m: f64,
    ) -> Self {
        let r = sensor.max_range_m;
        let [sx, sy] = scan.sensor_m;
        let lo = [
            ((sx - r) / spacing_m).floor(),
            ((sy - r) / spacing_m).floor(),
        ];
        let hi = [((sx + r) / spacing_m).ceil(), ((sy + r) / spacing_m).ceil()];
        let size = [(hi[0] - lo[0]) as usize + 1, (hi[1] - lo[1]) as usize + 1];
        let origin_m = [lo[0] * spacing_m, lo[1] * spacing_m];
        let (first, last) = fan_rad(sensor);
        let walls: Vec<_> = truth
            .static_boxes()
            .iter()
            .filter(|b| (b.z_range_m[0]..=b.z_range_m[1]).contains(&height_m))
            .collect();
        let (mut points_m, mut cells) = (Vec::new(), Vec::new());
        for row in 0..size[1] {
            for column in 0..size[0] {
                let p = [
                    origin_m[0] + column as f64 * spacing_m,
                    origin_m[1] + row as f64 * spacing_m,
                ];
                let (dx, dy) = (p[0] - sx, p[1] - sy);
                let (distance, bearing) = (
                    dx.hypot(dy),
                    patchflow_dataset::wrap_angle_rad(dy.atan2(dx) - scan.yaw_rad),
                );
                if distance > r || bearing < first || bearing > last {
                    continue;
                }
                // In front of every static surface, or at most a step inside one behind a face
                // the sensor sees.
                let seen = match walls.iter().find_map(|b| Some((b, b.depth_m(p)?))) {
                    Some((b, depth)) => {
                        depth <= spacing_m
                            && in_sight(scan.sensor_m, b.nearest_outline_point(p), &walls)
                    }
                    None => in_sight(scan.sensor_m, p, &walls),
                };
                if seen {
                    points_m.push(p);
                    cells.push(row * size[0] + column);
                }
            }
        }
        Self {
            spacing_m,
            origin_m,
            size,
            points_m,
            cells,
        }
    }

    /// Number of query points.
    pub fn len(&self) -> usize {
        self.points_m.len()
    }

    /// True if the grid has no point.
    pub fn is_empty(&self) -> bool {
        self.points_m.is_empty()
    }
}

/// True if no box of `walls` lies across the segment from `sensor_m` to `p` (a box that `p` is on
/// the outline of does not count, up to a micrometre).
fn in_sight(sensor_m: [f64; 2], p: [f64; 2], walls: &[&OrientedBox]) -> bool {
    let (dx, dy) = (p[0] - sensor_m[0], p[1] - sensor_m[1]);
    let distance = dx.hypot(dy);
    if distance < 1e-12 {
        return true;
    }
    let dir = [dx / distance, dy / distance];
    walls.iter().all(|b| {
        b.ray_entry_m(sensor_m, dir)
            .is_none_or(|entry| entry >= distance - 1e-6)
    })
}

/// The lowest and highest beam azimuth of the sensor, radians in the sensor frame (a full
/// circle if the fan covers one).
fn fan_rad(sensor: &SensorInfo) -> (f64, f64) {
    let span_deg = (f64::from(sensor.columns.saturating_sub(1)) * sensor.azimuth_step_deg).abs();
    if span_deg + sensor.azimuth_step_deg.abs() >= 360.0 - 1e-9 {
        return (-std::f64::consts::PI, std::f64::consts::PI);
    }
    let a = sensor.azimuth_rad(0);
    let b = sensor.azimuth_rad(sensor.columns.saturating_sub(1));
    // Half a step of margin on each edge: the edge beams observe up to there.
    let half_step = sensor.azimuth_step_deg.abs().to_radians() / 2.0;
    (a.min(b) - half_step, a.max(b) + half_step)
}

#[cfg(test)]
mod tests {
    use super::*;
    use patchflow_dataset::SensorKind;

    #[test]
    fn points_lie_in_range_in_front_of_the_sensor_and_of_static_walls_on_the_world_lattice() {
        let sensor = SensorInfo {
            kind: SensorKind::Planar,
            rate_hz: 1.0,
            max_range_m: 20.0,
            mount_height_m: 0.5,
            columns: 70,
            first_azimuth_deg: 90.0,
            azimuth_step_deg: -180.0 / 69.0,
            elevations_deg: vec![0.0],
        };
        // At (15, 0) facing +y: the upper half disc.
        let scan = PlanarScan {
            index: 0,
            stamp_secs: 0.0,
            sensor_m: [15.0, 0.0],
            yaw_rad: std::f64::consts::FRAC_PI_2,
            beams: vec![],
        };
        let wall = patchflow_dataset::StaticObstacle {
            semantic: 50,
            centre_m: [15.0, 14.0, 4.0],
            size_m: [60.0, 8.0, 8.0],
            yaw_rad: 0.0,
            exact: true,
        };
        let truth = GroundTruth::new(&[wall], Vec::new());
        let grid = QueryGrid::observed_by(&scan, &sensor, 0.5, &truth, 0.5);
        // The building's face (y = 10) and one step into it are scored, its interior is not.
        assert!(grid.points_m.contains(&[15.0, 10.5]) && grid.points_m.contains(&[5.0, 10.5]));
        let deep: Vec<_> = grid.points_m.iter().filter(|p| p[1] > 10.5).collect();
        assert!(deep.is_empty(), "{deep:?}");
        assert!(grid.points_m.iter().all(|p| p[1] >= -0.1));
        assert!(
            grid.points_m
                .iter()
                .all(|p| (p[0] - 15.0).hypot(p[1]) <= 20.0)
        );
        assert!(
            grid.points_m
                .iter()
                .all(|p| (p[0] * 2.0).fract() == 0.0 && (p[1] * 2.0).fract() == 0.0)
        );
        assert!(grid.points_m.contains(&[15.0, 9.5]) && grid.points_m.contains(&[-4.5, 0.0]));
        for (p, &cell) in grid.points_m.iter().zip(&grid.cells) {
            let (row, column) = (cell / grid.size[0], cell % grid.size[0]);
            assert_eq!(grid.origin_m[0] + column as f64 * 0.5, p[0]);
            assert_eq!(grid.origin_m[1] + row as f64 * 0.5, p[1]);
        }
    }
}
