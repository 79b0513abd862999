//! Tests of `box_reference`: which faces place the box, where its centre lies, and which extents
//! it keeps.

use super::*;

const TOLERANCE_M: f64 = 1e-9;

/// The outline of a car heading +x whose rear is at `rear_x` and whose right side lies along
/// y = 3 m, as a sensor at the origin sees it: its rear face (2 m wide) and `side_m` of its right
/// side, a point every 0.25 m.
fn rear_and_side(rear_x: f64, side_m: f64) -> Vec<[f64; 2]> {
    let steps = (side_m / 0.25).round() as usize;
    let mut points: Vec<[f64; 2]> = (0..=steps)
        .map(|k| [rear_x + 0.25 * k as f64, 3.0])
        .collect();
    points.extend((1..=8).map(|k| [rear_x, 3.0 + 0.25 * k as f64]));
    points
}

fn assert_near(p: [f64; 2], expected: [f64; 2]) {
    let d = (p[0] - expected[0]).hypot(p[1] - expected[1]);
    assert!(d < TOLERANCE_M, "{p:?} is not {expected:?}");
}

/// The box after `scans` identical clusters.
fn after(scans: usize, points: &[[f64; 2]], previous: Option<BoxReference>) -> BoxReference {
    (0..scans)
        .fold(previous, |b, _| {
            BoxReference::facing(points, [0.0, 0.0], 0.0, b.as_ref())
        })
        .unwrap()
}

#[test]
fn a_car_driving_away_beside_the_sensor_is_placed_by_its_rear_and_its_near_side() {
    let points = rear_and_side(10.0, 4.0);
    let reference = after(1, &points, None);
    assert_eq!(reference.faces, [Face::Low, Face::Low]);
    // Its centre: 2 m ahead of the rear, 1 m beyond the near side.
    assert_near(reference.point(&points, 0.0).unwrap(), [12.0, 4.0]);
}

#[test]
fn a_car_level_with_the_sensor_is_placed_by_the_middle_of_its_near_side() {
    let points: Vec<[f64; 2]> = (0..=16).map(|k| [-2.0 + 0.25 * k as f64, 3.0]).collect();
    let reference = after(1, &points, None);
    assert_eq!(reference.faces, [Face::Middle, Face::Low]);
    assert_near(reference.point(&points, 0.0).unwrap(), [0.0, 3.0]);
}

#[test]
fn once_a_cars_length_was_seen_its_centre_lies_half_of_it_ahead_of_the_rear_that_shows() {
    let whole = after(1, &rear_and_side(10.0, 4.0), None);
    // Further away only the rear and half a metre of the side show.
    let rear = rear_and_side(30.0, 0.5);
    let reference = BoxReference::facing(&rear, [0.0, 0.0], 0.0, Some(&whole)).unwrap();
    assert_near(reference.point(&rear, 0.0).unwrap(), [32.0, 4.0]);
}

#[test]
fn the_centre_does_not_depend_on_where_the_points_are_dense() {
    let mut points = rear_and_side(10.0, 4.0);
    let reference = after(1, &points, None);
    let before = reference.point(&points, 0.0).unwrap();
    points.extend((0..50).map(|k| [10.0 + 0.01 * k as f64, 3.0]));
    assert_near(reference.point(&points, 0.0).unwrap(), before);
}

#[test]
fn a_box_keeps_the_largest_extent_it_was_shown() {
    let reference = after(1, &rear_and_side(10.0, 4.0), None);
    let reference = after(1, &rear_and_side(20.0, 1.0), Some(reference));
    assert!(
        (reference.extent_m[0] - 4.0).abs() < TOLERANCE_M,
        "{reference:?}"
    );
    assert!(
        (reference.extent_m[1] - 2.0).abs() < TOLERANCE_M,
        "{reference:?}"
    );
}

#[test]
fn no_points_give_no_box() {
    assert_eq!(BoxReference::facing(&[], [0.0, 0.0], 0.0, None), None);
    let reference = after(1, &rear_and_side(10.0, 4.0), None);
    assert_eq!(reference.point(&[], 0.0), None);
}

#[test]
fn the_measured_centre_lies_within_the_reach_the_tracker_gates_by() {
    // Outlines of many shapes and boxes of many extents and headings.
    for k in 0..200 {
        let side_m = 0.25 * (k % 17) as f64;
        let points: Vec<[f64; 2]> = rear_and_side(3.0 + 0.1 * k as f64, side_m)
            .into_iter()
            .map(|[x, y]| [x, y * (1.0 + 0.01 * (k % 7) as f64)])
            .collect();
        let centroid = [
            points.iter().map(|p| p[0]).sum::<f64>() / points.len() as f64,
            points.iter().map(|p| p[1]).sum::<f64>() / points.len() as f64,
        ];
        let heading = 0.13 * k as f64;
        let seen = rear_and_side(0.0, 0.3 * (k % 23) as f64);
        let previous = BoxReference::facing(&seen, [5.0, -4.0], heading, None);
        let reference = BoxReference::facing(&points, [0.0, 0.0], heading, previous.as_ref());
        let reach = measured_reach_m(reference.as_ref(), reach_m(&points, centroid));
        let centre = measured_centre(reference.as_ref(), Some(heading), &points, centroid);
        let off = (centre[0] - centroid[0]).hypot(centre[1] - centroid[1]);
        assert!(
            off <= reach + TOLERANCE_M,
            "shape {k}: {off} m beyond a reach of {reach} m"
        );
    }
    assert_eq!(measured_reach_m(None, 3.0), 0.0);
}
