//! The ego car's own body below its roof-mounted lidar. A real mount sits a few decimetres above
//! the roof, so the lowest beams end on the car's own roof, bonnet and boot over much of the
//! azimuth: the returns every driver drops as self-returns, and the empty disc around the car in
//! KITTI scans. On a world with vehicle shapes the ego car has the body of its class; every beam
//! of the firing table is tested against it once, in the sensor frame, and a beam it stops is
//! never cast (and never returns). A sensor mounted below the body's top (a planar scanner at
//! bumper height, 0.5 m by default) looks out of the body's front, not through it: its beams are
//! never stopped by the body.

use rapier3d::parry::query::Ray;
use rapier3d::prelude::Vector;

use crate::scenario::ActorConfig;
use crate::world::{GridPiece, body_parts};

/// Farthest a beam can meet the ego car's body, metres (beyond its half length and height).
const REACH_M: f32 = 10.0;

/// For every direction of `rays` (sensor frame), whether the body of `ego` stops it; the sensor
/// is `mount_height_m` above the ground, over the centre of the ego's box.
pub(super) fn occluded_beams(rays: &[Vector], ego: &ActorConfig, mount_height_m: f64) -> Vec<bool> {
    let size = ego.size_m.unwrap_or([4.7, 1.8, 1.45]);
    if mount_height_m <= size[2] {
        return vec![false; rays.len()];
    }
    let drop_m = (mount_height_m - size[2] / 2.0) as f32;
    let body: Vec<GridPiece> = body_parts(ego.class, size, None, 0.5)
        .into_iter()
        .filter_map(|mut part| {
            // Box frame (origin at the box centre) to the sensor frame.
            part.centre_m[2] -= drop_m;
            GridPiece::new(&part)
        })
        .collect();
    rays.iter()
        .map(|&dir| {
            let ray = Ray::new(Vector::ZERO, dir);
            body.iter()
                .any(|part| part.cast_solid(&ray, REACH_M).is_some())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Scenario;

    fn ego() -> ActorConfig {
        let text = "sweeps = 1\n[ego]\npath_m = [[0.0, 0.0], [50.0, 0.0]]\nspeed_mps = 5.0\n";
        Scenario::from_toml(text, "e.toml", "e").unwrap().ego
    }

    fn beam(azimuth_deg: f32, elevation_deg: f32) -> Vector {
        let (a, e) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
        Vector::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
    }

    #[test]
    fn the_lowest_beams_end_on_the_car_and_the_others_pass() {
        let rays = [
            beam(0.0, -24.8),
            beam(90.0, -24.8),
            beam(180.0, -24.0),
            beam(90.0, -15.0),
            beam(0.0, -8.0),
            beam(45.0, 2.0),
        ];
        let occluded = occluded_beams(&rays, &ego(), 1.73);
        assert_eq!(occluded, [true, true, true, false, false, false]);
    }

    #[test]
    fn a_scanner_mounted_below_the_roof_looks_out_of_the_body_unstopped() {
        let rays = [
            beam(0.0, 0.0),
            beam(90.0, 0.0),
            beam(180.0, 0.0),
            beam(0.0, -5.0),
        ];
        assert_eq!(occluded_beams(&rays, &ego(), 0.5), [false; 4]);
    }
}
