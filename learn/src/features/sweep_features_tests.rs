//! Tests of one sweep's motion features: maps, clusters, patches.

use super::*;
use crate::features::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};

/// A car driving away along the line of sight (+x) and a static wall off to the side; the
/// ego drives 0.5 m along +y between the sweeps.
fn car_and_wall() -> SweepFeatures {
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
        ..FeatureParams::default()
    };
    let f = SweepFeatures::compute(&prev, &curr, &params).unwrap();
    assert!(
        f.points()
            .iter()
            .all(|p| curr.labels[p.index].semantic() != 40)
    );
    f
}

fn mean_patch_weight(f: &SweepFeatures, on: impl Fn(&SlicedPoint) -> bool) -> f64 {
    let idx: Vec<usize> = (0..f.len()).filter(|&i| on(&f.points()[i])).collect();
    assert!(idx.len() > 20, "{} points", idx.len());
    let patches = f.heading_patches(&idx);
    patches.iter().map(Patch::mean_abs_difference).sum::<f64>() / patches.len() as f64
}

#[test]
fn a_car_on_the_line_of_sight_changes_the_map_far_more_than_a_static_wall() {
    let f = car_and_wall();
    let car = mean_patch_weight(&f, |p| p.x_m > 5.0);
    let wall = mean_patch_weight(&f, |p| p.y_m > 10.0);
    assert!(car >= 5.0 * wall, "car {car} vs wall {wall}");
}

#[test]
fn the_car_and_the_wall_form_separate_clusters() {
    let f = car_and_wall();
    assert_eq!(f.clusters().len(), 2);
    let car_cluster = f.cluster_of((0..f.len()).find(|&i| f.points()[i].x_m > 5.0).unwrap());
    for i in 0..f.len() {
        assert_eq!(f.cluster_of(i) == car_cluster, f.points()[i].x_m > 5.0);
    }
}

#[test]
fn the_bearing_points_from_the_sensor_to_the_point() {
    let f = car_and_wall();
    let i = (0..f.len()).find(|&i| f.points()[i].y_m > 10.0).unwrap();
    let p = f.points()[i];
    assert!((f.bearing_rad(i) - p.y_m.atan2(p.x_m)).abs() < 1e-12);
    let g = f.gabor(&f.heading_patch(i));
    assert_eq!(g.len(), 16);
    assert_eq!(
        f.feature_of(&f.speed_patch(i, 0.3), FeatureKind::Patch)
            .len(),
        242
    );
}

/// A car driving away at 10 m/s along the line of sight, the features with the thesis' patches
/// and with patches on maps of 0.20 m cells.
fn fast_car_both_ways() -> (SweepFeatures, SweepFeatures) {
    let scene = SyntheticScene {
        boxes: vec![SceneBox::car(7, [14.0, 0.0], 0.0, 10.0)],
    };
    let lidar = SyntheticLidar::with_resolution(64, 1800);
    let prev = scene.scan(&lidar, [0.0, 0.0], 0.0, 0);
    let curr = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
    let thesis = FeatureParams {
        half_extent_m: 25.0,
        ..FeatureParams::default()
    };
    let wide = FeatureParams {
        patch_cell_m: 0.2,
        ..thesis.clone()
    };
    (
        SweepFeatures::compute(&prev, &curr, &thesis).unwrap(),
        SweepFeatures::compute(&prev, &curr, &wide).unwrap(),
    )
}

#[test]
fn patch_maps_of_their_own_leave_the_maps_points_and_clusters_as_they_were() {
    let (thesis, wide) = fast_car_both_ways();
    assert_eq!(wide.points(), thesis.points());
    assert_eq!(wide.clusters().ids(), thesis.clusters().ids());
    assert_eq!(wide.difference_map(), thesis.difference_map());
    assert_eq!(wide.difference_map().window().cell_m, 0.10);
}

#[test]
fn a_patch_on_coarser_cells_holds_the_face_a_fast_car_left() {
    let (thesis, wide) = fast_car_both_ways();
    // The car's rear face moved 1 m between the sweeps. A 1.1 m heading patch centred on it
    // ends 0.55 m behind it; a 2.2 m one reaches the cells the face left (occupied, now free).
    let rear = (0..wide.len())
        .min_by(|&a, &b| {
            let key = |i: usize| wide.points()[i].y_m.abs() + wide.points()[i].x_m;
            key(a).total_cmp(&key(b))
        })
        .unwrap();
    let least = |p: &Patch| {
        p.values[..PATCH_LEN / 2]
            .iter()
            .copied()
            .fold(0.0, f64::min)
    };
    let (near, far) = (
        least(&thesis.heading_patch(rear)),
        least(&wide.heading_patch(rear)),
    );
    assert!(
        far < near - 0.2,
        "least difference: 2.2 m patch {far}, 1.1 m patch {near}"
    );
}

#[test]
fn the_estimator_predicts_once_per_cell_of_the_patch_maps() {
    let (thesis, wide) = fast_car_both_ways();
    let car = thesis.clusters().members(0);
    assert_eq!(thesis.patch_cell_samples(car), thesis.cell_samples(car));
    let (coarse, fine) = (
        wide.patch_cell_samples(car).len(),
        thesis.cell_samples(car).len(),
    );
    assert!(
        coarse < fine,
        "{coarse} samples on 0.20 m cells, {fine} on 0.10 m cells"
    );
}
