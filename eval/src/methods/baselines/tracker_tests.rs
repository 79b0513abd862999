//! Tests of the multi-target tracker (`tracker.rs`).

use super::*;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

const DT: f64 = 0.1;

fn tracker() -> MultiTargetTracker {
    MultiTargetTracker::new(TrackerParams::default()).unwrap()
}

#[test]
fn one_track_id_survives_a_crossing_of_two_targets_at_different_speeds() {
    // A drives +x at 10 m/s along y = 0; B drives +y at 3 m/s along x = 0.5; their paths
    // cross near (0.5, 0) with the cars about a metre apart at the closest point.
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    let mut t = tracker();
    let (mut ids_a, mut ids_b) = (Vec::new(), Vec::new());
    for k in 0..40 {
        let time = k as f64 * DT;
        let mut noise = || rng.random_range(-0.1..0.1);
        let a = [-15.0 + 10.0 * time + noise(), noise()];
        let b = [0.5 + noise(), -5.5 + 3.0 * time + noise()];
        // Alternate the cluster order so list position carries no information.
        let (centroids, ia, ib) = if k % 2 == 0 {
            (vec![a, b], 0, 1)
        } else {
            (vec![b, a], 1, 0)
        };
        let assigned = t.step(k, time, &centroids).unwrap();
        ids_a.push(assigned[ia].unwrap());
        ids_b.push(assigned[ib].unwrap());
    }
    assert!(ids_a.iter().all(|id| *id == ids_a[0]), "{ids_a:?}");
    assert!(ids_b.iter().all(|id| *id == ids_b[0]), "{ids_b:?}");
    assert_ne!(ids_a[0], ids_b[0]);
    let vel_a = t.track(ids_a[0]).unwrap().filter.velocity();
    assert!((vel_a[0] - 10.0).abs() < 1.0, "{vel_a:?}");
}

#[test]
fn a_far_clutter_cluster_is_gated_out_of_a_confirmed_track() {
    let mut t = tracker();
    let mut target_id = None;
    for k in 0..10 {
        let target = [5.0 * k as f64 * DT, 0.0];
        let assigned = t.step(k, k as f64 * DT, &[target]).unwrap();
        target_id = assigned[0];
    }
    // The target vanishes for one scan while clutter appears 8 m ahead of it.
    let clutter = t.step(10, 1.0, &[[13.0, 0.0]]).unwrap();
    assert_ne!(clutter[0], target_id);
    let after = t.step(11, 1.1, &[[5.5, 0.0]]).unwrap();
    assert_eq!(after[0], target_id);
    // The clutter's tentative track died at its first miss.
    assert_eq!(t.tracks().len(), 1);
}

#[test]
fn tracks_are_confirmed_after_three_hits_and_ended_after_more_than_three_misses() {
    let mut t = tracker();
    let mut statuses = Vec::new();
    for k in 0..4 {
        let assigned = t.step(k, k as f64 * DT, &[[k as f64 * 0.4, 1.0]]).unwrap();
        statuses.push(t.track(assigned[0].unwrap()).unwrap().status);
    }
    assert_eq!(
        statuses,
        [
            TrackStatus::Tentative,
            TrackStatus::Tentative,
            TrackStatus::Confirmed,
            TrackStatus::Confirmed
        ]
    );
    for k in 4..7 {
        t.step(k, k as f64 * DT, &[]).unwrap();
        assert_eq!(t.tracks().len(), 1, "coasting at scan {k}");
    }
    t.step(7, 0.7, &[]).unwrap();
    assert!(t.tracks().is_empty());
}

#[test]
fn a_measured_velocity_keeps_a_cluster_with_the_track_moving_its_way() {
    use crate::methods::baselines::velocity_measurement::{GpVelocityNoise, VelocityMeasurement};
    let noise = GpVelocityNoise::default();
    let moving = VelocityMeasurement::from_heading_speed(0.0, 0.0, 8.0, 0.0, &noise);
    let at_rest = VelocityMeasurement::at_rest(&noise);
    // A drives +x at 8 m/s; B stands 0.5 m beyond where A will be at scan 10. At scan 10, B
    // is hidden and A's cluster lies 0.3 m ahead of A's prediction, 0.2 m short of B's.
    let run = |velocity_at_10: Option<VelocityMeasurement>| {
        let mut t = tracker();
        let (mut a, mut b) = (None, None);
        for k in 0..10 {
            let time = k as f64 * DT;
            let centroids = [[8.0 * time, 0.0], [8.5, 0.0]];
            let assigned = t
                .step_measured(k, time, &centroids, &[Some(moving), Some(at_rest)])
                .unwrap();
            (a, b) = (assigned[0], assigned[1]);
        }
        let taken = t
            .step_measured(10, 1.0, &[[8.3, 0.0]], &[velocity_at_10])
            .unwrap();
        (taken[0], a, b)
    };
    let (taken, a, b) = run(None);
    assert_eq!(taken, b, "by position alone the nearer track takes it");
    let (taken, a_again, _) = run(Some(moving));
    assert_eq!((taken, a_again), (a, a), "its velocity gives it back to A");
}

#[test]
fn a_time_stamp_that_does_not_increase_is_an_error() {
    let mut t = tracker();
    t.step(0, 1.0, &[[0.0, 0.0]]).unwrap();
    assert!(t.step(1, 1.0, &[[0.0, 0.0]]).is_err());
}

