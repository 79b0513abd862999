//! How the lidar departs from an ideal one (the `[sensor]` knobs): whether a return is detected
//! at all (received power ∝ reflectivity × cos(incidence) / range², against a soft threshold, so
//! dark, far and grazing surfaces lose returns as real HDL-64E data does), range noise that grows
//! with range, and the per-channel calibration of one sensor unit: an intensity gain and an
//! elevation error (the beam leaves at the true elevation, the point is written at the nominal
//! one). The calibration is drawn once per sequence from the run seed.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use crate::scenario::SensorKnobs;

/// Reflectivity of the reference target of `detection_range_m` (dark asphalt-like).
const REFERENCE_REFLECTIVITY: f32 = 0.1;
/// Steepness of the detection curve in log power: the keep probability goes from 10 % to 90 %
/// over a factor of about 3 in received power.
const STEEPNESS: f32 = 2.0;
const _: () = assert!(
    STEEPNESS == 2.0,
    "detection_probability squares the power ratio"
);

/// The sensor errors of one lidar unit.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SensorModel {
    knobs: SensorKnobs,
    /// Received power (reflectivity · cos / r²) returned half of the time; 0: every return kept.
    threshold: f32,
    /// Intensity gain of every channel, highest first.
    gains: Vec<f32>,
    /// Elevation error of every channel, radians, highest first.
    elevation_errors_rad: Vec<f64>,
}

impl SensorModel {
    /// The model of a lidar with `channels` channels, calibration drawn from `seed`.
    pub(crate) fn new(knobs: SensorKnobs, channels: usize, seed: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut normal = || rng.sample::<f64, _>(StandardNormal);
        let gains = (0..channels)
            .map(|_| (knobs.intensity_gain_std * normal()).exp() as f32)
            .collect();
        let elevation_errors_rad = (0..channels)
            .map(|_| (knobs.elevation_error_deg * normal()).to_radians())
            .collect();
        let threshold = if knobs.detection_range_m > 0.0 {
            REFERENCE_REFLECTIVITY / (knobs.detection_range_m * knobs.detection_range_m) as f32
        } else {
            0.0
        };
        Self {
            knobs,
            threshold,
            gains,
            elevation_errors_rad,
        }
    }

    /// True if the sensor is the ideal one of the first release.
    pub(crate) fn is_ideal(&self) -> bool {
        self.knobs.ideal()
    }

    /// Elevation error of channel `c` (highest first), radians.
    pub(crate) fn elevation_error_rad(&self, c: usize) -> f64 {
        self.elevation_errors_rad.get(c).copied().unwrap_or(0.0)
    }

    /// Intensity gain of channel `c` (highest first).
    #[inline]
    pub(crate) fn gain(&self, c: usize) -> f32 {
        self.gains.get(c).copied().unwrap_or(1.0)
    }

    /// Probability that a surface of `reflectivity` hit at `range_m` with `cos_incidence` returns.
    #[inline]
    pub(crate) fn detection_probability(
        &self,
        reflectivity: f32,
        cos_incidence: f32,
        range_m: f32,
    ) -> f32 {
        if self.threshold <= 0.0 {
            return 1.0;
        }
        let power =
            reflectivity.max(1e-4) * cos_incidence.abs().max(1e-4) / (range_m * range_m).max(1e-6);
        let ratio = self.threshold / power;
        // STEEPNESS = 2: the square, without a libm call.
        1.0 / (1.0 + ratio * ratio)
    }

    /// Std of the range noise at `range_m` beyond the constant part, metres.
    #[inline]
    pub(crate) fn extra_noise_std_m(&self, range_m: f32) -> f32 {
        self.knobs.range_noise_per_m as f32 * range_m
    }

    /// Chance a beam on a depth edge returns a mixed range.
    pub(crate) fn mixed_pixels(&self) -> f32 {
        self.knobs.mixed_pixels as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Realism;

    fn urban() -> SensorModel {
        SensorModel::new(SensorKnobs::of(Realism::Urban), 64, 3)
    }

    #[test]
    fn returns_are_lost_more_with_range_grazing_incidence_and_darkness() {
        let m = urban();
        let p = |r: f32, c: f32, d: f32| m.detection_probability(r, c, d);
        for k in 1..200 {
            let d = k as f32;
            assert!(
                p(0.15, 0.05, d + 1.0) <= p(0.15, 0.05, d),
                "not monotone in range at {d}"
            );
            let c = k as f32 / 200.0;
            assert!(
                p(0.15, c, 30.0) <= p(0.15, c + 0.005, 30.0),
                "not monotone in incidence"
            );
            assert!(
                p(c, 0.5, 60.0) <= p(c + 0.005, 0.5, 60.0),
                "not monotone in reflectivity"
            );
        }
        // Dark asphalt seen head-on at the detection range returns half of the time.
        assert!((p(0.1, 1.0, 140.0) - 0.5).abs() < 1e-4);
        // A bright wall at 100 m nearly always; asphalt at 60 m at a grazing 1.7° nearly never.
        assert!(p(0.5, 0.9, 100.0) > 0.9);
        assert!(p(0.15, 0.03, 60.0) < 0.1);
    }

    #[test]
    fn the_ideal_sensor_keeps_every_return_and_has_unit_gains() {
        let m = SensorModel::new(SensorKnobs::of(Realism::Ideal), 64, 3);
        assert!(m.is_ideal());
        assert_eq!(m.detection_probability(0.01, 0.01, 119.0), 1.0);
        assert!((0..64).all(|c| m.gain(c) == 1.0 && m.elevation_error_rad(c) == 0.0));
    }

    #[test]
    fn calibration_is_seeded_per_unit() {
        let knobs = SensorKnobs::of(Realism::Urban);
        assert_eq!(
            SensorModel::new(knobs, 64, 3),
            SensorModel::new(knobs, 64, 3)
        );
        assert_ne!(
            SensorModel::new(knobs, 64, 3),
            SensorModel::new(knobs, 64, 4)
        );
    }
}
