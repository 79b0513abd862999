//! Tests of the height slice: above the flat road and above the estimated ground.

use super::*;
use crate::SweepFeatures;
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

/// A car and a wall on flat ground, scanned once from the origin at 64 × 900 beams.
fn parked_car_and_wall_on_flat_ground() -> Sweep {
    let world = SyntheticWorld {
        scene: SyntheticScene {
            boxes: vec![
                SceneBox::car(1, [9.0, -3.0], 0.3, 5.0),
                SceneBox::wall([-6.0, 8.0], 0.2, [12.0, 0.4, 3.0]),
            ],
        },
        ..SyntheticWorld::default()
    };
    world.scan(
        &SyntheticLidar::with_resolution(64, 900),
        [0.0, 0.0],
        0.0,
        0,
    )
}

#[test]
fn on_flat_ground_the_estimated_slice_differs_from_the_flat_one_only_at_its_edges() {
    let sweep = parked_car_and_wall_on_flat_ground();
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

/// A car driving away along the line of sight and a static wall off to the side on flat ground
/// (the scene of `sweep_features`' tests), cut above the given ground; and the current sweep.
fn car_and_wall_above(ground: GroundMode) -> (SweepFeatures, Sweep) {
    let scene = SyntheticScene {
        boxes: vec![
            SceneBox::car(7, [14.0, 0.0], 0.0, 6.0),
            SceneBox::wall([0.0, 12.0], 0.0, [10.0, 0.4, 2.5]),
        ],
    };
    let lidar = SyntheticLidar::with_resolution(64, 1800);
    let prev = scene.scan(&lidar, [0.0, -0.5], 0.0, 0);
    let curr = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
    let params = FeatureParams {
        half_extent_m: 25.0,
        ground,
        ..FeatureParams::default()
    };
    (SweepFeatures::compute(&prev, &curr, &params).unwrap(), curr)
}

#[test]
fn on_flat_ground_the_estimated_ground_gives_the_clusters_of_the_flat_one() {
    let ((flat, sweep), (estimated, _)) = (
        car_and_wall_above(GroundMode::Flat),
        car_and_wall_above(GroundMode::Estimated),
    );
    // Each cluster as the set of its points' indices into the sweep.
    let clusters = |f: &SweepFeatures| -> Vec<std::collections::BTreeSet<usize>> {
        (0..f.clusters().len())
            .map(|c| {
                let members = f.clusters().members(c).iter();
                members.map(|&i| f.points()[i].index).collect()
            })
            .collect()
    };
    let (a, b) = (clusters(&flat), clusters(&estimated));
    assert_eq!(a.len(), b.len());
    for (ca, cb) in a.iter().zip(&b) {
        assert!(ca.intersection(cb).count() * 10 > 9 * ca.len());
        // The estimate stands a centimetre high at the foot of the wall: a ring of the wall at
        // 1.0001 m joins the slice. Nothing else changes sides.
        for &i in ca.symmetric_difference(cb) {
            let z = sweep.point_in_world(i).z;
            let from_edge = (z - 0.5).abs().min((z - 1.0).abs());
            assert!(from_edge < 0.02, "point {i} at {z:.4} m changed clusters");
        }
    }
}

#[test]
fn the_slice_places_points_with_the_estimated_pose_not_the_truth() {
    // The ego believes it stands 1.5 m east and 0.8 m north of where it is: the slice (what the
    // car's perception sees) must sit where the estimate puts it, 1.5 m / 0.8 m off the truth.
    let mut sweep = sweep_with(vec![[10.0, 0.0, -1.0]]);
    sweep.estimated_world_from_sensor = Some(Pose::from_parts(
        Translation3::new(6.5, -1.2, 1.73),
        UnitQuaternion::identity(),
    ));
    for params in [flat(), FeatureParams::default()] {
        let slice = HeightSlice::cut(&sweep, &params).unwrap();
        assert!(
            (slice.sensor_xy[0] - 6.5).abs() < 1e-9 && (slice.sensor_xy[1] + 1.2).abs() < 1e-9,
            "{:?}",
            slice.sensor_xy
        );
        if params.ground == GroundMode::Estimated {
            continue; // one point is no ground to slice above; its origin is checked
        }
        let point = slice.points[0];
        assert!(
            (point.x_m - 16.5).abs() < 1e-6 && (point.y_m + 1.2).abs() < 1e-6,
            "{point:?}"
        );
    }
}

#[test]
fn the_slice_above_the_estimated_ground_is_the_same_on_one_thread_and_on_two() {
    // More points than one parallel task takes, so the slice is joined from several runs.
    let sweep = parked_car_and_wall_on_flat_ground();
    assert!(sweep.points_in_sensor.len() > 3 * TASK_POINTS);
    let cut = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| HeightSlice::cut(&sweep, &FeatureParams::default()).unwrap())
    };
    let (one, two) = (cut(1), cut(2));
    assert_eq!(one, two);
    // The serial loop the runs replace, point by point.
    let params = FeatureParams::default();
    let points = points_in_world(&sweep).unwrap();
    let o = sweep.estimated_pose().translation.vector;
    let ground = GroundGrid::from_points_in_world(&points, [o.x, o.y], params.half_extent_m);
    let origin = [o.x, o.y, o.z];
    let slab = SlabAboveGround::new(&ground, origin, params.slice_min_m, params.slice_max_m);
    let mut serial = HeightSlice::empty(origin);
    let mut intervals = Vec::new();
    for (index, &end) in points.iter().enumerate() {
        intervals.clear();
        let hit = slab.clip(end, &mut intervals);
        serial.push(origin, end, index, &intervals, hit);
    }
    assert_eq!(one, serial);
    assert!(!one.points.is_empty());
    // Every point keeps its own index, in order.
    assert!(one.points.windows(2).all(|w| w[0].index < w[1].index));
}