/// A 12 m truck driving +x at 7 m/s along y = 20 m (the sensor at the origin) comes out from
/// behind a parked car whose edge hides everything at x < 0: per scan, the centroid of its visible
/// part, its two ends (smallest bearing first: the front, then the rear end) and the true
/// centroid. The rear end is hidden while the truck emerges (16 scans), then it shows whole.
fn emerging_truck(scans: usize) -> Vec<([f64; 2], [ObjectEnd; 2], [f64; 2])> {
    (0..scans)
        .map(|k| {
            let front = 1.0 + 0.7 * k as f64;
            let rear = front - 12.0;
            let hidden = rear < 0.0;
            let visible_rear = rear.max(0.0);
            let ends = [
                ObjectEnd {
                    xy: [front, 20.0],
                    hidden: false,
                },
                ObjectEnd {
                    xy: [visible_rear, 20.0],
                    hidden,
                },
            ];
            (
                [(front + visible_rear) / 2.0, 20.0],
                ends,
                [front - 6.0, 20.0],
            )
        })
        .collect()
}

/// Tracks [`emerging_truck`] with or without its ends; the track's speed and position per scan.
fn track_emerging_truck(with_ends: bool, scans: usize) -> Vec<(f64, [f64; 2])> {
    let mut t = tracker();
    let mut id = None;
    emerging_truck(scans)
        .into_iter()
        .enumerate()
        .map(|(k, (centroid, ends, _))| {
            let outline = ClusterOutline {
                ends: Some(ends),
                points_xy: &[],
            };
            let outlines = if with_ends { vec![outline] } else { vec![] };
            let taken = t
                .step_anchored(k, k as f64 * DT, &[centroid], &outlines, &[], [0.0, 0.0])
                .unwrap();
            assert!(
                id.is_none_or(|id| taken[0] == Some(id)),
                "scan {k}: track lost"
            );
            id = taken[0];
            let track = t.track(id.unwrap()).unwrap();
            let speed = track.filter.estimate().map_or(0.0, |e| e.speed_mps);
            (speed, track.filter.position())
        })
        .collect()
}

#[test]
fn a_truck_coming_out_from_behind_a_parked_car_is_tracked_at_its_own_speed() {
    // Its centroid moves at 3.5 m/s while it emerges; measured at its visible front end, the
    // track reads 7 m/s by the end of the emergence (scan 15) and the centroid track does not.
    let anchored = track_emerging_truck(true, 16);
    let centroid_only = track_emerging_truck(false, 16);
    assert!((anchored[15].0 - 7.0).abs() < 0.5, "{anchored:?}");
    assert!(centroid_only[15].0 < 5.0, "{centroid_only:?}");
}

#[test]
fn once_the_whole_truck_shows_its_track_is_back_on_the_centroid_at_its_speed() {
    let truth = emerging_truck(30);
    let track = track_emerging_truck(true, 30);
    for k in 17..30 {
        let (speed, position) = track[k];
        let true_centroid = truth[k].2;
        assert!((speed - 7.0).abs() < 0.5, "scan {k}: {speed} m/s");
        let off_m = (position[0] - true_centroid[0]).hypot(position[1] - true_centroid[1]);
        assert!(off_m < 0.3, "scan {k}: {off_m} m from the centroid");
    }
}

/// The outline of a 10 m × 2.5 m bus driving −x at 7 m/s, `time` seconds after its front was at
/// x = 25 m, its near side along y = 4 m, as a sensor at the origin samples it: one return per
/// 0.5° of bearing on the near side (densest where the side is nearest), and its front or its rear
/// face every 0.1 m while that faces the sensor.
fn passing_bus(time: f64) -> Vec<[f64; 2]> {
    let front = 25.0 - 7.0 * time;
    let rear = front + 10.0;
    let mut points: Vec<[f64; 2]> = (-178..=178)
        .map(|k| [4.0 * (k as f64 * 0.5f64.to_radians()).tan(), 4.0])
        .filter(|p| (front..=rear).contains(&p[0]))
        .collect();
    let face = (front > 0.0)
        .then_some(front)
        .or((rear < 0.0).then_some(rear));
    if let Some(x) = face {
        points.extend((1..=25).map(|k| [x, 4.0 + 0.1 * k as f64]));
    }
    points
}

/// The track's speed per scan on [`passing_bus`], measured by the clusters' outlines or by their
/// centroids alone.
fn track_passing_bus(with_outline: bool) -> Vec<f64> {
    let mut t = tracker();
    (0..60)
        .map(|k| {
            let points = passing_bus(k as f64 * DT);
            let centroid = crate::methods::observation::centroid_of(&points).unwrap();
            let outline = ClusterOutline {
                ends: None,
                points_xy: &points,
            };
            let outlines = if with_outline { vec![outline] } else { vec![] };
            let taken = t
                .step_anchored(k, k as f64 * DT, &[centroid], &outlines, &[], [0.0, 0.0])
                .unwrap();
            let track = t.track(taken[0].unwrap()).unwrap();
            track.filter.estimate().map_or(0.0, |e| e.speed_mps)
        })
        .collect()
}

#[test]
fn a_bus_passing_beside_the_sensor_is_tracked_at_its_speed_by_its_box_not_its_dense_side() {
    let worst = |speeds: &[f64]| {
        speeds[20..]
            .iter()
            .map(|s| (s - 7.0).abs())
            .fold(0.0, f64::max)
    };
    let by_box = track_passing_bus(true);
    let by_centroid = track_passing_bus(false);
    // The centroid stays with the dense part beside the sensor while the bus passes, and the
    // track's speed drops by metres per second; the box's centre moves with the bus.
    assert!(worst(&by_box) < 0.3, "{by_box:?}");
    assert!(worst(&by_centroid) > 1.5, "{by_centroid:?}");
}
