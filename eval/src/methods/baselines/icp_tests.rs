//! Tests of cluster ICP: exact, noisy and partial motions, degenerate clusters, known limits.

use super::*;
use crate::methods::baselines::rigid_motion::{icp_motion_estimate, icp_rigid_motion};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `n` points at random positions along the two visible sides (an L) of a 4.5 m × 1.8 m car,
/// as arc length `s` along the outline (0..4.5 the long side, 4.5..6.3 the short side).
fn random_car_outline(rng: &mut ChaCha8Rng, n: usize, corner: [f64; 2]) -> Vec<(f64, [f64; 2])> {
    (0..n)
        .map(|_| {
            let s: f64 = rng.random_range(0.0..6.3);
            let p = if s < 4.5 { [s, 0.0] } else { [4.5, s - 4.5] };
            (s, [corner[0] + p[0], corner[1] + p[1]])
        })
        .collect()
}

fn points(outline: &[(f64, [f64; 2])]) -> Vec<[f64; 2]> {
    outline.iter().map(|(_, p)| *p).collect()
}

fn moved(
    points: &[[f64; 2]],
    truth: &Isometry2<f64>,
    noise_m: f64,
    rng: &mut ChaCha8Rng,
) -> Vec<[f64; 2]> {
    points
        .iter()
        .map(|p| {
            let q = truth.transform_point(&Point2::new(p[0], p[1]));
            let mut jitter = || {
                if noise_m > 0.0 {
                    rng.random_range(-noise_m..noise_m)
                } else {
                    0.0
                }
            };
            [q.x + jitter(), q.y + jitter()]
        })
        .collect()
}

fn centroid_displacement_error(
    alignment: &IcpAlignment,
    source: &[[f64; 2]],
    truth: &Isometry2<f64>,
) -> f64 {
    let c = centroid_of(source).unwrap();
    let c = Point2::new(c[0], c[1]);
    (alignment.target_from_source.transform_point(&c) - truth.transform_point(&c)).norm()
}

fn random_motion(rng: &mut ChaCha8Rng) -> Isometry2<f64> {
    // Up to ±0.1 rad and ±1.5 m per scan: a car turning at 1 rad/s and driving 15 m/s at 10 Hz.
    let angle = rng.random_range(-0.1..0.1);
    Isometry2::new(
        Vector2::new(rng.random_range(-1.5..1.5), rng.random_range(-1.5..1.5)),
        angle,
    )
}

#[test]
fn icp_recovers_a_noise_free_rigid_motion_of_a_random_outline_to_1e9() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for _ in 0..10 {
        let source = points(&random_car_outline(&mut rng, 80, [20.0, -7.0]));
        let truth = random_motion(&mut rng);
        let target = moved(&source, &truth, 0.0, &mut rng);
        let a = align_icp(&source, &target, &IcpParams::default()).unwrap();
        assert!(a.converged && !a.degenerate);
        assert!((a.target_from_source.rotation.angle() - truth.rotation.angle()).abs() < 1e-9);
        assert!(centroid_displacement_error(&a, &source, &truth) < 1e-9);
    }
}

#[test]
fn icp_recovers_a_noisy_rigid_motion_within_2cm_and_half_a_degree() {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    for _ in 0..10 {
        let source = points(&random_car_outline(&mut rng, 80, [15.0, 5.0]));
        let truth = random_motion(&mut rng);
        // ±2 cm uniform noise on the target, about the lidar's range noise.
        let target = moved(&source, &truth, 0.02, &mut rng);
        let a = align_icp(&source, &target, &IcpParams::default()).unwrap();
        assert!(centroid_displacement_error(&a, &source, &truth) < 0.02);
        assert!(
            (a.target_from_source.rotation.angle() - truth.rotation.angle()).abs()
                < 0.5f64.to_radians()
        );
    }
}

#[test]
fn icp_recovers_the_motion_under_partial_overlap_within_10cm() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    for _ in 0..10 {
        // t−1 misses the first 0.8 m of the long side, t the last 0.5 m of the short side;
        // fresh random samples in both scans, ±2 cm noise.
        let source_outline = random_car_outline(&mut rng, 90, [-12.0, 8.0]);
        let source: Vec<[f64; 2]> = source_outline
            .iter()
            .filter(|(s, _)| *s > 0.8)
            .map(|(_, p)| *p)
            .collect();
        let target_outline = random_car_outline(&mut rng, 90, [-12.0, 8.0]);
        let kept: Vec<[f64; 2]> = target_outline
            .iter()
            .filter(|(s, _)| *s < 5.8)
            .map(|(_, p)| *p)
            .collect();
        let truth = random_motion(&mut rng);
        let target = moved(&kept, &truth, 0.02, &mut rng);
        for symmetric in [false, true] {
            let params = IcpParams {
                symmetric,
                ..IcpParams::default()
            };
            let a = align_icp(&source, &target, &params).unwrap();
            let error_m = centroid_displacement_error(&a, &source, &truth);
            assert!(error_m < 0.10, "symmetric {symmetric}: {error_m} m, {a:?}");
        }
    }
}

#[test]
fn the_found_rotation_is_proper_even_for_a_collinear_cluster() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let source: Vec<[f64; 2]> = (0..30).map(|i| [i as f64 * 0.1, 2.0]).collect();
    let target = moved(
        &source,
        &Isometry2::new(Vector2::new(0.5, 0.0), 0.02),
        0.01,
        &mut rng,
    );
    let a = align_icp(&source, &target, &IcpParams::default()).unwrap();
    let r = a.target_from_source.rotation.to_rotation_matrix();
    assert!((r.matrix().determinant() - 1.0).abs() < 1e-12);
}

