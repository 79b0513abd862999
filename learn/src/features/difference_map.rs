//! The difference map (thesis 2.1.2, Eq. 2.9): m_t − m_{t−1} on one world-aligned window, so a
//! moving object shows a loss of occupancy behind it and a gain ahead.

use crate::FeatureParams;
use crate::features::counts_view::CountsView;
use crate::features::grid::{GridMap, GridWindow};
use crate::features::reflection_map::{MapValues, reflection_and_difference};
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
    /// Builds both sweeps' reflection maps on `window` (the current sweep's map window,
    /// [`FeatureParams::map_window`]) and their difference (thesis Eq. 2.8-2.9).
    pub fn build(
        prev: &HeightSlice,
        curr: &HeightSlice,
        window: GridWindow,
        params: &FeatureParams,
    ) -> Self {
        Self::build_for_priors(prev, curr, window, params.spread, &[params.prior])
            .into_iter()
            .next()
            .unwrap_or_else(|| Self {
                reflection: GridMap::filled(window, params.prior),
                difference: GridMap::filled(window, 0.0),
            })
    }

    /// Like [`Self::build`] once per prior, with the hit-and-miss `spread` of
    /// [`FeatureParams::spread`]: the beams are traced once (in parallel for the two sweeps),
    /// since the prior only fills unobserved cells; each slice keeps its counts for the next pair.
    pub fn build_for_priors(
        prev: &HeightSlice,
        curr: &HeightSlice,
        window: GridWindow,
        spread: f64,
        priors: &[f64],
    ) -> Vec<Self> {
        // 2.1.1: hits and misses of both sweeps' sliced beams on the current window (each
        // sweep's beams traced once: the previous one's counts are usually those it was traced
        // with as the current sweep).
        let (prev_counts, curr_counts) = rayon::join(
            || prev.counts_holding(&window),
            || curr.counts_holding(&window),
        );
        let [prev_view, curr_view] =
            [&prev_counts, &curr_counts].map(|(counts, at)| CountsView::at(counts, &window, *at));
        // Eq. 2.8-2.9: spread, divide, subtract.
        let maps = reflection_and_difference(&prev_view, &curr_view, priors, spread);
        maps.into_iter()
            .zip(priors)
            .map(|(values, &prior)| Self::from_values(window, values, prior))
            .collect()
    }

    /// Wraps one prior's values.
    fn from_values(window: GridWindow, values: MapValues, prior: f64) -> Self {
        Self {
            reflection: GridMap::from_values(window, values.reflection, prior)
                .unwrap_or_else(|| GridMap::filled(window, prior)),
            difference: GridMap::from_values(window, values.difference, 0.0)
                .unwrap_or_else(|| GridMap::filled(window, 0.0)),
        }
    }
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
        MapPair::build(&prev, &curr, params.map_window(curr.sensor_xy), &params)
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

    #[test]
    fn maps_for_several_priors_match_maps_built_one_prior_at_a_time() {
        let scene = SyntheticScene {
            boxes: vec![SceneBox::car(1, [0.0, 12.0], 0.0, 5.0)],
        };
        let lidar = SyntheticLidar::with_resolution(32, 900);
        let params = FeatureParams {
            half_extent_m: 15.0,
            ..FeatureParams::default()
        };
        let prev = HeightSlice::cut(&scene.scan(&lidar, [0.0, 0.0], 0.0, 0), &params).unwrap();
        let next = scene.advanced(0.1);
        let curr = HeightSlice::cut(&next.scan(&lidar, [0.3, 0.0], 0.0, 1), &params).unwrap();
        let both = MapPair::build_for_priors(
            &prev,
            &curr,
            params.map_window(curr.sensor_xy),
            params.spread,
            &[0.01, 0.5],
        );
        for (pair, prior) in both.iter().zip([0.01, 0.5]) {
            let one = MapPair::build(
                &prev,
                &curr,
                params.map_window(curr.sensor_xy),
                &FeatureParams {
                    prior,
                    ..params.clone()
                },
            );
            assert_eq!(pair, &one, "prior {prior}");
        }
    }

    #[test]
    fn maps_from_the_counts_a_slice_keeps_equal_maps_traced_afresh() {
        // The ego drives 0.7 m per sweep (within the room the counts keep), then jumps 6 m (not).
        let scene = SyntheticScene {
            boxes: vec![
                SceneBox::car(1, [4.0, 9.0], 0.3, 6.0),
                SceneBox::wall([-3.0, -6.0], 0.2, [8.0, 0.4, 2.5]),
            ],
        };
        let lidar = SyntheticLidar::with_resolution(32, 900);
        let params = FeatureParams {
            half_extent_m: 15.0,
            ..FeatureParams::default()
        };
        let sensors = [[0.0, 0.0], [0.7, 0.05], [1.4, 0.1], [7.4, 0.1]];
        let cut = |k: usize| {
            let sweep = scene
                .advanced(0.1 * k as f64)
                .scan(&lidar, sensors[k], 0.0, k as u32);
            HeightSlice::cut(&sweep, &params).unwrap()
        };
        let kept: Vec<HeightSlice> = (0..sensors.len()).map(cut).collect();
        for k in 1..sensors.len() {
            let window = params.map_window(sensors[k]);
            let from_kept = MapPair::build(&kept[k - 1], &kept[k], window, &params);
            let afresh = MapPair::build(&cut(k - 1), &cut(k), window, &params);
            assert_eq!(from_kept, afresh, "sweep {k}");
        }
    }
}
