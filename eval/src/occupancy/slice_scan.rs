//! A 3-D lidar's sweep as an occupancy observation in the plane (issue 12, the intersection seen
//! through the height slice): the sweep is cut to the thesis' slice, 0.5-1.0 m above the local
//! ground estimated from the sweep itself (`patchflow-learn`'s [`HeightSlice`], the slice the
//! motion features use; thesis 2.1.1), and each beam's part inside the slice becomes one beam of
//! a [`PlanarScan`] from where it enters the slice to where it leaves it or returns. A return in
//! the slice is an occupied point; the sliced stretch before it is free space, sampled as a planar
//! scanner's beam is. A beam's stretch above or below the slice says nothing about the slice and
//! is left out (a ray from the sensor to the return would cross cars it passed over). This is
//! where the occupancy family meets the features: `patchflow-occupancy` does not depend on
//! `patchflow-learn`, so the cut is made here and handed to [`OccupancySequence::load_with`].
//!
//! [`OccupancySequence::load_with`]: patchflow_occupancy::OccupancySequence::load_with

use patchflow_dataset::{SensorInfo, Sweep};
use patchflow_learn::{FeatureParams, GroundMode, HeightSlice};
use patchflow_occupancy::{Beam, PlanarScan};

/// The feature parameters of the cut: the thesis slice above the sweep's own ground estimate,
/// the ground estimated over the sensor's whole reach (not only the 40 m feature window).
pub fn slice_params(sensor: &SensorInfo) -> FeatureParams {
    FeatureParams {
        ground: GroundMode::Estimated,
        half_extent_m: sensor.max_range_m,
        ..FeatureParams::default()
    }
}

/// The height the slice observes, where its truth is taken: the middle of the slice, metres.
pub fn slice_height_m(sensor: &SensorInfo) -> f64 {
    let params = slice_params(sensor);
    0.5 * (params.slice_min_m + params.slice_max_m)
}

