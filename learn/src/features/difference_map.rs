//! The difference map (thesis 2.1.2, Eq. 2.9): m_t − m_{t−1} on one world-aligned window, so a
//! moving object shows a loss of occupancy behind it and a gain ahead.

use crate::FeatureParams;
use crate::features::grid::{GridMap, GridWindow};
use crate::features::reflection_map::reflection_map;
use crate::features::slice::HeightSlice;

/// The current reflection map and the difference map, both on the current sweep's window.
#[derive(Debug, Clone, PartialEq)]
pub struct MapPair {
    /// Reflection map of the current sweep, m_t.
    pub reflection: GridMap,
    /// m_t − m_{t−1}; cells outside the window read 0.
    pub difference: GridMap,
}

impl MapPair {
    /// Builds both sweeps' reflection maps on the window centred on the current sensor (in
    /// parallel), then subtracts in place: the previous map's storage becomes the difference.
    pub fn build(prev: &HeightSlice, curr: &HeightSlice, params: &FeatureParams) -> Self {
        let window = GridWindow::centred(curr.sensor_xy, params.half_extent_m, params.cell_m);
        let (mut difference, reflection) = rayon::join(
            || reflection_map(&prev.beams, &window, params.prior, params.spread),
            || reflection_map(&curr.beams, &window, params.prior, params.spread),
        );
        subtract_from(&mut difference, &reflection);
        Self {
            reflection,
            difference,
        }
    }
}

/// Turns `prev` into `curr − prev` (thesis Eq. 2.9); both lie on the same window.
fn subtract_from(prev: &mut GridMap, curr: &GridMap) {
    for (p, c) in prev.values_mut().iter_mut().zip(curr.values()) {
        *p = c - *p;
    }
    prev.set_outside(0.0);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::features::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};

    /// Maps of a scene and the same scene 0.1 s later, sensor still at the origin.
    fn maps_of(scene: &SyntheticScene, prior: f64) -> MapPair {
        let lidar = SyntheticLidar::with_resolution(64, 1800);
        let params = FeatureParams {
            half_extent_m: 20.0,
            ..FeatureParams::with_prior(prior)
        };
        let prev = HeightSlice::cut(&scene.scan(&lidar, [0.0, 0.0], 0.0, 0), &params).unwrap();
        let next = scene.advanced(0.1);
        let curr = HeightSlice::cut(&next.scan(&lidar, [0.0, 0.0], 0.0, 1), &params).unwrap();
        MapPair::build(&prev, &curr, &params)
    }

    /// Mean of the map over the rectangle `[x0, x1] × [y0, y1]` (cell centres inside).
    fn mean_over(map: &GridMap, x0: f64, x1: f64, y0: f64, y1: f64) -> f64 {
        let w = map.window();
        let (mut sum, mut n) = (0.0, 0);
        for row in 0..w.rows {
            for col in 0..w.cols {
                let [x, y] = w.centre_of(col, row);
                if (x0..=x1).contains(&x) && (y0..=y1).contains(&y) {
                    sum += map.values()[w.index(col, row)];
                    n += 1;
                }
            }
        }
        sum / f64::from(n)
    }

    #[test]
    fn a_car_crossing_the_view_leaves_a_loss_behind_and_a_gain_ahead() {
        // Heading +x at 5 m/s: 0.5 m per sweep; the visible side is the face at y = 11.1.
        let scene = SyntheticScene {
            boxes: vec![SceneBox::car(1, [0.0, 12.0], 0.0, 5.0)],
        };
        let maps = maps_of(&scene, 0.5);
        let gain = mean_over(&maps.difference, 2.3, 2.7, 10.95, 11.25);
        let loss = mean_over(&maps.difference, -2.2, -1.8, 10.95, 11.25);
        let middle = mean_over(&maps.difference, -1.0, 1.0, 10.95, 11.25);
        assert!(gain > 0.3, "gain ahead {gain}");
        assert!(loss < -0.3, "loss behind {loss}");
        assert!(
            middle.abs() < 0.05,
            "the unchanged middle of the side {middle}"
        );
    }

    #[test]
    fn a_car_approaching_along_the_line_of_sight_gains_in_front_and_loses_its_old_face() {
        let scene = SyntheticScene {
            boxes: vec![SceneBox::car(1, [15.0, 0.0], std::f64::consts::PI, 5.0)],
        };
        let maps = maps_of(&scene, 0.01);
        // Old face at x = 12.75, new face at x = 12.25.
        let gain = mean_over(&maps.difference, 12.2, 12.45, -0.5, 0.5);
        let loss = mean_over(&maps.difference, 12.75, 12.9, -0.5, 0.5);
        assert!(gain > 0.3, "gain {gain}");
        assert!(loss < -0.3, "loss {loss}");
    }

    #[test]
    fn a_static_scene_has_a_zero_difference_map() {
        let scene = SyntheticScene {
            boxes: vec![SceneBox::wall([8.0, 3.0], 0.4, [6.0, 0.5, 2.5])],
        };
        let maps = maps_of(&scene, 0.5);
        assert!(maps.difference.values().iter().all(|v| v.abs() < 1e-12));
        assert_eq!(maps.difference.outside(), 0.0);
    }
}
