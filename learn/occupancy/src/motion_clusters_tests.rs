//! Tests of the motion clusters on synthetic scans: a sensor at the origin facing +y, a wall
//! along y = 10 and a car's face (a horizontal segment) in front of it.

use super::*;
use crate::{Beam, PlanarScan};

/// A scan at `t` from the origin: `beams` beams over 180° (from +x counter-clockwise) out to
/// `range_m`, against segments.
fn scan_of_segments(
    t: f64,
    beams: u32,
    range_m: f64,
    segments: &[([f64; 2], [f64; 2])],
) -> PlanarScan {
    let step = std::f64::consts::PI / f64::from(beams - 1);
    let beams = (0..beams)
        .map(|j| {
            let (s, c) = (step * f64::from(j)).sin_cos();
            // Ray–segment intersection: r·(c, s) = a + u·(b − a), 0 ≤ u ≤ 1.
            let range = segments
                .iter()
                .filter_map(|&(a, b)| {
                    let e = [b[0] - a[0], b[1] - a[1]];
                    let det = e[0] * s - e[1] * c;
                    if det.abs() < 1e-12 {
                        return None;
                    }
                    let r = (e[0] * a[1] - e[1] * a[0]) / det;
                    let u = (c * a[1] - s * a[0]) / det;
                    (r > 0.0 && (0.0..=1.0).contains(&u)).then_some(r)
                })
                .fold(f64::INFINITY, f64::min);
            let hit = range <= range_m;
            let r = if hit { range } else { range_m };
            Beam {
                start_m: [0.0, 0.0],
                end_m: [c * r, s * r],
                hit,
            }
        })
        .collect();
    PlanarScan {
        index: t as usize,
        stamp_secs: t,
        sensor_m: [0.0, 0.0],
        yaw_rad: std::f64::consts::FRAC_PI_2,
        beams,
    }
}

/// A scan at `t` of 721 beams over 180° (0.25° apart, out to 20 m) against horizontal segments
/// `(y, x_from, x_to)`.
fn scan(t: f64, segments: &[(f64, f64, f64)]) -> PlanarScan {
    let segments: Vec<([f64; 2], [f64; 2])> = segments
        .iter()
        .map(|&(y, x0, x1)| ([x0, y], [x1, y]))
        .collect();
    scan_of_segments(t, 721, 20.0, &segments)
}

const WALL: (f64, f64, f64) = (10.1, -12.0, 12.0);

fn clusters(a: &PlanarScan, b: &PlanarScan) -> Vec<MotionCluster> {
    let p = MotionClusterParams::default();
    let (ca, cb) = (
        ScanCells::from_scan(a, p.cell_m),
        ScanCells::from_scan(b, p.cell_m),
    );
    let scans = PairScans {
        first: &ca,
        second: &cb,
        before: None,
        after: None,
    };
    motion_clusters(&scans, b.index, &p)
}

#[test]
fn a_wall_seen_twice_is_one_stationary_object_and_nothing_moves() {
    let found = clusters(&scan(0.0, &[WALL]), &scan(1.0, &[WALL]));
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].kind, ClusterKind::Stationary);
    assert_eq!(found[0].velocity_mps, [0.0, 0.0]);
    assert!(found[0].cells_m.len() > 20);
}

#[test]
fn a_car_face_moving_two_metres_along_itself_gets_its_velocity_at_both_ends() {
    // The face spans x −3 … 1 at t = 0 and x −1 … 3 at t = 1: 2 m/s along +x.
    let found = clusters(
        &scan(0.0, &[WALL, (4.1, -3.0, 1.0)]),
        &scan(1.0, &[WALL, (4.1, -1.0, 3.0)]),
    );
    let moving: Vec<&MotionCluster> = found
        .iter()
        .filter(|c| c.kind != ClusterKind::Stationary && c.centroid_m[1] < 6.0)
        .collect();
    assert_eq!(moving.len(), 2, "{found:?}");
    for c in moving {
        assert_eq!(c.association, Association::AdjacentObject);
        let [vx, vy] = c.velocity_mps;
        assert!(
            (vx - 2.0).abs() <= 0.5 && vy.abs() < 0.3,
            "{:?}: {vx}, {vy}",
            c.kind
        );
    }
    let wall = found
        .iter()
        .find(|c| c.centroid_m[1] > 9.0)
        .expect("the wall");
    assert_eq!(wall.kind, ClusterKind::Stationary);
}

#[test]
fn an_object_that_jumps_past_its_own_length_is_paired_by_its_centroids() {
    // A 1 m face moves 5 m to the left in one second.
    let found = clusters(
        &scan(0.0, &[WALL, (4.1, 2.0, 3.0)]),
        &scan(1.0, &[WALL, (4.1, -3.0, -2.0)]),
    );
    let paired: Vec<&MotionCluster> = found
        .iter()
        .filter(|c| c.association == Association::Paired)
        .collect();
    assert_eq!(paired.len(), 2, "{found:?}");
    for c in paired {
        let [vx, vy] = c.velocity_mps;
        assert!((vx + 5.0).abs() < 0.3 && vy.abs() < 0.3, "{vx}, {vy}");
    }
}

