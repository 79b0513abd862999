//! Tests of the bar check: what kind of miss each pattern of errors is read as.

use super::*;
use crate::bench::bar_markdown::bar_markdown;
use crate::methods::estimate::MotionEstimate;
use crate::scene::truth_at_scan::TruthAtScan;

/// 20 scans of a car at 8 m/s heading 90°, 20 m away with 100 points; `estimate(k)` gives
/// the held method's heading (degrees) and speed at scan k.
fn situation(estimate: impl Fn(usize) -> (f64, f64)) -> SituationResult {
    let truth: Vec<TruthAtScan> = (0..20)
        .map(|k| TruthAtScan {
            range_m: Some(20.0),
            target_points: Some(100),
            ..TruthAtScan::from_velocity(k, [0.0, 8.0])
        })
        .collect();
    let estimates = (0..20)
        .map(|k| {
            let (h, s) = estimate(k);
            let h = h.to_radians();
            Some(MotionEstimate::from_velocity([s * h.cos(), s * h.sin()]))
        })
        .collect();
    SituationResult {
        name: "situation4".into(),
        scans: 20,
        truth,
        methods: BTreeMap::from([(HELD, estimates)]),
    }
}

fn only_row(s: &SituationResult) -> BarRow {
    let scored = [(s.name.clone(), s.scans, s.metrics().unwrap())];
    bar_rows(std::slice::from_ref(s), &scored, &BTreeMap::new()).remove(0)
}

#[test]
fn small_errors_meet_the_bar() {
    let row = only_row(&situation(|k| {
        (90.0 + if k % 2 == 0 { 5.0 } else { -5.0 }, 8.3)
    }));
    assert!(row.met);
    assert!((row.heading_rmse_deg.unwrap() - 5.0).abs() < 1e-9);
    assert!((row.speed_bias_mps.unwrap() - 0.3).abs() < 1e-9);
}

#[test]
fn one_reversed_scan_is_read_as_an_outlier() {
    let row = only_row(&situation(|k| (if k == 7 { 270.0 } else { 90.0 }, 8.0)));
    assert!(!row.met, "one 180° error in 20 scans is an RMSE of 40°");
    // The worst tenth (2 scans) holds the whole squared error; without it the RMSE is 0.
    assert!((row.worst_tenth_share - 1.0).abs() < 1e-12);
    assert!(row.heading_rmse_without_worst_deg.unwrap() < 1e-9);
    let md = bar_markdown(&[row], "urban");
    assert!(md.contains("meets the bar in **0 of 1**"), "{md}");
    assert!(
        md.contains("heading: a few scans carry most of the error"),
        "{md}"
    );
}

#[test]
fn a_constant_offset_is_read_as_a_spread_misreading() {
    let row = only_row(&situation(|_| (130.0, 4.0)));
    assert!((row.worst_tenth_share - 0.1).abs() < 1e-12);
    assert!((row.speed_bias_mps.unwrap() + 4.0).abs() < 1e-9);
    let md = bar_markdown(&[row], "urban");
    assert!(md.contains("systematic misreading"), "{md}");
    assert!(md.contains("underestimated by 4.00 m/s"), "{md}");
    assert!(
        md.contains("misses on heading (40.0°) and speed (4.00 m/s)"),
        "{md}"
    );
}

#[test]
fn scans_right_after_the_target_was_hidden_are_counted_with_their_error() {
    let mut s = situation(|k| (if k == 5 { 180.0 } else { 90.0 }, 8.0));
    s.truth[4].target_points = Some(0);
    let row = only_row(&s);
    assert_eq!(row.after_hidden_scans, 1);
    assert!((row.after_hidden_share - 1.0).abs() < 1e-12);
}

#[test]
fn scans_that_saw_the_target_through_a_gap_are_counted_with_their_error() {
    let mut s = situation(|k| (if k >= 16 { 180.0 } else { 90.0 }, 8.0));
    for k in 14..20 {
        s.truth[k].target_hidden_ends = Some(2);
    }
    s.truth[13].target_hidden_ends = Some(1); // one end hidden: seen past an object, not through a gap
    let row = only_row(&s);
    assert_eq!(row.through_gap_scans, 6);
    assert!((row.through_gap_share - 1.0).abs() < 1e-12);
    let md = bar_markdown(&[row], "urban");
    assert!(md.contains("| 6, 100 % |"), "{md}");
    assert!(
        md.contains("100 % of it on the 6 scans that saw the target through a gap"),
        "{md}"
    );
}

#[test]
fn the_ideal_rung_decides_between_world_and_training() {
    let bad = only_row(&situation(|_| (130.0, 8.0)));
    let ideal = |h: f64| Scores {
        heading_rmse_deg: Some(h),
        speed_rmse_mps: Some(0.5),
        coverage: 1.0,
        scans: 20,
    };
    let world = BarRow {
        ideal: Some(ideal(10.0)),
        ..bad.clone()
    };
    let training = BarRow {
        ideal: Some(ideal(40.0)),
        ..bad
    };
    assert!(bar_markdown(&[world], "urban").contains("the world breaks them here"));
    assert!(bar_markdown(&[training], "urban").contains("they miss it on `ideal` too"));
}

#[test]
fn the_bar_reads_the_scores_it_is_given_instead_of_scoring_again() {
    let s = situation(|_| (90.0, 8.0));
    let mut metrics = s.metrics().unwrap();
    let held = metrics.get_mut(&HELD).unwrap();
    assert!(held.heading_rmse_deg.unwrap() < 1e-6);
    held.heading_rmse_deg = Some(40.0);
    let rows = bar_rows(
        std::slice::from_ref(&s),
        &[(s.name.clone(), s.scans, metrics)],
        &BTreeMap::new(),
    );
    assert_eq!(rows[0].heading_rmse_deg, Some(40.0));
    assert!(!rows[0].met, "40° is over the bar");
    // A situation the report did not score has no row.
    assert!(bar_rows(std::slice::from_ref(&s), &[], &BTreeMap::new()).is_empty());
}
