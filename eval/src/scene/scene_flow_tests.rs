//! Tests of the scene-flow metrics: the zero-flow identities, hand-computed accuracies, the
//! three-way split and the speed buckets.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::*;

const DT: f64 = 0.1;

/// Random points of every class: half standing still, the others at 0.1-14 m/s in any direction.
fn random_truth(n: usize, seed: u64) -> Vec<([f64; 3], FlowClass)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|k| {
            let class = FlowClass::ALL[k % FlowClass::ALL.len()];
            let speed = if rng.random::<bool>() {
                0.0
            } else {
                rng.random_range(0.1..14.0)
            };
            let heading: f64 = rng.random_range(-3.1..3.1);
            let climb: f64 = rng.random_range(-0.05..0.05);
            let d = [
                speed * heading.cos() * DT,
                speed * heading.sin() * DT,
                speed * climb * DT,
            ];
            (d, class)
        })
        .collect()
}

#[test]
fn zero_flow_scores_exactly_one_normalised_and_its_epe3d_is_the_mean_true_displacement() {
    let truth = random_truth(5000, 1);
    // Two tallies merged, as scans are.
    let (mut a, mut b) = (SceneFlowTally::default(), SceneFlowTally::default());
    for (k, (d, class)) in truth.iter().enumerate() {
        let tally = if k < 2000 { &mut a } else { &mut b };
        tally.add([0.0; 3], *d, *class, DT);
    }
    a.merge(&b);
    let m = a.metrics();
    assert_eq!(m.points, 5000);
    assert_eq!(m.normalised_dynamic_epe, Some(1.0));
    let mean_displacement = truth
        .iter()
        .map(|(d, _)| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
        .sum::<f64>()
        / truth.len() as f64;
    assert!((m.epe3d_m.unwrap() - mean_displacement).abs() < 1e-12);
    // Its background-static EPE is the mean displacement of background points up to 0.5 m/s.
    let slow: Vec<f64> = truth
        .iter()
        .filter(|(_, class)| *class == FlowClass::Background)
        .map(|(d, _)| end_point_error([0.0; 3], *d))
        .filter(|&d| d <= DYNAMIC_SPEED_MPS * DT)
        .collect();
    let expected = slow.iter().sum::<f64>() / slow.len() as f64;
    assert!((m.epe_bg_static_m.unwrap() - expected).abs() < 1e-12);
}

#[test]
fn a_perfect_prediction_has_no_error_and_no_outlier() {
    let mut tally = SceneFlowTally::default();
    for (d, class) in random_truth(500, 2) {
        tally.add(d, d, class, DT);
    }
    let m = tally.metrics();
    assert_eq!(m.epe3d_m, Some(0.0));
    assert_eq!(
        (m.acc_strict, m.acc_relax, m.outliers),
        (Some(1.0), Some(1.0), Some(0.0))
    );
    assert_eq!(m.normalised_dynamic_epe, Some(0.0));
}

#[test]
fn accuracies_and_outliers_follow_the_absolute_or_relative_thresholds() {
    let mut tally = SceneFlowTally::default();
    let car = FlowClass::Car;
    // 1 m true move. Errors 0.04 m (strict), 0.08 m (relax only), 0.2 m (neither, outlier by
    // the 10 % relative error), 0.09 m on a 2 m move (strict by the 4.5 % relative error).
    tally.add([1.04, 0.0, 0.0], [1.0, 0.0, 0.0], car, DT);
    tally.add([1.08, 0.0, 0.0], [1.0, 0.0, 0.0], car, DT);
    tally.add([1.2, 0.0, 0.0], [1.0, 0.0, 0.0], car, DT);
    tally.add([0.0, 2.09, 0.0], [0.0, 2.0, 0.0], car, DT);
    let m = tally.metrics();
    assert_eq!(m.acc_strict, Some(0.5));
    assert_eq!(m.acc_relax, Some(0.75));
    assert_eq!(m.outliers, Some(0.25));
    assert!((m.epe3d_m.unwrap() - (0.04 + 0.08 + 0.2 + 0.09) / 4.0).abs() < 1e-12);
}

#[test]
fn the_three_way_epe_averages_its_three_groups_and_leaves_out_moving_background() {
    let mut tally = SceneFlowTally::default();
    // Foreground dynamic (1 m/s): errors 0.2 and 0.4; foreground static: 0.1; background
    // static: 0.0 and 0.3; background dynamic: 5.0 (ignored by the three-way EPE).
    tally.add([0.3, 0.0, 0.0], [0.1, 0.0, 0.0], FlowClass::Car, DT);
    tally.add([0.5, 0.0, 0.0], [0.1, 0.0, 0.0], FlowClass::Pedestrian, DT);
    tally.add([0.1, 0.0, 0.0], [0.0, 0.0, 0.0], FlowClass::Truck, DT);
    tally.add([0.0, 0.0, 0.0], [0.0, 0.0, 0.0], FlowClass::Background, DT);
    tally.add([0.0, 0.3, 0.0], [0.0, 0.0, 0.0], FlowClass::Background, DT);
    tally.add([5.1, 0.0, 0.0], [0.1, 0.0, 0.0], FlowClass::Background, DT);
    let m = tally.metrics();
    let close = |a: Option<f64>, b: f64| (a.unwrap() - b).abs() < 1e-12;
    assert!(close(m.epe_fg_dynamic_m, 0.3));
    assert!(close(m.epe_fg_static_m, 0.1));
    assert!(close(m.epe_bg_static_m, 0.15));
    assert!(close(m.epe_threeway_m, (0.3 + 0.1 + 0.15) / 3.0));
}

#[test]
fn dynamic_buckets_divide_the_error_by_the_mean_true_displacement_of_their_points() {
    let mut tally = SceneFlowTally::default();
    // Car: one bucket of two points moving 0.5 m with errors 0.1 and 0.3 → 0.2 / 0.5 = 0.4.
    // Cyclist: a point moving 2 m (overflow bucket) with error 1 → 0.5. Mean over classes 0.45.
    tally.add([0.6, 0.0, 0.0], [0.5, 0.0, 0.0], FlowClass::Car, DT);
    tally.add([0.8, 0.0, 0.0], [0.5, 0.0, 0.0], FlowClass::Car, DT);
    tally.add([3.0, 0.0, 0.0], [2.0, 0.0, 0.0], FlowClass::Cyclist, DT);
    // A standing car point off by 0.06 m: the static bucket, not the normalised score.
    tally.add([0.06, 0.0, 0.0], [0.0, 0.0, 0.0], FlowClass::Car, DT);
    let m = tally.metrics();
    assert!(
        (m.normalised_dynamic_epe.unwrap() - 0.45).abs() < 1e-12,
        "{m:?}"
    );
    assert!((m.bucketed_static_epe_m.unwrap() - 0.06).abs() < 1e-12);
}

#[test]
fn buckets_are_1_49_m_wide_up_to_one_metre_then_one_overflow() {
    assert_eq!(bucket_of(0.0), 0);
    assert_eq!(bucket_of(0.99 / 49.0), 0);
    assert_eq!(bucket_of(1.01 / 49.0), 1);
    assert_eq!(bucket_of(0.999), 48);
    assert_eq!(bucket_of(1.0), 49);
    assert_eq!(bucket_of(30.0), 49);
}

#[test]
fn an_empty_tally_has_no_scores() {
    let m = SceneFlowTally::default().metrics();
    assert_eq!(m.points, 0);
    assert!(
        m.epe3d_m.is_none() && m.epe_threeway_m.is_none() && m.normalised_dynamic_epe.is_none()
    );
}
