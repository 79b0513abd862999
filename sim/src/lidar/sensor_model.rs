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

    /// Whether a return with the uniform draw `u` in [0, 1) is detected: exactly
    /// `u < detection_probability(reflectivity, cos_incidence, range_m)`, bit for bit, but
    /// mostly without its three chained divisions (the lidar asks this for every return, and a
    /// drop decided late stalls the next beam). In f64 the probability is `P² / (P² + T²D²)`
    /// (`P` = reflectivity × cosine, `D` = range², `T` the threshold, all as the f32 formula
    /// rounds them), and the draw is compared with it by multiplying out; the f32 formula lies
    /// within 7 units of 2⁻²⁴ (relative) of that value, so a draw outside a relative band of
    /// 10⁻⁵ around it decides the same way, and a draw inside the band (about one in 10⁵) is
    /// decided by the formula itself.
    #[inline]
    pub(crate) fn detects(
        &self,
        reflectivity: f32,
        cos_incidence: f32,
        range_m: f32,
        u: f32,
    ) -> bool {
        const BAND: f64 = 1e-5;
        if self.threshold <= 0.0 {
            return u < 1.0;
        }
        let p = f64::from(reflectivity.max(1e-4) * cos_incidence.abs().max(1e-4));
        let td = f64::from(self.threshold) * f64::from((range_m * range_m).max(1e-6));
        let (kept, all) = (p * p, p * p + td * td);
        let lhs = f64::from(u) * all;
        if lhs < kept * (1.0 - BAND) {
            true
        } else if lhs > kept * (1.0 + BAND) {
            false
        } else {
            u < self.detection_probability(reflectivity, cos_incidence, range_m)
        }
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
    fn the_detection_decision_is_exactly_the_draw_against_the_probability() {
        let m = urban();
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut near_the_edge = 0;
        for _ in 0..200_000 {
            let r = rng.random_range(0.0f32..1.0);
            let c = rng.random_range(-1.0f32..1.0);
            let d = rng.random_range(0.0f32..200.0);
            let p = m.detection_probability(r, c, d);
            // Random draws, and draws on and next to the probability itself.
            for u in [rng.random::<f32>(), p, p.next_down(), p.next_up()] {
                if (0.0..1.0).contains(&u) {
                    assert_eq!(
                        m.detects(r, c, d, u),
                        u < p,
                        "r {r} c {c} d {d} u {u} p {p}"
                    );
                }
            }
            near_the_edge += usize::from(p > 1e-3 && p < 0.999);
        }
        assert!(near_the_edge > 10_000, "{near_the_edge} cases in the ramp");
        let ideal = SensorModel::new(SensorKnobs::of(Realism::Ideal), 64, 3);
        assert!(ideal.detects(0.01, 0.01, 119.0, 0.999_999));
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
