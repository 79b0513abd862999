//! Tests of GP-KF's report rules: when a track's heading is settled or known well enough to
//! report ([`GpTrustFilter::heading_settled`], [`GpTrustFilter::reported_heading_known`]), and
//! which learned readings agree with a track.

use super::*;

#[test]
fn a_track_started_on_one_gp_reading_does_not_report_however_tight_the_gp_says_it_is() {
    let noise = GpVelocityNoise::default();
    let mut filter = GpTrustFilter::start([0.0, 0.0], KalmanParams::default()).unwrap();
    let reading = VelocityMeasurement::from_heading_speed(0.0, 1e-6, 8.0, 1e-6, &noise);
    filter.update_velocity(&reading).unwrap();
    // The filter holds the GP's motion (the state starts from it) ...
    assert!(filter.estimate().is_some());
    // ... but the mixture's heading is not known to within 12.5° yet.
    assert!(!filter.heading_settled());
}

#[test]
fn a_track_reports_its_likeliest_mode_once_the_mixture_knows_the_heading_within_the_bar() {
    // Two scans of an 8 m/s car read by the GP to 5° or to 20°: on the first the modes disagree
    // (the trusted one adds the GP's persistent error, the unreliable one ignores the reading),
    // so the mixture's heading is wider than the 25° bar whatever the GP states; on the second
    // the mixture is within the bar and the likeliest mode reports where it states its heading to
    // 12.5° (5°: mixture 14°, reported 8°).
    let noise = GpVelocityNoise::default();
    for (heading_std_deg, known) in [(5.0_f64, true), (20.0, false)] {
        let mut filter = GpTrustFilter::start([0.0, 0.0], KalmanParams::default()).unwrap();
        assert!(!filter.reported_heading_known(), "no learned reading yet");
        let var = heading_std_deg.to_radians().powi(2);
        let reading = VelocityMeasurement::from_heading_speed(0.0, var, 8.0, 0.25, &noise);
        filter.update_velocity(&reading).unwrap();
        if known {
            let e = filter.estimate().unwrap();
            assert!(
                heading_within_report_bar(&e),
                "the likeliest mode is tight: {e:?}"
            );
        }
        assert!(
            !filter.reported_heading_known(),
            "{heading_std_deg}°, one reading"
        );
        TrackFilter::predict(&mut filter, DT);
        TrackFilter::update(&mut filter, [0.8, 0.0]).unwrap();
        filter.update_velocity(&reading).unwrap();
        assert_eq!(
            filter.reported_heading_known(),
            known,
            "{heading_std_deg}°, two readings"
        );
        assert!(
            !filter.heading_settled(),
            "the mixture has not settled to 12.5°"
        );
    }
}

#[test]
fn a_track_whose_gp_and_centroids_agree_reports_within_five_scans() {
    let noise = GpVelocityNoise::default();
    let z = centroids(5, 4);
    let mut filter = GpTrustFilter::start(z[0], KalmanParams::default()).unwrap();
    let reading = VelocityMeasurement::from_heading_speed(0.0, 0.0, 8.0, 0.0, &noise);
    filter.update_velocity(&reading).unwrap();
    for zk in &z[1..] {
        TrackFilter::predict(&mut filter, DT);
        TrackFilter::update(&mut filter, *zk).unwrap();
        filter.update_velocity(&reading).unwrap();
    }
    assert!(filter.heading_settled());
    let e = filter.estimate().unwrap();
    assert!(e.heading_rad.to_degrees().abs() < 5.0, "{e:?}");
}

#[test]
fn a_track_without_gp_readings_does_not_report_on_two_centroids() {
    // Two centroids 0.8 m apart with 0.5 m of noise each: the heading is not settled.
    let mut filter = GpTrustFilter::start([0.0, 0.0], KalmanParams::default()).unwrap();
    TrackFilter::predict(&mut filter, DT);
    TrackFilter::update(&mut filter, [0.8, 0.0]).unwrap();
    assert!(!filter.heading_settled());
}

#[test]
fn a_track_without_learned_readings_does_not_report_however_many_centroids_agree() {
    // Twenty centroids on a straight line at 8 m/s settle a centroid filter's heading, but no GP
    // or classifier reading was fused: that is KF-AUTO's estimate, not GP-KF's.
    let mut filter = settled_on_centroids();
    assert!(filter.estimate().is_some());
    assert!(!filter.heading_settled());
    // One GP reading that agrees, and the settled centroids let it report.
    let noise = GpVelocityNoise::default();
    let reading = VelocityMeasurement::from_heading_speed(0.0, 0.01, 8.0, 0.25, &noise);
    filter.update_velocity(&reading).unwrap();
    assert!(filter.heading_settled());
}

/// A track settled by twenty centroids of a car driving +x at 8 m/s, no learned reading fused.
fn settled_on_centroids() -> GpTrustFilter {
    let z = centroids(20, 8);
    let mut filter = GpTrustFilter::start(z[0], KalmanParams::default()).unwrap();
    for zk in &z[1..] {
        TrackFilter::predict(&mut filter, DT);
        TrackFilter::update(&mut filter, *zk).unwrap();
    }
    filter
}

