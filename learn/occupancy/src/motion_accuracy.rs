//! How well a learned motion map matches the traffic (issue 25): the RMSE of the velocity field Υ
//! against the exact velocities of the training run's actors, on the lanes (cells a car covered
//! at some scan of the run, the truth there the mean velocity of the cars that covered it) and
//! off them (cells the run observed that no car ever covered, truth 0). Only cells the run's scans
//! observed are scored: elsewhere the map has nothing to learn from.

use std::collections::{BTreeMap, BTreeSet};

use serde::{Deserialize, Serialize};

use crate::scan_cells::{Cell, ScanCells};
use crate::{MotionField, OccupancySequence, OrientedBox};

/// The motion map's accuracy against the training run's actors.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct MotionAccuracy {
    /// RMSE of |Υ − v| over the lane cells, m/s.
    pub lane_rmse_mps: f64,
    /// RMSE of |Υ| over the observed cells no car covered, m/s.
    pub off_lane_rmse_mps: f64,
    /// Lane cells scored.
    pub lane_cells: usize,
    /// Off-lane cells scored.
    pub off_lane_cells: usize,
    /// Cell size of the lattice, metres.
    pub cell_m: f64,
}

impl MotionAccuracy {
    /// Scores `field` against the actors of `training` on a lattice of `cell_m` cells.
    pub fn of(field: &dyn MotionField, training: &OccupancySequence, cell_m: f64) -> Self {
        let mut observed: BTreeSet<Cell> = BTreeSet::new();
        for scan in &training.scans {
            for &cell in ScanCells::from_scan(scan, cell_m).cells.keys() {
                observed.insert(cell);
            }
        }
        let centre_m = |(c, r): Cell| [(c as f64 + 0.5) * cell_m, (r as f64 + 0.5) * cell_m];
        let statics = training.truth.static_boxes();
        let height_m = training.scan_height_m();
        // Truth velocity sums per lane cell: every actor box of every scan, its cells covered.
        let mut lanes: BTreeMap<Cell, ([f64; 2], usize)> = BTreeMap::new();
        for (_, actors) in training.truth.actors_by_scan() {
            for actor in actors {
                let b = OrientedBox::of_object(actor);
                let reach = b.half_extents_m[0].hypot(b.half_extents_m[1]);
                let lo = cell_index(b.centre_m, -reach, cell_m);
                let hi = cell_index(b.centre_m, reach, cell_m);
                for c in lo.0..=hi.0 {
                    for r in lo.1..=hi.1 {
                        if !b.contains(centre_m((c, r)), height_m) {
                            continue;
                        }
                        let e = lanes.entry((c, r)).or_insert(([0.0; 2], 0));
                        e.0[0] += actor.velocity_mps[0];
                        e.0[1] += actor.velocity_mps[1];
                        e.1 += 1;
                    }
                }
            }
        }
        let (mut lane_sq, mut lane_n, mut off_sq, mut off_n) = (0.0, 0, 0.0, 0);
        for &cell in &observed {
            let p = centre_m(cell);
            let v = field.velocity_mps(p);
            match lanes.get(&cell) {
                Some((sum, n)) => {
                    let truth = [sum[0] / *n as f64, sum[1] / *n as f64];
                    lane_sq += (v[0] - truth[0]).powi(2) + (v[1] - truth[1]).powi(2);
                    lane_n += 1;
                }
                None if !statics.iter().any(|b| b.contains(p, height_m)) => {
                    off_sq += v[0] * v[0] + v[1] * v[1];
                    off_n += 1;
                }
                None => {}
            }
        }
        let rmse = |sq: f64, n: usize| if n == 0 { 0.0 } else { (sq / n as f64).sqrt() };
        Self {
            lane_rmse_mps: rmse(lane_sq, lane_n),
            off_lane_rmse_mps: rmse(off_sq, off_n),
            lane_cells: lane_n,
            off_lane_cells: off_n,
            cell_m,
        }
    }
}

/// The cell of `centre + offset` on both axes.
fn cell_index(centre: [f64; 2], offset: f64, cell_m: f64) -> Cell {
    (
        ((centre[0] + offset) / cell_m).floor() as i64,
        ((centre[1] + offset) / cell_m).floor() as i64,
    )
}

#[cfg(test)]
mod tests {
    use patchflow_dataset::{ActorClass, ObjectTruth, SensorInfo, SensorKind};

    use super::*;
    use crate::{Beam, GroundTruth, PlanarScan};

    /// A car 4 m × 2 m centred at (6, 0) driving +x at 2 m/s, and a scan from the origin whose
    /// beams fan over it.
    fn training() -> OccupancySequence {
        let car = ObjectTruth {
            id: 1,
            name: "car".into(),
            class: ActorClass::Car,
            target: false,
            moving: true,
            centre_m: [6.0, 0.0, 0.75],
            size_m: [4.0, 2.0, 1.5],
            yaw_rad: 0.0,
            velocity_mps: [2.0, 0.0, 0.0],
            speed_mps: 2.0,
            heading_rad: 0.0,
            yaw_rate_radps: 0.0,
            point_count: 0,
        };
        let beams = (0..41)
            .map(|j| {
                let a = (-40.0 + 2.0 * f64::from(j)).to_radians();
                Beam {
                    start_m: [0.0, 0.0],
                    end_m: [12.0 * a.cos(), 12.0 * a.sin()],
                    hit: false,
                }
            })
            .collect();
        let scan = PlanarScan {
            index: 0,
            stamp_secs: 0.0,
            sensor_m: [0.0, 0.0],
            yaw_rad: 0.0,
            beams,
        };
        OccupancySequence {
            name: "test".into(),
            dir: "test".into(),
            sensor: SensorInfo {
                kind: SensorKind::Planar,
                rate_hz: 1.0,
                max_range_m: 12.0,
                mount_height_m: 0.5,
                columns: 41,
                first_azimuth_deg: -40.0,
                azimuth_step_deg: 2.0,
                elevations_deg: vec![0.0],
            },
            scans: vec![scan],
            truth: GroundTruth::new(&[], vec![(0.0, vec![car])]),
            scan_height_m: 0.5,
        }
    }

    #[derive(Debug)]
    struct Field(f64);

    impl MotionField for Field {
        fn velocity_mps(&self, xy_m: [f64; 2]) -> [f64; 2] {
            let on_car = (4.0..=8.0).contains(&xy_m[0]) && xy_m[1].abs() <= 1.0;
            [if on_car { self.0 } else { 0.0 }, 0.0]
        }
        fn error_mps(&self, _: [f64; 2]) -> f64 {
            0.1
        }
    }

    #[test]
    fn the_exact_lane_velocity_scores_zero_and_a_still_field_the_cars_speed() {
        let seq = training();
        let exact = MotionAccuracy::of(&Field(2.0), &seq, 0.5);
        assert!(
            exact.lane_cells > 10 && exact.off_lane_cells > 100,
            "{exact:?}"
        );
        assert!(exact.lane_rmse_mps < 1e-12 && exact.off_lane_rmse_mps < 1e-12);
        let still = MotionAccuracy::of(&Field(0.0), &seq, 0.5);
        assert!((still.lane_rmse_mps - 2.0).abs() < 1e-12, "{still:?}");
    }
}
