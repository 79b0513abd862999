//! How much of the ground around a cluster the previous sweep never observed: an object that has
//! just come into view (from behind a building or a parked car, or into range) shows on the
//! difference map where it became visible, not how it moved.
//!
//! Where a cell was unobserved at t − 1 the difference map reads m_t − prior (thesis Eq. 2.9 with
//! the map prior of 2.1.2): a car emerging from behind a building gains occupancy where it now
//! stands and loses it in the band between it and the sensor, which was hidden before and is free
//! now, the pattern of a car moving *away* from the sensor. The estimator's GPs read such patches
//! as confidently as any (docs/estimator.md, "Stop 45").

use crate::SweepFeatures;
use crate::features::patch::{PATCH_CELLS, PATCH_SIDE};

/// Two map values closer than this are the same value (the previous map is recovered as
/// m_t − (m_t − m_{t−1}), which can be off the prior by rounding).
const SAME_VALUE: f64 = 1e-9;

impl SweepFeatures {
    /// The share of cells of the patches' maps, over the 11 × 11 cells centred on each of
    /// `positions_xy` (a heading patch's reach, axis-aligned), whose previous value is the map
    /// prior: cells no sliced beam of the previous sweep reached, and cells outside the window.
    /// 0 for no positions. (An observed cell whose hits and misses balance to exactly the prior
    /// counts as unobserved; the share is a coarse measure. `ChangeEvidence` tells the two apart
    /// exactly with the maps at a second prior, which the estimator's features do not build.)
    pub fn unobserved_before_share(&self, positions_xy: &[[f64; 2]]) -> f64 {
        if positions_xy.is_empty() {
            return 0.0;
        }
        let maps = self.patch_source();
        let (now, difference) = (&maps.reflection, &maps.difference);
        let prior = self.params().prior;
        let half = (PATCH_SIDE / 2) as i64;
        let mut unobserved = 0usize;
        for &[x, y] in positions_xy {
            let [u, v] = now.window().to_local(x, y);
            let (col, row) = (u.floor() as i64, v.floor() as i64);
            for r in row - half..=row + half {
                for c in col - half..=col + half {
                    let before = now.get(c, r) - difference.get(c, r);
                    unobserved += usize::from((before - prior).abs() < SAME_VALUE);
                }
            }
        }
        unobserved as f64 / (positions_xy.len() * PATCH_CELLS) as f64
    }
}

#[cfg(test)]
mod tests {
    use crate::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
    use crate::{EstimatorParams, FeatureParams, SweepFeatures};

    /// A wall behind the sensor, so that both sweeps have sliced points whatever else they hold.
    fn wall() -> SceneBox {
        SceneBox::wall([-10.0, 0.0], 0.0, [0.4, 20.0, 2.5])
    }

    /// The features of `current` after `previous`, scanned from the origin, and the positions
    /// of the sliced points ahead of the sensor (x > 0: the car's in `current`).
    fn car_positions(
        previous: &SyntheticScene,
        current: &SyntheticScene,
    ) -> (SweepFeatures, Vec<[f64; 2]>) {
        let lidar = SyntheticLidar::with_resolution(64, 1800);
        let features = SweepFeatures::compute(
            &previous.scan(&lidar, [0.0, 0.0], 0.0, 0),
            &current.scan(&lidar, [0.0, 0.0], 0.0, 1),
            &EstimatorParams::default().features,
        )
        .unwrap();
        let car: Vec<[f64; 2]> = features
            .points()
            .iter()
            .filter(|p| p.x_m > 0.0)
            .map(|p| [p.x_m, p.y_m])
            .collect();
        assert!(car.len() > 20, "{} car points", car.len());
        (features, car)
    }

    #[test]
    fn cells_hidden_from_the_previous_sweep_count_as_unobserved_before() {
        // In the previous sweep a wall 2 m ahead hid everything beyond it (a truck that has
        // since driven off); now the car behind it is in view.
        let car = SceneBox::car(1, [6.0, 2.5], 0.3, 6.0);
        let previous = SyntheticScene {
            boxes: vec![
                car.clone(),
                wall(),
                SceneBox::wall([2.0, 1.5], 0.0, [0.4, 14.0, 2.5]),
            ],
        };
        let current = SyntheticScene {
            boxes: vec![car, wall()],
        };
        let (features, car) = car_positions(&previous, &current);
        let share = features.unobserved_before_share(&car);
        assert!(share > 0.95, "share {share}");
    }

    #[test]
    fn a_car_seen_in_both_sweeps_has_most_of_its_surroundings_observed_before() {
        let scene = SyntheticScene {
            boxes: vec![SceneBox::car(1, [6.0, 2.5], 0.3, 6.0), wall()],
        };
        let (features, car) = car_positions(&scene, &scene.advanced(0.1));
        let share = features.unobserved_before_share(&car);
        // What lies behind the car's visible faces is hidden in both sweeps: about a third.
        assert!(share < 0.6, "share {share}");
    }

    #[test]
    fn no_positions_have_nothing_unobserved() {
        let scene = SyntheticScene {
            boxes: vec![wall()],
        };
        let lidar = SyntheticLidar::with_resolution(16, 360);
        let sweep = scene.scan(&lidar, [0.0, 0.0], 0.0, 0);
        let features = SweepFeatures::compute(&sweep, &sweep, &FeatureParams::default()).unwrap();
        assert_eq!(features.unobserved_before_share(&[]), 0.0);
    }
}