#[test]
fn a_track_whose_only_learned_reading_contradicts_its_centroids_does_not_report() {
    // A track chained through clutter moves as its jumps do; the GP reads the object it then
    // takes 110° away from it, stated to 10°. The mixture follows the centroids (the reading is
    // taken as unreliable) and knows its heading tightly, but nothing learned supports it.
    let noise = GpVelocityNoise::default();
    let mut filter = settled_on_centroids();
    let contradicting =
        VelocityMeasurement::from_heading_speed(110f64.to_radians(), 0.01, 7.0, 0.25, &noise);
    filter.update_velocity(&contradicting).unwrap();
    let mixture = filter.mixture_estimate();
    assert!(heading_within_report_bar(&mixture), "{mixture:?}");
    assert!(!filter.heading_settled());
    assert!(!filter.reported_heading_known());
    // A later reading that agrees lets it report.
    TrackFilter::predict(&mut filter, DT);
    TrackFilter::update(&mut filter, [20.0 * 0.8, 0.0]).unwrap();
    let agreeing = VelocityMeasurement::from_heading_speed(0.0, 0.01, 8.0, 0.25, &noise);
    filter.update_velocity(&agreeing).unwrap();
    assert!(filter.heading_settled());
}

#[test]
fn a_loosely_stated_reading_confirms_no_track() {
    // A reading stated to 60° fits the track's prediction (it fits any) but says nothing of it.
    let noise = GpVelocityNoise::default();
    let mut filter = settled_on_centroids();
    let var = 60f64.to_radians().powi(2);
    let loose = VelocityMeasurement::from_heading_speed(0.0, var, 8.0, 0.25, &noise);
    let innovation = filter.combined.velocity_innovation(&loose).unwrap();
    assert!(
        innovation.mahalanobis_sq <= READING_GATE_CHI2,
        "{innovation:?}"
    );
    filter.update_velocity(&loose).unwrap();
    assert!(!filter.heading_settled());
}

#[test]
fn the_classifiers_reading_at_rest_agrees_with_a_standing_track() {
    // A reading at rest states no heading; the gate alone decides.
    let noise = GpVelocityNoise::default();
    let mut filter = GpTrustFilter::start([5.0, 2.0], KalmanParams::default()).unwrap();
    for _ in 0..5 {
        TrackFilter::predict(&mut filter, DT);
        TrackFilter::update(&mut filter, [5.0, 2.0]).unwrap();
    }
    assert!(
        filter
            .agrees(&VelocityMeasurement::at_rest(&noise))
            .unwrap()
    );
    let fast = VelocityMeasurement::from_heading_speed(0.0, 0.01, 12.0, 0.25, &noise);
    assert!(
        !filter.agrees(&fast).unwrap(),
        "12 m/s against a standing track"
    );
}

/// A GP reading of a car driving +x at `speed_mps`, its heading stated to 5°.
fn reading_at(speed_mps: f64) -> VelocityMeasurement {
    let var = 5f64.to_radians().powi(2);
    VelocityMeasurement::from_heading_speed(0.0, var, speed_mps, 0.25, &GpVelocityNoise::default())
}

/// A track of a car driving +x at `speed_mps`, started on its first centroid, that has fused
/// `readings` of [`reading_at`] and the centroids of the scans between them.
fn young_track(speed_mps: f64, readings: usize) -> GpTrustFilter {
    let reading = reading_at(speed_mps);
    let mut young = GpTrustFilter::start([0.0, 0.0], KalmanParams::default()).unwrap();
    young.update_velocity(&reading).unwrap();
    for k in 1..readings {
        TrackFilter::predict(&mut young, DT);
        TrackFilter::update(&mut young, [speed_mps * DT * k as f64, 0.0]).unwrap();
        young.update_velocity(&reading).unwrap();
    }
    young
}

#[test]
fn the_report_is_the_likeliest_mode_where_a_rule_allows_and_a_gap_waits_for_the_settled_rule() {
    // A 6 m/s car read three times by the GP to 5°: the reported mode knows heading and speed
    // within the report bars, the mixture its heading within 25° but not yet within 12.5°.
    assert_eq!(
        young_track(6.0, 1).report(false),
        None,
        "one reading: neither rule"
    );
    let young = young_track(6.0, 3);
    assert!(young.reported_heading_known() && !young.heading_settled());
    assert_eq!(young.report(false), young.estimate());
    assert_eq!(
        young.report(true),
        None,
        "seen through a gap before it settles"
    );
    let mut settled = settled_on_centroids();
    settled.update_velocity(&reading_at(6.0)).unwrap();
    assert!(settled.heading_settled());
    assert_eq!(settled.report(true), settled.estimate());
}

#[test]
fn a_track_that_does_not_know_its_speed_within_half_the_bar_does_not_report() {
    // An 8 m/s car read twice by the GP to 5° (at the 1 m/s floor of a reading's speed error):
    // the likeliest mode states its heading to 7.5°, within 12.5°, but its speed to 0.80 m/s, more
    // than half the 1.5 m/s bar; it reports once it knows the speed that well.
    let young = young_track(8.0, 2);
    let e = young.estimate().unwrap();
    assert!(young.reported_heading_known(), "the heading rule allows it");
    assert!(
        e.speed_var.unwrap().sqrt() > MAX_REPORTED_SPEED_STD_MPS,
        "{e:?}"
    );
    assert_eq!(young.report(false), None);
    let mut settled = settled_on_centroids();
    settled.update_velocity(&reading_at(8.0)).unwrap();
    assert_eq!(settled.report(false), settled.estimate());
}
