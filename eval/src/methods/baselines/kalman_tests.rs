//! Tests of the constant-velocity Kalman filter and its persistent velocity-sensor error.

use super::*;
use crate::methods::baselines::velocity_measurement::GpVelocityNoise;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn gaussian(rng: &mut ChaCha8Rng, std: f64) -> f64 {
    // Box-Muller.
    let u1: f64 = rng.random_range(1e-12..1.0);
    let u2: f64 = rng.random_range(0.0..1.0);
    std * (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// Noisy centroids of a target at constant velocity `v`, every `dt` seconds.
fn noisy_track(v: [f64; 2], dt: f64, n: usize, noise_m: f64, seed: u64) -> Vec<[f64; 2]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|k| {
            let t = k as f64 * dt;
            [
                5.0 + v[0] * t + gaussian(&mut rng, noise_m),
                -3.0 + v[1] * t + gaussian(&mut rng, noise_m),
            ]
        })
        .collect()
}

#[test]
fn the_filter_converges_to_the_true_velocity_of_a_constant_velocity_target() {
    let v = [6.0, -2.0];
    let z = noisy_track(v, 0.1, 80, 0.3, 11);
    let mut kf = ConstantVelocityKalman::new(z[0], KalmanParams::default()).unwrap();
    let mut late_errors = Vec::new();
    for (k, zk) in z.iter().enumerate().skip(1) {
        kf.predict(0.1);
        kf.update(*zk).unwrap();
        if k >= 40 {
            let e = kf.velocity();
            late_errors.push(((e[0] - v[0]).powi(2) + (e[1] - v[1]).powi(2)).sqrt());
        }
    }
    let mean_error = late_errors.iter().sum::<f64>() / late_errors.len() as f64;
    assert!(mean_error < 0.6, "mean velocity error {mean_error} m/s");
}

#[test]
fn the_filtered_velocity_is_smoother_than_raw_centroid_differences() {
    let v = [4.0, 3.0];
    let z = noisy_track(v, 0.1, 60, 0.3, 12);
    let mut kf = ConstantVelocityKalman::new(z[0], KalmanParams::default()).unwrap();
    let (mut kf_sq, mut raw_sq, mut n) = (0.0, 0.0, 0.0);
    for k in 1..z.len() {
        kf.predict(0.1);
        kf.update(z[k]).unwrap();
        if k >= 10 {
            let e = kf.velocity();
            kf_sq += (e[0] - v[0]).powi(2) + (e[1] - v[1]).powi(2);
            let raw = [(z[k][0] - z[k - 1][0]) / 0.1, (z[k][1] - z[k - 1][1]) / 0.1];
            raw_sq += (raw[0] - v[0]).powi(2) + (raw[1] - v[1]).powi(2);
            n += 1.0;
        }
    }
    let (kf_rms, raw_rms) = ((kf_sq / n).sqrt(), (raw_sq / n).sqrt());
    assert!(kf_rms < raw_rms / 3.0, "KF {kf_rms} vs raw {raw_rms}");
}

#[test]
fn no_estimate_is_reported_before_the_second_measurement() {
    let mut kf = ConstantVelocityKalman::new([1.0, 1.0], KalmanParams::default()).unwrap();
    assert!(kf.estimate().is_none());
    kf.predict(0.1);
    kf.update([1.5, 1.0]).unwrap();
    let e = kf.estimate().unwrap();
    assert!(e.heading_rad.abs() < 1e-9);
    assert!(e.heading_var.unwrap() > 0.0 && e.speed_var.unwrap() > 0.0);
}

#[test]
fn a_velocity_measurement_gives_an_estimate_from_the_first_scan() {
    let mut kf = ConstantVelocityKalman::new([0.0, 0.0], KalmanParams::default()).unwrap();
    let measured = VelocityMeasurement {
        velocity_xy_mps: [6.0, 2.0],
        covariance: Matrix2::identity() * 0.01,
        persistent_covariance: Matrix2::identity() * 0.01,
        persistence_secs: 3.0,
    };
    kf.update_velocity(&measured).unwrap();
    let e = kf.estimate().unwrap();
    assert!((e.velocity_xy_mps[0] - 6.0).abs() < 0.01 && (e.velocity_xy_mps[1] - 2.0).abs() < 0.01);
}

