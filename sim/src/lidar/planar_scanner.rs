//! The planar range scanner (`[lidar] kind = "planar"`): one channel at 0° elevation and `beams`
//! beams spread over a horizontal field of view centred on the sensor's forward axis, like a SICK
//! LMS291 or the scanner of the DGPOM paper (70 beams over 180°, 20 m, 1 Hz). It is cast by the
//! same [`super::Lidar`] as the spinning lidar: its beams are the columns of a one-channel firing
//! table, and its scan is one block cast at the scan's reference time (a real planar scanner's
//! mirror turns far faster than it reports scans, so a scan is taken as one instant).

use crate::scenario::{LidarConfig, PLANAR_BEAMS, PLANAR_FOV_DEG};

/// Azimuth of beam `j` of a planar scanner, radians in the sensor frame (x forward, y left):
/// the beams run clockwise seen from above, from +fov/2 (left) to −fov/2 (right), the first and
/// last on the edges of the field of view (a full circle leaves out the duplicate edge).
pub(super) fn planar_azimuth_rad(config: &LidarConfig, j: u32) -> f64 {
    let fov_rad = config.fov_deg.unwrap_or(PLANAR_FOV_DEG).to_radians();
    let beams = config.beams.unwrap_or(PLANAR_BEAMS).max(2);
    let gaps = if fov_rad >= std::f64::consts::TAU - 1e-12 {
        beams
    } else {
        beams - 1
    };
    fov_rad / 2.0 - fov_rad * f64::from(j) / f64::from(gaps)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Scenario, SensorKind, Simulation};

    fn planar_config(fov_deg: f64, beams: u32) -> LidarConfig {
        LidarConfig {
            kind: SensorKind::Planar,
            fov_deg: Some(fov_deg),
            beams: Some(beams),
            ..LidarConfig::default()
        }
    }

    #[test]
    fn seventy_beams_over_180_degrees_run_from_left_to_right_with_both_edges() {
        let config = planar_config(180.0, 70);
        let first = planar_azimuth_rad(&config, 0).to_degrees();
        let last = planar_azimuth_rad(&config, 69).to_degrees();
        let step = first - planar_azimuth_rad(&config, 1).to_degrees();
        assert!((first - 90.0).abs() < 1e-9 && (last + 90.0).abs() < 1e-9);
        assert!((step - 180.0 / 69.0).abs() < 1e-9, "{step}");
    }

    #[test]
    fn a_full_circle_scanner_does_not_repeat_its_first_beam() {
        let config = planar_config(360.0, 360);
        let step = planar_azimuth_rad(&config, 0) - planar_azimuth_rad(&config, 1);
        assert!((step.to_degrees() - 1.0).abs() < 1e-9);
    }

    /// A fixed planar scanner at the origin facing +x, a wall whose near face is the plane
    /// x = 10 m, and (optionally) a car crossing between them, in the flat world of the
    /// `ideal` rung (exact ranges).
    fn wall_scene(extra: &str) -> Simulation {
        let text = format!(
            "sweeps = 6\nrealism = \"ideal\"\n[lidar]\nkind = \"planar\"\nbeams = 181\nrate_hz = 1.0\nmax_range_m = 30.0\nrange_noise_std_m = 0.0\n[ego]\npath_m = [[0.0, 0.0], [1.0, 0.0]]\nspeed_mps = 0.0\n[[structures]]\nkind = \"wall\"\ncentre_m = [10.15, 0.0]\nsize_m = [40.0, 0.3, 3.0]\nyaw_deg = 90.0\n{extra}"
        );
        let scenario = Scenario::from_toml(&text, "wall.toml", "wall").unwrap();
        Simulation::new(&scenario, 1).unwrap()
    }

    #[test]
    fn a_planar_scanner_hits_a_wall_at_the_range_its_bearing_implies() {
        let sweep = wall_scene("").sweep(0);
        // Beams within ±63° reach the 40 m wall inside 30 m: 10 / cos(a) ≤ 22 m.
        assert!(sweep.len() > 100, "{} returns", sweep.len());
        for p in &sweep.points_in_sensor {
            let bearing = f64::from(p[1]).atan2(f64::from(p[0]));
            let range = f64::from(p[0]).hypot(f64::from(p[1]));
            assert!(
                (range - 10.0 / bearing.cos()).abs() < 1e-3,
                "bearing {:.2}°: range {range} m",
                bearing.to_degrees()
            );
            assert_eq!(p[2], 0.0, "a planar return lies in the scan plane");
        }
        assert!(sweep.labels.iter().all(|l| l.semantic() == 51));
    }

    #[test]
    fn a_planar_scanner_on_an_ego_with_a_car_body_still_sees_the_wall() {
        // With vehicle shapes the ego has a car's body; the scanner at 0.5 m sits inside its
        // box (a bumper scanner) and must not be blinded by it.
        let sweep = wall_scene("[world]\nshapes = true\n").sweep(0);
        assert!(sweep.len() > 100, "{} returns", sweep.len());
    }

    #[test]
    fn a_fixed_scanner_sees_static_structure_identically_in_every_scan() {
        let mut sim = wall_scene(
            "[[actors]]\nname = \"crossing\"\npath_m = [[5.0, -20.0], [5.0, 20.0]]\nspeed_mps = 2.0\n",
        );
        let (first, later) = (sim.sweep(0), sim.sweep(5));
        assert_eq!(first.world_from_sensor, later.world_from_sensor);
        assert!((later.stamp_secs - 5.0).abs() < 1e-12);
        let wall = |s: &patchflow_dataset::Sweep| -> Vec<[f32; 3]> {
            (0..s.len())
                .filter(|&i| s.labels[i].instance() == 0)
                .map(|i| s.points_in_sensor[i])
                .collect()
        };
        assert!(wall(&first).len() > 50);
        // The car (4.7 m long, from y = −20 at t = 0 to −10 at t = 5) hides other beams of the wall.
        let car_points = |s: &patchflow_dataset::Sweep| s.objects[0].point_count;
        assert!(car_points(&later) > 0, "the car is in view at t = 5");
        let later_wall = wall(&later);
        assert!(later_wall.iter().all(|p| wall(&first).contains(p)));
        assert!(later.time_in_sweep_secs.iter().all(|&t| t == 0.0));
    }
}
