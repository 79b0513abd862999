//! The height slice (thesis 2.1.1): the parts of the beams and the end points between 0.5 m and
//! 1.0 m above the ground, projected onto the ground plane. The ground is the flat road the
//! thesis assumes (world z = 0) or the local ground estimated from the sweep itself.

use patchflow_dataset::Sweep;

use crate::features::ground_grid::{GroundGrid, points_in_world};
use crate::features::ground_slab::{SlabAboveGround, clip_to_slab};
use crate::{FeatureParams, GroundMode, Result};

/// The part of one beam inside the height slice, projected to the ground plane (world x, y).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlicedBeam {
    /// Where the beam enters the slice (or the sensor, if it starts inside).
    pub start_xy: [f64; 2],
    /// Where it leaves the slice, or its end point.
    pub end_xy: [f64; 2],
    /// True if the end point lies in the slice: the end cell is a hit, the rest misses.
    pub hit: bool,
}

/// An end point inside the slice: world x, y and its index among the sweep's points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlicedPoint {
    /// World x, metres.
    pub x_m: f64,
    /// World y, metres.
    pub y_m: f64,
    /// Index into the sweep's per-point arrays.
    pub index: usize,
}

/// One sweep cut to the height slice.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightSlice {
    /// Sensor position at the sweep's reference time, world x, y.
    pub sensor_xy: [f64; 2],
    /// Every part of a beam that crosses or ends in the slice, in point order (over uneven
    /// ground a beam may pass through the slice more than once).
    pub beams: Vec<SlicedBeam>,
    /// Every end point in the slice, in point order.
    pub points: Vec<SlicedPoint>,
}

impl HeightSlice {
    /// Cuts a sweep: beams run from the sensor origin to each end point, and heights are taken
    /// above the ground `params.ground` names (world z = 0, or the sweep's own estimated ground,
    /// [`GroundGrid`]). A non-finite point is an error.
    pub fn cut(sweep: &Sweep, params: &FeatureParams) -> Result<Self> {
        // The end points in the world frame.
        let points = points_in_world(sweep)?;
        let o = sweep.world_from_sensor.translation.vector;
        let origin = [o.x, o.y, o.z];
        match params.ground {
            GroundMode::Flat => Ok(Self::above_flat(&points, origin, params)),
            GroundMode::Estimated => {
                // The ground under the sweep, from the sweep alone (thesis 6, future work).
                let ground =
                    GroundGrid::from_points_in_world(&points, [o.x, o.y], params.half_extent_m);
                // 2.1.1: the slice above it.
                Ok(Self::above(&points, origin, &ground, params))
            }
        }
    }

    /// Cuts a sweep above a given ground ([`Self::cut`] with `GroundMode::Estimated` is this
    /// with the sweep's own estimate).
    pub fn cut_above(sweep: &Sweep, ground: &GroundGrid, params: &FeatureParams) -> Result<Self> {
        let points = points_in_world(sweep)?;
        let o = sweep.world_from_sensor.translation.vector;
        Ok(Self::above(&points, [o.x, o.y, o.z], ground, params))
    }

    /// The slice above the plane z = 0: one straight clip per beam (the thesis' flat road).
    fn above_flat(points: &[[f64; 3]], origin: [f64; 3], params: &FeatureParams) -> Self {
        let (zmin, zmax) = (params.slice_min_m, params.slice_max_m);
        let mut slice = Self::empty(origin);
        for (index, &end) in points.iter().enumerate() {
            let Some(interval) = clip_to_slab(origin[2], end[2], zmin, zmax) else {
                continue;
            };
            let hit = (zmin..=zmax).contains(&end[2]);
            slice.push(origin, end, index, &[interval], hit);
        }
        slice
    }

    /// The slice above `ground`: each beam in the pieces where it runs between `slice_min_m` and
    /// `slice_max_m` above the ground under it.
    fn above(
        points: &[[f64; 3]],
        origin: [f64; 3],
        ground: &GroundGrid,
        params: &FeatureParams,
    ) -> Self {
        let slab = SlabAboveGround::new(ground, origin, params.slice_min_m, params.slice_max_m);
        let mut slice = Self::empty(origin);
        let mut intervals = Vec::new();
        for (index, &end) in points.iter().enumerate() {
            intervals.clear();
            let hit = slab.clip(end, &mut intervals);
            slice.push(origin, end, index, &intervals, hit);
        }
        slice
    }