/// The sweep's beams cut to the height slice, as a scan in the plane (world frame, the ego's
/// estimated pose); an error says why the sweep cannot be cut.
///
/// ```
/// use patchflow_eval::height_slice_scan;
/// use patchflow_learn::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
/// let scene = SyntheticScene { boxes: vec![SceneBox::wall([10.5, 0.0], 0.0, [1.0, 20.0, 3.0])] };
/// let lidar = SyntheticLidar::with_resolution(32, 360);
/// let sweep = scene.scan(&lidar, [0.0, 0.0], 0.0, 0);
/// let sensor = patchflow_dataset::SensorInfo {
///     kind: patchflow_dataset::SensorKind::Spinning,
///     rate_hz: 1.0,
///     max_range_m: lidar.max_range_m,
///     mount_height_m: lidar.mount_height_m,
///     columns: 360,
///     first_azimuth_deg: 180.0,
///     azimuth_step_deg: -1.0,
///     elevations_deg: lidar.elevations_deg.clone(),
/// };
/// let scan = height_slice_scan(&sweep, &sensor).unwrap();
/// assert!(scan.hits() > 0);
/// assert!(scan.beams.iter().filter(|b| b.hit).all(|b| (b.end_m[0] - 10.0).abs() < 0.01));
/// ```
pub fn height_slice_scan(sweep: &Sweep, sensor: &SensorInfo) -> Result<PlanarScan, String> {
    // Thesis 2.1.1: the beams' parts 0.5-1.0 m above the local ground, projected to the plane.
    let slice = HeightSlice::cut(sweep, &slice_params(sensor)).map_err(|e| e.to_string())?;
    let beams = slice
        .beams
        .iter()
        .map(|b| Beam {
            start_m: b.start_xy,
            end_m: b.end_xy,
            hit: b.hit,
        })
        .collect();
    let pose = sweep.estimated_pose();
    let forward = pose.rotation * nalgebra::Vector3::x();
    Ok(PlanarScan {
        index: sweep.index as usize,
        stamp_secs: sweep.stamp_secs,
        sensor_m: slice.sensor_xy,
        yaw_rad: forward.y.atan2(forward.x),
        beams,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use patchflow_dataset::SensorKind;
    use patchflow_learn::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
    use patchflow_occupancy::{SampleParams, scan_samples};

    fn sensor(lidar: &SyntheticLidar) -> SensorInfo {
        SensorInfo {
            kind: SensorKind::Spinning,
            rate_hz: 1.0,
            max_range_m: lidar.max_range_m,
            mount_height_m: lidar.mount_height_m,
            columns: lidar.azimuth_steps as u32,
            first_azimuth_deg: 180.0,
            azimuth_step_deg: -360.0 / lidar.azimuth_steps as f64,
            elevations_deg: lidar.elevations_deg.clone(),
        }
    }

    /// A wall (3 m high) whose face is at x = 10, and a low box (0.4 m, below the slice) at
    /// y = 6 in front of the sensor's left.
    fn scene() -> SyntheticScene {
        SyntheticScene {
            boxes: vec![
                SceneBox::wall([10.5, 0.0], 0.0, [1.0, 20.0, 3.0]),
                SceneBox::wall([0.0, 6.5], 0.0, [2.0, 1.0, 0.4]),
            ],
        }
    }

    #[test]
    fn a_wall_at_ten_metres_gives_occupied_points_there_and_free_points_before_it() {
        let lidar = SyntheticLidar::with_resolution(64, 720);
        let sweep = scene().scan(&lidar, [0.0, 0.0], 0.0, 3);
        let scan = height_slice_scan(&sweep, &sensor(&lidar)).unwrap();
        assert!(scan.hits() > 20, "{}", scan.hits());
        assert_eq!(scan.sensor_m, [0.0, 0.0]);
        // Every occupied point lies on the wall's face, within the slice's range of heights.
        let samples = scan_samples(&scan, &SampleParams::default());
        let occupied: Vec<_> = samples.iter().filter(|s| s.occupied).collect();
        assert_eq!(occupied.len(), scan.hits());
        assert!(occupied.iter().all(|s| (s.xy_m[0] - 10.0).abs() < 0.01));
        // Free points straight ahead lie before the wall, none behind it.
        let ahead: Vec<_> = samples
            .iter()
            .filter(|s| !s.occupied && s.xy_m[1].abs() < 1.0 && s.xy_m[0] > 0.0)
            .collect();
        assert!(!ahead.is_empty());
        assert!(
            ahead.iter().all(|s| s.xy_m[0] < 9.5),
            "free sample at or past the wall"
        );
        assert!(samples.iter().all(|s| s.t_secs == sweep.stamp_secs));
    }

    #[test]
    fn returns_outside_the_slice_give_no_occupied_point() {
        let lidar = SyntheticLidar::with_resolution(64, 720);
        let sweep = scene().scan(&lidar, [0.0, 0.0], 0.0, 3);
        // The sweep has returns on the low box and on the wall above the slice ...
        let world: Vec<_> = (0..sweep.len()).map(|i| sweep.point_in_world(i)).collect();
        let on_low_box = |x: f64, y: f64| x.abs() < 1.5 && (y - 6.0).abs() < 0.5;
        assert!(world.iter().any(|p| on_low_box(p.x, p.y) && p.z > 0.05));
        assert!(world.iter().any(|p| (p.x - 10.0).abs() < 0.01 && p.z > 1.2));
        // ... but the slice has no return on the low box, and exactly the wall's returns
        // between 0.5 and 1.0 m.
        let scan = height_slice_scan(&sweep, &sensor(&lidar)).unwrap();
        let hits: Vec<_> = scan.beams.iter().filter(|b| b.hit).collect();
        assert!(hits.iter().all(|b| !on_low_box(b.end_m[0], b.end_m[1])));
        let in_slice = world.iter().filter(|p| (0.5..=1.0).contains(&p.z)).count();
        assert!(
            (hits.len() as i64 - in_slice as i64).abs() <= 2,
            "{} hits, {in_slice} points 0.5-1.0 m up",
            hits.len()
        );
    }
}
