//! Tests of GP-KF's interacting multiple model over the GP's trust.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::*;
use crate::methods::baselines::tracker::{MultiTargetTracker, TrackerParams};
use crate::methods::baselines::velocity_measurement::GpVelocityNoise;

const DT: f64 = 0.1;

/// Centroids of a car driving +x at 8 m/s, 0.3 m of noise per axis.
fn centroids(n: usize, seed: u64) -> Vec<[f64; 2]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|k| {
            let noise = rng.random_range(-0.3..0.3);
            [8.0 * k as f64 * DT, noise]
        })
        .collect()
}

/// Runs `F` over the centroids with the GP reading `gp_heading_deg(k)` at 8 m/s (merged variance
/// as small as the floors allow); returns the final heading error in degrees and the filter.
fn run<F: TrackFilter>(gp_heading_deg: impl Fn(usize) -> f64) -> (f64, F) {
    let noise = GpVelocityNoise::default();
    let z = centroids(60, 5);
    let mut filter = F::start(z[0], KalmanParams::default()).unwrap();
    for (k, zk) in z.iter().enumerate() {
        if k > 0 {
            filter.predict(DT);
            filter.update(*zk).unwrap();
        }
        let h = gp_heading_deg(k).to_radians();
        let reading = VelocityMeasurement::from_heading_speed(h, 0.0, 8.0, 0.0, &noise);
        filter.update_velocity(&reading).unwrap();
    }
    let e = filter.estimate().unwrap();
    (e.heading_rad.to_degrees().abs(), filter)
}

/// A GP that reads the car 40-90° off, to either side, scan after scan.
fn wild(k: usize) -> f64 {
    let side = if (k / 3).is_multiple_of(2) { 1.0 } else { -1.0 };
    side * (40.0 + (k * 37 % 50) as f64)
}

#[test]
fn a_gp_that_reads_wildly_loses_the_tracks_trust() {
    let (_, filter) = run::<GpTrustFilter>(wild);
    assert!(filter.gp_trust() < 0.05, "trust {}", filter.gp_trust());
}

#[test]
fn with_a_wild_gp_the_track_follows_the_centroids_better_than_one_fixed_noise_does() {
    let (trusting, _) = run::<GpTrustFilter>(wild);
    let (fixed, _) = run::<ConstantVelocityKalman>(wild);
    assert!(trusting < 5.0, "IMM heading error {trusting}°");
    assert!(
        trusting < 0.5 * fixed,
        "IMM {trusting}° against one noise {fixed}°"
    );
}

#[test]
fn a_gp_that_agrees_with_the_centroids_keeps_the_tracks_trust() {
    let (error, filter) = run::<GpTrustFilter>(|k| if k.is_multiple_of(2) { 3.0 } else { -3.0 });
    assert!(filter.gp_trust() > 0.5, "trust {}", filter.gp_trust());
    assert!(error < 3.0, "heading error {error}°");
}

#[test]
fn without_gp_readings_the_filter_is_the_constant_velocity_filter() {
    let z = centroids(30, 9);
    let mut imm = GpTrustFilter::start(z[0], KalmanParams::default()).unwrap();
    let mut kf = ConstantVelocityKalman::new(z[0], KalmanParams::default()).unwrap();
    for zk in &z[1..] {
        TrackFilter::predict(&mut imm, DT);
        kf.predict(DT);
        TrackFilter::update(&mut imm, *zk).unwrap();
        kf.update(*zk).unwrap();
    }
    let (a, b) = (imm.estimate().unwrap(), kf.estimate().unwrap());
    assert!((a.heading_rad - b.heading_rad).abs() < 1e-9);
    assert!((a.speed_mps - b.speed_mps).abs() < 1e-9);
}

#[test]
fn on_its_first_gp_reading_a_track_reports_the_gps_motion() {
    let noise = GpVelocityNoise::default();
    let mut filter = GpTrustFilter::start([0.0, 0.0], KalmanParams::default()).unwrap();
    let reading = VelocityMeasurement::from_heading_speed(0.0, 0.0, 8.0, 0.0, &noise);
    filter.update_velocity(&reading).unwrap();
    let e = filter.estimate().unwrap();
    assert!((e.speed_mps - 8.0).abs() < 0.2, "{e:?}");
    assert!(e.heading_rad.abs() < 1e-9, "{e:?}");
}

#[test]
fn a_mode_nothing_can_switch_into_keeps_its_own_state() {
    let z = centroids(5, 3);
    let mut filter = GpTrustFilter::start(z[0], KalmanParams::default()).unwrap();
    filter.predicted = [1.0, 0.0, 0.0];
    let before = filter.modes[UNRELIABLE].moments();
    TrackFilter::predict(&mut filter, DT);
    let mut expected = ConstantVelocityKalman::new(z[0], KalmanParams::default()).unwrap();
    expected.set_moments(before.0, before.1);
    expected.predict(DT);
    assert_eq!(filter.modes[UNRELIABLE].moments(), expected.moments());
}

/// GP-KF's tracker after 20 scans of one car driving +x at 8 m/s along y = 0, every scan read by
/// the GP as `reading`; returns the tracker and the car's track.
fn tracked_for_20_scans(
    reading: VelocityMeasurement,
) -> (MultiTargetTracker<GpTrustFilter>, usize) {
    let mut tracker =
        MultiTargetTracker::<GpTrustFilter>::with_track_filter(TrackerParams::default()).unwrap();
    let mut id = None;
    for k in 0..20 {
        let taken = tracker
            .step_measured(
                k,
                k as f64 * DT,
                &[[8.0 * k as f64 * DT, 0.0]],
                &[Some(reading)],
            )
            .unwrap();
        id = taken[0];
    }
    (tracker, id.unwrap())
}

