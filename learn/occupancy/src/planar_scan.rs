//! One scan of a planar range scanner as occupancy maps see it: every beam in the world's ground
//! plane from the sensor to its return, or to the maximum range when it returned nothing (free
//! space all the way). The beams without a return are rebuilt from the sensor's beam pattern
//! (`sensor.json`), since a dataset stores returns only.

use patchflow_dataset::{SensorInfo, SensorKind, Sweep};

/// One beam in the ground plane, world frame, metres: the stretch of it that observed the plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Beam {
    /// Where the beam starts observing the plane: the sensor for a planar scanner; for a 3-D
    /// lidar's beam cut to a height slice, where it enters the slice.
    pub start_m: [f64; 2],
    /// Where the beam ends: its return, or the point at maximum range when it saw nothing.
    pub end_m: [f64; 2],
    /// True if the beam ended on a surface.
    pub hit: bool,
}

/// One planar scan: the sensor position, its time and every beam.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanarScan {
    /// Scan number in its sequence.
    pub index: usize,
    /// Time of the scan, seconds since the sequence started.
    pub stamp_secs: f64,
    /// The sensor's position in the ground plane, world frame (where every beam starts).
    pub sensor_m: [f64; 2],
    /// The sensor's forward axis, counter-clockwise from world +x.
    pub yaw_rad: f64,
    /// Every beam of the sensor's pattern, in firing order.
    pub beams: Vec<Beam>,
}

impl PlanarScan {
    /// The beams of `sweep` as taken by `sensor`: each return goes to the beam whose azimuth it
    /// lies on; beams without one end at maximum range. Only a planar scanner's sweeps can be
    /// read this way; the error says why not.
    ///
    /// ```
    /// use patchflow_dataset::{SensorInfo, SensorKind, Sweep};
    /// use patchflow_occupancy::PlanarScan;
    /// let sensor = SensorInfo {
    ///     kind: SensorKind::Planar,
    ///     rate_hz: 1.0,
    ///     max_range_m: 20.0,
    ///     mount_height_m: 0.5,
    ///     columns: 3,
    ///     first_azimuth_deg: 90.0,
    ///     azimuth_step_deg: -90.0,
    ///     elevations_deg: vec![0.0],
    /// };
    /// let sweep = Sweep { points_in_sensor: vec![[5.0, 0.0, 0.0]], ..Sweep::default() };
    /// let scan = PlanarScan::from_sweep(&sweep, &sensor).unwrap();
    /// assert!(scan.beams[1].hit && !scan.beams[0].hit);
    /// assert!((scan.beams[0].end_m[1] - 20.0).abs() < 1e-9);
    /// ```
    pub fn from_sweep(sweep: &Sweep, sensor: &SensorInfo) -> Result<Self, String> {
        if sensor.kind != SensorKind::Planar || sensor.elevations_deg.len() != 1 {
            return Err(format!(
                "occupancy maps are built from a planar scanner's scans; this sequence's sensor is {:?} with {} channels",
                sensor.kind,
                sensor.elevations_deg.len()
            ));
        }
        let mut range_m: Vec<Option<f64>> = vec![None; sensor.columns as usize];
        for (i, p) in sweep.points_in_sensor.iter().enumerate() {
            let (x, y) = (f64::from(p[0]), f64::from(p[1]));
            let column = sensor.column_of(y.atan2(x)).ok_or_else(|| {
                format!(
                    "return {i} at azimuth {:.2}° is on none of the sensor's beams",
                    y.atan2(x).to_degrees()
                )
            })?;
            let slot = &mut range_m[column as usize];
            if slot.is_none() {
                *slot = Some(x.hypot(y));
            }
        }
        // The scanner's own pose estimate, as a real system has (the truth where there is none).
        let pose = &sweep.estimated_pose();
        let to_world = |r: f64, column: u32| -> [f64; 2] {
            let (s, c) = sensor.azimuth_rad(column).sin_cos();
            let p = pose * nalgebra::Point3::new(r * c, r * s, 0.0);
            [p.x, p.y]
        };
        let origin = pose.translation.vector;
        let beams = range_m
            .iter()
            .zip(0u32..)
            .map(|(range, column)| Beam {
                start_m: [origin.x, origin.y],
                end_m: to_world(range.unwrap_or(sensor.max_range_m), column),
                hit: range.is_some(),
            })
            .collect();
        let forward = pose.rotation * nalgebra::Vector3::x();
        Ok(Self {
            index: sweep.index as usize,
            stamp_secs: sweep.stamp_secs,
            sensor_m: [origin.x, origin.y],
            yaw_rad: forward.y.atan2(forward.x),
            beams,
        })
    }

    /// Number of beams that returned from a surface.
    pub fn hits(&self) -> usize {
        self.beams.iter().filter(|b| b.hit).count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use patchflow_dataset::Pose;

    fn sensor(columns: u32) -> SensorInfo {
        SensorInfo {
            kind: SensorKind::Planar,
            rate_hz: 1.0,
            max_range_m: 20.0,
            mount_height_m: 0.5,
            columns,
            first_azimuth_deg: 90.0,
            azimuth_step_deg: -180.0 / f64::from(columns - 1),
            elevations_deg: vec![0.0],
        }
    }

    #[test]
    fn beams_start_at_the_sensor_and_end_at_their_return_in_the_world_frame() {
        // Sensor at (15, 0) facing +y: its forward axis is world +y, its left is world −x.
        let pose = Pose::new(
            nalgebra::Vector3::new(15.0, 0.0, 0.5),
            nalgebra::Vector3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2),
        );
        let sweep = Sweep {
            world_from_sensor: pose,
            points_in_sensor: vec![[7.5, 0.0, 0.0]],
            stamp_secs: 3.0,
            index: 3,
            ..Sweep::default()
        };
        let scan = PlanarScan::from_sweep(&sweep, &sensor(5)).unwrap();
        assert_eq!(scan.sensor_m, [15.0, 0.0]);
        assert!((scan.yaw_rad - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert_eq!(scan.hits(), 1);
        let forward = scan.beams[2];
        assert!(forward.hit);
        assert!((forward.end_m[0] - 15.0).abs() < 1e-9 && (forward.end_m[1] - 7.5).abs() < 1e-9);
        let left = scan.beams[0];
        assert!(!left.hit);
        assert!((left.end_m[0] + 5.0).abs() < 1e-9 && left.end_m[1].abs() < 1e-9);
    }

    #[test]
    fn a_spinning_lidars_sweep_is_refused_with_the_reason() {
        let spinning = SensorInfo {
            kind: SensorKind::Spinning,
            ..sensor(5)
        };
        let err = PlanarScan::from_sweep(&Sweep::default(), &spinning).unwrap_err();
        assert!(err.contains("planar"), "{err}");
    }
}
