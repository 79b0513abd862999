//! The nearest sliced return per bearing around the sensor: which objects a nearer one hides in
//! part. An object seen through a gap (a car crossing behind a row of parked cars) shows a stub
//! whose ends are the gap's edges, not its own: its motion along the stub changes no cell of the
//! difference map but at those edges, and the estimator's GPs read such stubs confidently and
//! wrong (docs/estimator.md, "Stop 46").

use std::f64::consts::{PI, TAU};

use patchflow_dataset::wrap_angle_rad;

use crate::SweepFeatures;

/// Width of a bearing bin, radians (0.25°: one or two azimuth steps of a 64-beam spinning lidar
/// at 10 Hz, so every bin a surface covers holds a return).
const BIN_RAD: f64 = 0.25 * PI / 180.0;
/// Bins looked at beyond each end of an object (1°: 0.4 m at 25 m).
const BINS_BEYOND_END: usize = 4;
/// A return this much nearer than an object's end hides what lies beyond that end, metres.
const NEARER_BY_M: f64 = 0.5;

/// One end of an object seen from the sensor: its point of smallest or of largest bearing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObjectEnd {
    /// The end point, world frame, metres.
    pub xy: [f64; 2],
    /// Whether a nearer return within 1° beyond it hides what lies further on: the object may go
    /// on behind it, so the point need not be the object's own end.
    pub hidden: bool,
}

/// The smallest range of the sliced returns per bearing bin, seen from the sensor.
#[derive(Debug, Clone)]
pub struct RangeProfile {
    sensor_xy: [f64; 2],
    nearest_m: Vec<f64>,
}

impl RangeProfile {
    /// The profile of the current sweep's sliced points.
    pub fn of(features: &SweepFeatures) -> Self {
        let sensor_xy = features.sensor_xy();
        let bins = (TAU / BIN_RAD).round() as usize;
        let mut nearest_m = vec![f64::INFINITY; bins];
        for p in features.points() {
            let (dx, dy) = (p.x_m - sensor_xy[0], p.y_m - sensor_xy[1]);
            let bin = bin_of(dy.atan2(dx), bins);
            nearest_m[bin] = nearest_m[bin].min(dx.hypot(dy));
        }
        Self {
            sensor_xy,
            nearest_m,
        }
    }

    /// How many ends of the object at `positions_xy` (0, 1 or 2) a nearer return hides: whether,
    /// within 1° beyond its smallest and its largest bearing, a return lies at least 0.5 m nearer
    /// than the object's point at that end. 0 for no positions.
    pub fn hidden_ends(&self, positions_xy: &[[f64; 2]]) -> usize {
        self.ends(positions_xy)
            .map_or(0, |ends| ends.iter().filter(|end| end.hidden).count())
    }

    /// The object's two ends seen from the sensor, its points of smallest and of largest bearing
    /// (in that order), each with whether a nearer return hides what lies beyond it (as
    /// [`Self::hidden_ends`] counts). `None` for no positions.
    pub fn ends(&self, positions_xy: &[[f64; 2]]) -> Option<[ObjectEnd; 2]> {
        let &first = positions_xy.first()?;
        let polar = |[x, y]: [f64; 2]| {
            let (dx, dy) = (x - self.sensor_xy[0], y - self.sensor_xy[1]);
            (dy.atan2(dx), dx.hypot(dy))
        };
        // Bearings relative to the first position's, so that an object across ±180° stays whole.
        let reference_rad = polar(first).0;
        let relative = |xy: [f64; 2]| {
            let (bearing, range) = polar(xy);
            (wrap_angle_rad(bearing - reference_rad), range, xy)
        };
        let (mut low, mut high) = (relative(first), relative(first));
        for &xy in &positions_xy[1..] {
            let point = relative(xy);
            if point.0 < low.0 {
                low = point;
            }
            if point.0 > high.0 {
                high = point;
            }
        }
        let end = |(bearing, range, xy): (f64, f64, [f64; 2]), step: f64| ObjectEnd {
            xy,
            hidden: (1..=BINS_BEYOND_END).any(|k| {
                let bin = bin_of(
                    reference_rad + bearing + step * k as f64 * BIN_RAD,
                    self.bins(),
                );
                self.nearest_m[bin] < range - NEARER_BY_M
            }),
        };
        Some([end(low, -1.0), end(high, 1.0)])
    }

