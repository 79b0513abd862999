//! The query points a map is scored on (DGPOM paper, Table 1): a regular lattice over the area
//! the sensor observes, i.e. within its maximum range and its field of view. The lattice is
//! aligned to the world origin, so maps of one sequence share their points, and it keeps its
//! rows and columns so maps can be drawn as images.

use patchflow_dataset::SensorInfo;

use crate::PlanarScan;

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
    /// `sensor.max_range_m` of it and inside the fan of its beams.
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
    /// let grid = QueryGrid::observed_by(&scan, &sensor, 1.0);
    /// // Half a disc of radius 20 m: about π · 20² / 2 ≈ 628 points.
    /// assert!((600..660).contains(&grid.points_m.len()));
    /// ```
    pub fn observed_by(scan: &PlanarScan, sensor: &SensorInfo, spacing_m: f64) -> Self {
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
        let (mut points_m, mut cells) = (Vec::new(), Vec::new());
        for row in 0..size[1] {
            for column in 0..size[0] {
                let p = [
                    origin_m[0] + column as f64 * spacing_m,
                    origin_m[1] + row as f64 * spacing_m,
                ];
                let (dx, dy) = (p[0] - sx, p[1] - sy);
                let bearing = wrap(dy.atan2(dx) - scan.yaw_rad);
                if dx.hypot(dy) <= r && bearing >= first && bearing <= last {
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

/// An angle wrapped into [−π, π).
fn wrap(a: f64) -> f64 {
    (a + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
}

#[cfg(test)]
mod tests {
    use super::*;
    use patchflow_dataset::SensorKind;

    #[test]
    fn points_lie_in_range_in_front_of_the_sensor_on_the_world_lattice() {
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
        let grid = QueryGrid::observed_by(&scan, &sensor, 0.5);
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
        assert!(grid.points_m.contains(&[15.0, 19.5]) && grid.points_m.contains(&[-4.5, 0.0]));
        for (p, &cell) in grid.points_m.iter().zip(&grid.cells) {
            let (row, column) = (cell / grid.size[0], cell % grid.size[0]);
            assert_eq!(grid.origin_m[0] + column as f64 * 0.5, p[0]);
            assert_eq!(grid.origin_m[1] + row as f64 * 0.5, p[1]);
        }
    }
}