#[test]
fn fewer_than_three_points_give_the_centroid_translation() {
    let a = align_icp(
        &[[0.0, 0.0], [1.0, 0.0]],
        &[[2.0, 1.0], [3.0, 1.0]],
        &IcpParams::default(),
    )
    .unwrap();
    assert!(a.degenerate);
    let v = a.velocity_of([0.5, 0.0], 0.1);
    assert!((v[0] - 20.0).abs() < 1e-9 && (v[1] - 10.0).abs() < 1e-9);
}

#[test]
fn an_empty_cluster_or_a_bad_interval_gives_no_estimate() {
    assert!(align_icp(&[], &[[0.0, 0.0]], &IcpParams::default()).is_none());
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let c = points(&random_car_outline(&mut rng, 20, [0.0, 0.0]));
    assert!(icp_motion_estimate(&c, &c, 0.0, &IcpParams::default()).is_none());
}

#[test]
fn non_finite_points_are_ignored() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let source = points(&random_car_outline(&mut rng, 60, [3.0, 3.0]));
    let truth = Isometry2::translation(0.5, 0.2);
    let mut target = moved(&source, &truth, 0.0, &mut rng);
    target.push([f64::NAN, 1.0]);
    target.push([f64::INFINITY, 0.0]);
    let a = align_icp(&source, &target, &IcpParams::default()).unwrap();
    assert!(centroid_displacement_error(&a, &source, &truth) < 1e-9);
    assert!(align_icp(&[[f64::NAN, 0.0]], &source, &IcpParams::default()).is_none());
}

#[test]
fn velocity_is_the_centroid_displacement_not_the_translation() {
    // A pure rotation about the cluster's own centre, far from the origin, means no motion,
    // although the transform's translation is large.
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let source = points(&random_car_outline(&mut rng, 80, [30.0, 30.0]));
    let c = centroid_of(&source).unwrap();
    let about_centre =
        Isometry2::new(Vector2::new(c[0], c[1]), 0.08) * Isometry2::translation(-c[0], -c[1]);
    let target = moved(&source, &about_centre, 0.0, &mut rng);
    let alignment = align_icp(&source, &target, &IcpParams::default()).unwrap();
    assert!(alignment.target_from_source.translation.vector.norm() > 1.0);
    let e = icp_motion_estimate(&source, &target, 0.1, &IcpParams::default()).unwrap();
    assert!(e.speed_mps < 1e-6, "{e:?}");
}

#[test]
fn a_regularly_sampled_line_can_trap_point_to_point_icp_in_a_local_minimum() {
    // Documents a known limit (not a wish): on an evenly spaced 0.1 m grid, a 0.05 rad turn
    // leaves ICP at a fixed point with a centimetre-level residual instead of zero.
    let mut source: Vec<[f64; 2]> = (0..45).map(|i| [20.0 + i as f64 * 0.1, -7.0]).collect();
    source.extend((1..18).map(|i| [24.5, -7.0 + i as f64 * 0.1]));
    let truth = Isometry2::new(Vector2::new(0.9, 0.4), 0.05);
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    let target = moved(&source, &truth, 0.0, &mut rng);
    let a = align_icp(&source, &target, &IcpParams::default()).unwrap();
    assert!(a.converged);
    assert!(a.inlier_rms_m > 0.01 && a.inlier_rms_m < 0.05, "{a:?}");
}

#[test]
fn rigid_motion_moves_each_current_point_back_to_where_it_came_from() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let source = points(&random_car_outline(&mut rng, 80, [12.0, -4.0]));
    let truth = Isometry2::new(Vector2::new(0.6, 0.2), 0.04);
    let target = moved(&source, &truth, 0.0, &mut rng);
    let motion = icp_rigid_motion(&source, &target, 0.1, &IcpParams::default()).unwrap();
    for (p, q) in source.iter().zip(&target) {
        let v = motion.velocity_of_current_point(*q);
        assert!((v[0] - (q[0] - p[0]) / 0.1).abs() < 1e-6, "{v:?}");
        assert!((v[1] - (q[1] - p[1]) / 0.1).abs() < 1e-6, "{v:?}");
    }
    assert_eq!(
        Some(motion.estimate),
        icp_motion_estimate(&source, &target, 0.1, &IcpParams::default())
    );
}

#[test]
fn a_large_cluster_pairs_the_same_points_in_parallel_blocks_as_one_by_one() {
    let target: Vec<[f64; 2]> = (0..3000)
        .map(|i| {
            let a = i as f64 * 0.003;
            [10.0 * a.cos() + 0.01 * (i % 7) as f64, 4.0 * a.sin()]
        })
        .collect();
    let source: Vec<[f64; 2]> = target.iter().map(|p| [p[0] + 0.05, p[1] - 0.02]).collect();
    let tree = ImmutableKdTree::<f64, 2>::new_from_slice(&target).unwrap();
    let transform = Isometry2::new(Vector2::new(-0.04, 0.01), 0.002);
    let (paired_source, paired_target) = correspondences(&source, &target, &tree, &transform, 0.03);
    let one_by_one: (Vec<[f64; 2]>, Vec<[f64; 2]>) = source
        .iter()
        .filter_map(|p| {
            let moved = transform.transform_point(&Point2::new(p[0], p[1]));
            let nearest = tree
                .query(&[moved.x, moved.y])
                .nearest_one::<SquaredEuclidean<f64>>()
                .execute();
            (nearest.distance <= 0.03 * 0.03).then(|| (*p, target[nearest.item as usize]))
        })
        .unzip();
    assert!(source.len() >= PARALLEL_MIN_POINTS);
    assert!(!paired_source.is_empty() && paired_source.len() < source.len());
    assert_eq!((paired_source, paired_target), one_by_one);
}