    fn bins(&self) -> usize {
        self.nearest_m.len()
    }
}

/// The bin of a bearing, any angle.
fn bin_of(bearing_rad: f64, bins: usize) -> usize {
    let turns = (bearing_rad + PI).rem_euclid(TAU) / TAU;
    ((turns * bins as f64) as usize).min(bins - 1)
}

#[cfg(test)]
mod tests {
    use super::{ObjectEnd, RangeProfile};
    use crate::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
    use crate::{EstimatorParams, SweepFeatures};

    /// A car 20 m ahead crossing the line of sight (its long side towards the sensor), a wall
    /// behind the sensor so both sweeps have points, and the given boxes 15 m ahead (parked cars
    /// seen end-on, 1.8 m wide). Returns how many ends of the car a nearer return hides.
    fn hidden_ends_of_the_car_behind(parked_y_m: &[f64]) -> usize {
        ends_of_the_car_behind(parked_y_m)
            .iter()
            .filter(|end| end.hidden)
            .count()
    }

    /// [`hidden_ends_of_the_car_behind`]'s car's two ends (smallest bearing first).
    fn ends_of_the_car_behind(parked_y_m: &[f64]) -> [ObjectEnd; 2] {
        let mut boxes = vec![
            SceneBox::wall([-10.0, 0.0], 0.0, [0.4, 20.0, 2.5]),
            SceneBox::car(1, [20.0, 0.0], std::f64::consts::FRAC_PI_2, 6.0),
        ];
        boxes.extend(
            parked_y_m
                .iter()
                .map(|&y| SceneBox::wall([15.0, y], 0.0, [4.5, 1.8, 1.5])),
        );
        let scene = SyntheticScene { boxes };
        let lidar = SyntheticLidar::with_resolution(64, 1800);
        let sweep = scene.scan(&lidar, [0.0, 0.0], 0.0, 0);
        let features =
            SweepFeatures::compute(&sweep, &sweep, &EstimatorParams::default().features).unwrap();
        let car: Vec<[f64; 2]> = features
            .points()
            .iter()
            .filter(|p| p.x_m > 17.0)
            .map(|p| [p.x_m, p.y_m])
            .collect();
        assert!(car.len() >= 10, "{} car points", car.len());
        RangeProfile::of(&features).ends(&car).unwrap()
    }

    #[test]
    fn a_car_in_the_open_has_no_hidden_end() {
        assert_eq!(hidden_ends_of_the_car_behind(&[]), 0);
    }

    #[test]
    fn a_car_seen_past_one_parked_car_has_one_hidden_end() {
        assert_eq!(hidden_ends_of_the_car_behind(&[-1.6]), 1);
    }

    #[test]
    fn the_end_a_parked_car_hides_is_the_one_on_its_side() {
        // The parked car stands at y = −1.6 m, on the side of the smaller bearings.
        let [low, high] = ends_of_the_car_behind(&[-1.6]);
        assert!(low.hidden && !high.hidden, "{low:?} {high:?}");
        assert!(low.xy[1] < high.xy[1], "{low:?} {high:?}");
    }

    #[test]
    fn a_car_seen_through_the_gap_between_two_parked_cars_has_both_ends_hidden() {
        assert_eq!(hidden_ends_of_the_car_behind(&[-1.6, 1.6]), 2);
    }

    #[test]
    fn no_positions_have_no_hidden_end() {
        let scene = SyntheticScene {
            boxes: vec![SceneBox::wall([10.0, 0.0], 0.0, [0.4, 20.0, 2.5])],
        };
        let sweep = scene.scan(
            &SyntheticLidar::with_resolution(16, 900),
            [0.0, 0.0],
            0.0,
            0,
        );
        let features =
            SweepFeatures::compute(&sweep, &sweep, &EstimatorParams::default().features).unwrap();
        assert_eq!(RangeProfile::of(&features).hidden_ends(&[]), 0);
    }
}