/// Final heading error (degrees) of a filter fed a car's noisy centroids at 8 m/s along x and,
/// every scan, a GP reading it 25° off with `noise`.
fn heading_error_with_a_persistently_wrong_gp(noise: &GpVelocityNoise) -> f64 {
    let v = [8.0, 0.0];
    let centroids = noisy_track(v, 0.1, 60, 0.3, 3);
    let mut kf = ConstantVelocityKalman::new(centroids[0], KalmanParams::default()).unwrap();
    let wrong = 25f64.to_radians();
    for (k, z) in centroids.iter().enumerate() {
        if k > 0 {
            kf.predict(0.1);
            kf.update(*z).unwrap();
        }
        let gp = VelocityMeasurement::from_heading_speed(wrong, 0.0, 8.0, 0.0, noise);
        kf.update_velocity(&gp).unwrap();
    }
    let e = kf.velocity();
    e[1].atan2(e[0]).to_degrees().abs()
}

#[test]
fn the_centroids_learn_away_a_persistent_gp_error() {
    let modelled = heading_error_with_a_persistently_wrong_gp(&GpVelocityNoise::default());
    let white_only = heading_error_with_a_persistently_wrong_gp(&GpVelocityNoise {
        persistent_heading_std_rad: 0.0,
        persistent_speed_std_mps: 0.0,
        ..GpVelocityNoise::default()
    });
    assert!(
        modelled < 3.0,
        "with the persistent error modelled: {modelled}°"
    );
    assert!(white_only > 6.0, "fused as white noise: {white_only}°");
}

#[test]
fn without_velocity_measurements_the_persistent_error_stays_out_of_the_state() {
    let centroids = noisy_track([5.0, 1.0], 0.1, 30, 0.3, 5);
    let mut kf = ConstantVelocityKalman::new(centroids[0], KalmanParams::default()).unwrap();
    for z in &centroids[1..] {
        kf.predict(0.1);
        kf.update(*z).unwrap();
    }
    let block = kf.covariance.fixed_view::<2, 6>(4, 0).into_owned();
    assert_eq!(block, nalgebra::Matrix2x6::zeros());
    assert_eq!((kf.state[4], kf.state[5]), (0.0, 0.0));
}

#[test]
fn a_measurement_with_no_correlation_time_is_refused() {
    let mut kf = ConstantVelocityKalman::new([0.0, 0.0], KalmanParams::default()).unwrap();
    let mut measured =
        VelocityMeasurement::from_heading_speed(0.0, 0.0, 5.0, 0.0, &GpVelocityNoise::default());
    measured.persistence_secs = 0.0;
    let error = kf.update_velocity(&measured).unwrap_err().to_string();
    assert!(error.contains("persistence_secs"), "{error}");
}

#[test]
fn the_mahalanobis_distance_grows_with_the_residual() {
    let mut kf = ConstantVelocityKalman::new([0.0, 0.0], KalmanParams::default()).unwrap();
    kf.predict(0.1);
    let near = kf.innovation([0.1, 0.0]).unwrap().mahalanobis_sq;
    let far = kf.innovation([10.0, 0.0]).unwrap().mahalanobis_sq;
    assert!(near < 9.21 && far > 9.21);
}

#[test]
fn a_non_positive_noise_is_an_error() {
    let params = KalmanParams {
        centroid_noise_std_m: 0.0,
        ..KalmanParams::default()
    };
    assert!(ConstantVelocityKalman::new([0.0, 0.0], params).is_err());
}

/// A filter whose state is `(x, y, vx, vy, 0, 0, ax, ay)`, covariance zero.
fn filter_at(state: [f64; 8]) -> ConstantVelocityKalman {
    let mut filter = ConstantVelocityKalman::new([0.0, 0.0], KalmanParams::default()).unwrap();
    filter.set_moments(State::from_column_slice(&state), StateCovariance::zeros());
    filter
}

#[test]
fn the_singer_transition_matches_a_published_example() {
    // MathWorks' Sensor Fusion and Tracking Toolbox, `singer` (τ = 20 s, Δt = 1 s): the 2-D state
    // (x, vx, ax, y, vy, ay) = (1, 1, 0, 2, 5, −2) predicts to (2, 1, 0, 6.0165, 3.0492, −1.9025).
    let mut filter = filter_at([1.0, 2.0, 1.0, 5.0, 0.0, 0.0, 0.0, -2.0]);
    filter.predict_singer(1.0, 2.5, 20.0);
    let (state, _) = filter.moments();
    let expected = [2.0, 6.0165, 1.0, 3.0492, 0.0, 0.0, 0.0, -1.9025];
    for (i, want) in expected.iter().enumerate() {
        assert!((state[i] - want).abs() < 5e-5, "entry {i}: {state:?}");
    }
}