    fn empty(origin: [f64; 3]) -> Self {
        Self {
            sensor_xy: [origin[0], origin[1]],
            beams: Vec::new(),
            points: Vec::new(),
        }
    }

    /// Adds the parts `intervals` (beam parameters, in order) of the beam to point `index`; the
    /// last part carries the hit if the end point lies in the slice.
    fn push(
        &mut self,
        origin: [f64; 3],
        end: [f64; 3],
        index: usize,
        intervals: &[(f64, f64)],
        hit: bool,
    ) {
        let at = |t: f64| {
            [
                origin[0] + t * (end[0] - origin[0]),
                origin[1] + t * (end[1] - origin[1]),
            ]
        };
        let last = intervals.len().saturating_sub(1);
        for (k, &(t0, t1)) in intervals.iter().enumerate() {
            self.beams.push(SlicedBeam {
                start_xy: at(t0),
                end_xy: at(t1),
                hit: hit && k == last,
            });
        }
        if hit {
            self.points.push(SlicedPoint {
                x_m: end[0],
                y_m: end[1],
                index,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::features::grid::GridWindow;
    use crate::features::synthetic::{
        SceneBox, SyntheticGround, SyntheticLidar, SyntheticScene, SyntheticWorld,
    };
    use nalgebra::{Translation3, UnitQuaternion};
    use patchflow_dataset::{PointLabel, Pose};

    /// The thesis' flat road: these beams are checked against world heights.
    fn flat() -> FeatureParams {
        FeatureParams {
            ground: GroundMode::Flat,
            ..FeatureParams::default()
        }
    }

    fn sweep_with(points: Vec<[f32; 3]>) -> Sweep {
        let n = points.len();
        Sweep {
            world_from_sensor: Pose::from_parts(
                Translation3::new(5.0, -2.0, 1.73),
                UnitQuaternion::identity(),
            ),
            points_in_sensor: points,
            intensities: vec![0.5; n],
            labels: vec![PointLabel::default(); n],
            flow_in_world_mps: vec![[0.0; 3]; n],
            time_in_sweep_secs: vec![0.0; n],
            ..Sweep::default()
        }
    }

    #[test]
    fn a_beam_ending_in_the_slice_is_cut_where_it_enters_and_kept_as_a_hit() {
        // End 10 m ahead at z = 0.73 (world): enters the slice (z = 1.0) at 73 % of the way.
        let slice = HeightSlice::cut(&sweep_with(vec![[10.0, 0.0, -1.0]]), &flat()).unwrap();
        assert_eq!(slice.beams.len(), 1);
        let beam = slice.beams[0];
        assert!(beam.hit);
        assert!((beam.start_xy[0] - (5.0 + 7.3)).abs() < 1e-6, "{beam:?}");
        assert!((beam.end_xy[0] - 15.0).abs() < 1e-6);
        assert_eq!(slice.points[0].index, 0);
    }

    #[test]
    fn a_ground_beam_keeps_only_its_passage_through_the_slice_as_misses() {
        // End on the ground 17.3 m ahead: inside the slice between 7.3 m and 12.3 m.
        let slice = HeightSlice::cut(&sweep_with(vec![[17.3, 0.0, -1.73]]), &flat()).unwrap();
        let beam = slice.beams[0];
        assert!(!beam.hit && slice.points.is_empty());
        assert!((beam.start_xy[0] - 12.3).abs() < 1e-5 && (beam.end_xy[0] - 17.3).abs() < 1e-5);
    }

    #[test]
    fn beams_above_the_slice_are_dropped() {
        let slice = HeightSlice::cut(&sweep_with(vec![[20.0, 0.0, 0.5]]), &flat()).unwrap();
        assert!(slice.beams.is_empty() && slice.points.is_empty());
    }

    #[test]
    fn a_non_finite_point_is_an_error() {
        let err = HeightSlice::cut(&sweep_with(vec![[f32::NAN, 0.0, 0.0]]), &flat());
        assert!(err.is_err());
    }

    /// The slice's points on actor `id`, relative to the sensor, and their count.
    fn actor_points(slice: &HeightSlice, sweep: &Sweep, id: u16) -> Vec<[f64; 2]> {
        slice
            .points
            .iter()
            .filter(|p| sweep.labels[p.index].instance() == id)
            .map(|p| [p.x_m - slice.sensor_xy[0], p.y_m - slice.sensor_xy[1]])
            .collect()
    }

    fn centroid(points: &[[f64; 2]]) -> [f64; 2] {
        let n = points.len() as f64;
        let sum = points
            .iter()
            .fold([0.0, 0.0], |s, p| [s[0] + p[0], s[1] + p[1]]);
        [sum[0] / n, sum[1] / n]
    }

    #[test]
    fn a_car_on_a_raised_sloped_road_slices_like_the_same_car_on_flat_ground() {
        let car = SceneBox::car(3, [12.0, 2.0], 1.2, 0.0);
        let lidar = SyntheticLidar::with_resolution(64, 1800);
        let on = |ground: SyntheticGround| {
            let world = SyntheticWorld {
                scene: SyntheticScene {
                    boxes: vec![car.clone()],
                },
                ground,
                canopies: Vec::new(),
            };
            world.scan(&lidar, [0.0, 0.0], 0.0, 0)
        };
        let flat_sweep = on(SyntheticGround::default());
        let raised_sweep = on(SyntheticGround {
            base_m: 1.0,
            grade: [0.04, -0.02],
            ..SyntheticGround::default()
        });
        let params = FeatureParams::default();
        let level = HeightSlice::cut(&flat_sweep, &flat()).unwrap();
        let raised = HeightSlice::cut(&raised_sweep, &params).unwrap();
        let (a, b) = (
            actor_points(&level, &flat_sweep, 3),
            actor_points(&raised, &raised_sweep, 3),
        );
        assert!(a.len() > 50, "{} car points on flat ground", a.len());
        let ratio = b.len() as f64 / a.len() as f64;
        assert!(
            (0.85..1.15).contains(&ratio),
            "{} vs {} car points",
            b.len(),
            a.len()
        );
        let (ca, cb) = (centroid(&a), centroid(&b));
        assert!(
            (ca[0] - cb[0]).hypot(ca[1] - cb[1]) < 0.1,
            "{ca:?} vs {cb:?}"
        );
        // Within the map window only the car is in the slice: the raised road is not.
        let in_window = |slice: &HeightSlice| {
            let w = GridWindow::centred(slice.sensor_xy, params.half_extent_m, params.cell_m);
            slice
                .points
                .iter()
                .filter(|p| w.cell_of(p.x_m, p.y_m).is_some())
                .count()
        };
        assert_eq!(in_window(&raised), b.len());
        // The flat slice of the raised road is the road itself behind the sensor, not the car.
        let road_as_obstacle = HeightSlice::cut(&raised_sweep, &flat()).unwrap();
        assert!(in_window(&road_as_obstacle) > 10 * a.len());
    }

    #[test]
    fn on_flat_ground_the_estimated_slice_differs_from_the_flat_one_only_at_its_edges() {
        let world = SyntheticWorld {
            scene: SyntheticScene {
                boxes: vec![
                    SceneBox::car(1, [9.0, -3.0], 0.3, 5.0),
                    SceneBox::wall([-6.0, 8.0], 0.2, [12.0, 0.4, 3.0]),
                ],
            },
            ..SyntheticWorld::default()
        };
        let sweep = world.scan(
            &SyntheticLidar::with_resolution(64, 900),
            [0.0, 0.0],
            0.0,
            0,
        );
        let level = HeightSlice::cut(&sweep, &flat()).unwrap();
        let estimated = HeightSlice::cut(&sweep, &FeatureParams::default()).unwrap();
        let indices = |s: &HeightSlice| -> std::collections::BTreeSet<usize> {
            s.points.iter().map(|p| p.index).collect()
        };
        let (a, b) = (indices(&level), indices(&estimated));
        let changed: Vec<usize> = a.symmetric_difference(&b).copied().collect();
        // The estimate stands a centimetre or so high at the feet of the wall and the car.
        assert!(
            changed.len() * 20 < a.len(),
            "{} of {} changed",
            changed.len(),
            a.len()
        );
        for i in changed {
            let z = sweep.point_in_world(i).z;
            let from_edge = (z - 0.5).abs().min((z - 1.0).abs());
            assert!(from_edge < 0.02, "point {i} at {z:.3} m changed");
        }
    }
}