#[test]
fn crossing_cars_are_paired_with_themselves_when_the_scans_around_bear_it_out() {
    // Two 1 m faces, 3 m apart across two lanes, pass each other at 6 m/s each way: between
    // scans 1 and 2 each car's vacated cells are nearer the other car's arrived cells (3.2 m)
    // than its own (6 m), so nearest first pairs across the lanes.
    let at = |t: f64| {
        let a = -9.0 + 6.0 * t; // near lane, +x
        let b = 8.0 - 6.0 * t; // far lane, −x
        scan(t, &[WALL, (4.1, a, a + 1.0), (7.1, b, b + 1.0)])
    };
    let p = MotionClusterParams::default();
    let cells: Vec<ScanCells> = (0..4)
        .map(|t| ScanCells::from_scan(&at(f64::from(t)), p.cell_m))
        .collect();
    let paired = |scans: PairScans<'_>| -> Vec<MotionCluster> {
        motion_clusters(&scans, 2, &p)
            .into_iter()
            .filter(|c| c.association == Association::Paired)
            .collect()
    };
    let lone = paired(PairScans {
        first: &cells[1],
        second: &cells[2],
        before: None,
        after: None,
    });
    assert!(
        lone.iter().any(|c| c.velocity_mps[1].abs() > 2.0),
        "nearest first pairs across the lanes: {lone:?}"
    );
    let borne_out = paired(PairScans {
        first: &cells[1],
        second: &cells[2],
        before: Some(&cells[0]),
        after: Some(&cells[3]),
    });
    assert_eq!(borne_out.len(), 4, "{borne_out:?}");
    for c in &borne_out {
        let lane_v = if c.centroid_m[1] < 6.0 { 6.0 } else { -6.0 };
        let [vx, vy] = c.velocity_mps;
        assert!(
            (vx - lane_v).abs() < 0.3 && vy.abs() < 0.3,
            "{:?} at {:?}: {vx}, {vy}",
            c.kind,
            c.centroid_m
        );
    }
}

#[test]
fn a_far_face_that_leaves_one_return_a_scan_is_paired_when_the_beams_are_sparser_than_a_cell() {
    // 91 beams 2° apart: 1.05 m apart at 30 m. A 0.6 m face, square to the beam, moves 8° (4.19
    // m) round the scanner at 30 m every second, on a beam each scan: one return, one cell.
    let face = |t: f64| {
        let (s, c) = (60f64 + 8.0 * t).to_radians().sin_cos();
        let centre = [30.0 * c, 30.0 * s];
        let half = [-0.3 * s, 0.3 * c];
        (
            [centre[0] - half[0], centre[1] - half[1]],
            [centre[0] + half[0], centre[1] + half[1]],
        )
    };
    let wall = ([-100.0, 50.0], [100.0, 50.0]);
    let p = MotionClusterParams::default();
    let cells: Vec<ScanCells> = (0..4)
        .map(|t| {
            let t = f64::from(t);
            ScanCells::from_scan(&scan_of_segments(t, 91, 60.0, &[wall, face(t)]), p.cell_m)
        })
        .collect();
    let scans = PairScans {
        first: &cells[1],
        second: &cells[2],
        before: Some(&cells[0]),
        after: Some(&cells[3]),
    };
    let paired: Vec<MotionCluster> = motion_clusters(&scans, 2, &p)
        .into_iter()
        .filter(|c| c.association == Association::Paired)
        .collect();
    assert_eq!(paired.len(), 2, "{paired:?}");
    // The chord from 68° to 76° at 30 m: 4.19 m along 162°.
    let (s, c) = 162f64.to_radians().sin_cos();
    for cl in &paired {
        assert_eq!(cl.cells_m.len(), 1);
        let [vx, vy] = cl.velocity_mps;
        assert!(
            (vx - 4.19 * c).abs() < 0.3 && (vy - 4.19 * s).abs() < 0.3,
            "{vx}, {vy}"
        );
    }
    // The same scans from a scanner whose beams are under a cell apart at 60 m (0.25°): there
    // one cell is an edge flickering.
    let denser = |map: &ScanCells| ScanCells {
        beam_step_rad: 0.25f64.to_radians(),
        ..map.clone()
    };
    let (first, second) = (denser(&cells[1]), denser(&cells[2]));
    let dense = PairScans {
        first: &first,
        second: &second,
        ..scans
    };
    assert!(
        motion_clusters(&dense, 2, &p)
            .iter()
            .all(|c| c.association != Association::Paired)
    );
}