#[test]
fn the_singer_process_noise_matches_its_closed_form() {
    // Singer (1970)'s closed form at α = 1/s, Δt = 0.1 s (integrated symbolically), per unit jerk
    // spectral density: position, velocity, acceleration (to 17 digits).
    let closed_form = [
        [
            4.731_871_504_893_655e-7,
            1.170_030_662_731_349e-5,
            1.508_816_574_131_134e-4,
        ],
        [
            1.170_030_662_731_349e-5,
            3.094_595_329_282_17e-4,
            4.527_958_503_031_356e-3,
        ],
        [
            1.508_816_574_131_134e-4,
            4.527_958_503_031_356e-3,
            9.063_462_346_100_907e-2,
        ],
    ];
    let q = motion::singer_process_noise(0.1, 1.0);
    for (i, row) in closed_form.iter().enumerate() {
        for (j, want) in row.iter().enumerate() {
            assert!((q[i][j] / want - 1.0).abs() < 1e-12, "({i}, {j}): {q:?}");
        }
    }
}

#[test]
fn with_a_long_time_constant_the_singer_noise_is_the_wiener_process_acceleration_noise() {
    // Bar-Shalom, Li and Kirubarajan (2001), eq. 6.2.3-8: Δt⁵/20, Δt⁴/8, Δt³/6, Δt³/3, Δt²/2, Δt.
    let dt: f64 = 0.1;
    let wiener = [
        [dt.powi(5) / 20.0, dt.powi(4) / 8.0, dt.powi(3) / 6.0],
        [dt.powi(4) / 8.0, dt.powi(3) / 3.0, dt * dt / 2.0],
        [dt.powi(3) / 6.0, dt * dt / 2.0, dt],
    ];
    let q = motion::singer_process_noise(dt, 1e-5);
    for (i, row) in wiener.iter().enumerate() {
        for (j, want) in row.iter().enumerate() {
            assert!((q[i][j] / want - 1.0).abs() < 1e-5, "({i}, {j}): {q:?}");
        }
    }
}

#[test]
fn held_by_noise_alone_the_singer_acceleration_settles_at_its_stationary_spread() {
    // ȧ = −a/τ + j with white jerk of density q has the stationary variance q·τ/2.
    let (jerk, tau) = (2.5, 1.0);
    let mut filter = filter_at([0.0; 8]);
    for _ in 0..300 {
        filter.predict_singer(0.1, jerk, tau);
    }
    let (_, covariance) = filter.moments();
    let stationary = jerk * jerk * tau / 2.0;
    for axis in [6, 7] {
        let var = covariance[(axis, axis)];
        assert!(
            (var / stationary - 1.0).abs() < 1e-9,
            "{var} against {stationary}"
        );
    }
    assert_eq!(covariance[(6, 7)], 0.0, "the axes stay independent");
}

#[test]
fn a_singer_acceleration_fades_by_e_over_its_time_constant() {
    let mut filter = filter_at([0.0, 0.0, 3.0, 0.0, 0.0, 0.0, 2.0, 0.0]);
    for _ in 0..10 {
        filter.predict_singer(0.1, 2.5, 1.0);
    }
    let (state, _) = filter.moments();
    assert!(
        (state[6] - 2.0 / std::f64::consts::E).abs() < 1e-12,
        "{state:?}"
    );
    // The speed gained is the acceleration's integral, 2·τ·(1 − 1/e).
    let gained = 2.0 * (1.0 - 1.0 / std::f64::consts::E);
    assert!((state[2] - 3.0 - gained).abs() < 1e-12, "{state:?}");
}

#[test]
fn the_constant_velocity_prediction_drops_an_acceleration_the_state_carries() {
    let mut filter = filter_at([0.0, 0.0, 3.0, 0.0, 0.0, 0.0, 2.0, 0.0]);
    filter.predict(0.1);
    let (state, covariance) = filter.moments();
    assert!((state[0] - 0.3).abs() < 1e-12, "{state:?}");
    assert_eq!(state[2], 3.0);
    assert_eq!(state.fixed_rows::<2>(6).norm(), 0.0);
    assert_eq!(covariance.fixed_rows::<2>(6).norm(), 0.0);
}