#[test]
fn a_split_target_whose_fragment_carries_a_consistent_gp_reading_stays_with_its_track() {
    // A car drives +x at 8 m/s and the GP reads it 5° off every scan, which the IMM keeps
    // trusting. At scan 20 its cluster splits: the fragment the GP read lies 0.3 m ahead of the
    // track's prediction, its sibling (no reading, as under the per-target protocol) 0.25 m
    // behind. By position alone the sibling is nearer; the reading is evidence for the track.
    let noise = GpVelocityNoise::default();
    let reading = VelocityMeasurement::from_heading_speed(5f64.to_radians(), 0.0, 8.0, 0.0, &noise);
    let (mut tracker, id) = tracked_for_20_scans(reading);
    let track = tracker.track(id).unwrap();
    assert!(
        track.filter.gp_trust() > 0.5,
        "trust {}",
        track.filter.gp_trust()
    );
    let predicted = 8.0 * 20.0 * DT;
    let fragments = [[predicted - 0.25, 0.0], [predicted + 0.3, 0.0]];
    // The case the likelihood ratio is for: with the reading's squared misfit added to the
    // fragment's distance (stop 36's cost), the sibling would be cheaper.
    let mut predicted_track = track.filter.clone();
    TrackFilter::predict(&mut predicted_track, DT);
    let d2 = fragments.map(|c| predicted_track.innovation(c).unwrap().mahalanobis_sq);
    let misfit = predicted_track
        .combined
        .velocity_innovation(&reading)
        .unwrap();
    assert!(d2[0] < d2[1] + misfit.mahalanobis_sq, "{d2:?} {misfit:?}");
    let taken = tracker
        .step_measured(20, 2.0, &fragments, &[None, Some(reading)])
        .unwrap();
    assert_eq!(
        taken[1],
        Some(id),
        "the fragment with the reading stays with the track"
    );
}

#[test]
fn the_white_mode_carries_no_persistent_gp_error_after_mixing() {
    // A GP 25° off every scan: the persistent mode learns a standing error; after each mixing
    // step the white mode's error states are exactly zero, mean and covariance.
    let (_, mut filter) = run::<GpTrustFilter>(|_| 25.0);
    let (mean, _) = filter.modes[TRUSTED].moments();
    assert!(
        mean.fixed_rows::<2>(4).norm() > 0.1,
        "persistent mode {mean:?}"
    );
    TrackFilter::predict(&mut filter, DT);
    let (mean, covariance) = filter.modes[WHITE].moments();
    assert_eq!(mean.fixed_rows::<2>(4).norm(), 0.0);
    assert_eq!(covariance.fixed_rows::<2>(4).norm(), 0.0);
    assert_eq!(covariance.fixed_columns::<2>(4).norm(), 0.0);
}

#[test]
fn a_wild_gp_reading_does_not_push_the_track_off_its_nearer_fragment() {
    // The track trusts a GP 5° off; at scan 20 the cluster splits, and the GP reads the nearer
    // fragment 90° off (it misreads the right object, as in situation 4).
    let noise = GpVelocityNoise::default();
    let good = VelocityMeasurement::from_heading_speed(5f64.to_radians(), 0.0, 8.0, 0.0, &noise);
    let wild = VelocityMeasurement::from_heading_speed(95f64.to_radians(), 0.0, 8.0, 0.0, &noise);
    let (mut tracker, id) = tracked_for_20_scans(good);
    let predicted = 8.0 * 20.0 * DT;
    let fragments = [[predicted - 0.35, 0.0], [predicted + 0.2, 0.0]];
    let taken = tracker
        .step_measured(20, 2.0, &fragments, &[None, Some(wild)])
        .unwrap();
    assert_eq!(
        taken[1],
        Some(id),
        "the nearer fragment stays with the track"
    );
}

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

/// Heading error (degrees) of GP-KF's filter after a car at 7 m/s turns 90° left in 1.3 s (about
/// 8 m/s² sideways), the GP reading its heading to within ±2° every scan.
fn heading_error_after_a_turn() -> f64 {
    let noise = GpVelocityNoise::default();
    let (speed, yaw_rate) = (7.0, std::f64::consts::FRAC_PI_2 / 1.3);
    let radius = speed / yaw_rate;
    let mut filter = GpTrustFilter::start([0.0, -radius], KalmanParams::default()).unwrap();
    let mut heading = 0.0;
    // 20 scans straight along +x, then the turn (13 scans), then 3 scans straight along +y.
    let mut position = [0.0, -radius];
    for k in 0..36 {
        if k > 0 {
            heading = if (20..33).contains(&k) {
                heading + yaw_rate * DT
            } else {
                heading
            };
            position = [
                position[0] + speed * DT * heading.cos(),
                position[1] + speed * DT * heading.sin(),
            ];
            TrackFilter::predict(&mut filter, DT);
            TrackFilter::update(&mut filter, position).unwrap();
        }
        let wobble = if k % 2 == 0 { 2f64 } else { -2.0 }.to_radians();
        let reading =
            VelocityMeasurement::from_heading_speed(heading + wobble, 0.0, speed, 0.0, &noise);
        filter.update_velocity(&reading).unwrap();
    }
    let e = filter.estimate().unwrap();
    (e.heading_rad - heading).to_degrees().abs()
}

#[test]
fn a_track_whose_gp_reads_a_sharp_turn_well_follows_it() {
    // With the centroid filter's 2 m/s² in every mode it lags 13.2° here (2.5° with 5 m/s²).
    let error = heading_error_after_a_turn();
    assert!(error < 8.0, "{error}°");
}
