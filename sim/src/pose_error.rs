//! The ego's localisation error, GPS/INS-like: a slowly drifting offset of the horizontal
//! position and the heading, each a sum of a few seeded sinusoids with periods around the drift
//! time (a band-limited stand-in for a Gauss-Markov drift). A closed form in time, so the error
//! at any instant is known without simulating the instants before it (sweeps stay independent),
//! and bounded by construction.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::motion::MotionState;
use crate::scenario::PoseErrorKnobs;
use crate::seed::{hash_name, mix, sub_seed};

/// Sinusoids per error component.
const TERMS: usize = 4;

/// One error component: `Σ a_k sin(ω_k t + φ_k)`.
#[derive(Debug, Clone, PartialEq)]
struct Drift {
    terms: [(f64, f64, f64); TERMS],
}

impl Drift {
    fn new(std: f64, drift_secs: f64, rng: &mut ChaCha8Rng) -> Self {
        // Σ a² / 2 = std²; periods spread over an octave band around 4 × the drift time.
        let amplitude = std * (2.0 / TERMS as f64).sqrt();
        let terms = std::array::from_fn(|k| {
            let period = drift_secs * 4.0 / (1 << k) as f64 * rng.random_range(0.7..1.3);
            (
                amplitude,
                std::f64::consts::TAU / period,
                rng.random_range(0.0..std::f64::consts::TAU),
            )
        });
        Self { terms }
    }

    fn at(&self, t: f64) -> f64 {
        self.terms
            .iter()
            .map(|&(a, w, p)| a * (w * t + p).sin())
            .sum()
    }

    /// The largest value the component can reach.
    #[cfg(test)]
    fn bound(&self) -> f64 {
        self.terms.iter().map(|t| t.0.abs()).sum()
    }
}

/// The ego's pose error over time.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PoseError {
    x: Drift,
    y: Drift,
    yaw: Drift,
    exact: bool,
}

impl PoseError {
    /// The error of sequence `name` under run `seed`.
    pub(crate) fn new(knobs: &PoseErrorKnobs, seed: u64, name: &str) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(sub_seed(mix(seed ^ hash_name(name)), 0xE57));
        let drift = knobs.drift_secs;
        Self {
            x: Drift::new(knobs.position_std_m, drift, &mut rng),
            y: Drift::new(knobs.position_std_m, drift, &mut rng),
            yaw: Drift::new(knobs.yaw_std_deg.to_radians(), drift, &mut rng),
            exact: knobs.exact(),
        }
    }

    /// The ego's estimated state at `t_secs` given its true state then (the same state when exact).
    pub(crate) fn estimate(&self, truth: &MotionState, t_secs: f64) -> MotionState {
        if self.exact {
            return *truth;
        }
        let mut estimate = *truth;
        estimate.position_m[0] += self.x.at(t_secs);
        estimate.position_m[1] += self.y.at(t_secs);
        estimate.yaw_rad += self.yaw.at(t_secs);
        estimate
    }

    /// Largest position error along one axis and largest yaw error, (metres, radians).
    #[cfg(test)]
    pub(crate) fn bounds(&self) -> (f64, f64) {
        (self.x.bound().max(self.y.bound()), self.yaw.bound())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Realism;

    fn state() -> MotionState {
        MotionState {
            position_m: [10.0, -2.0],
            yaw_rad: 0.3,
            velocity_mps: [5.0, 0.0],
            speed_mps: 5.0,
            heading_rad: 0.3,
            yaw_rate_radps: 0.0,
        }
    }

    #[test]
    fn the_error_drifts_slowly_within_its_bound_and_has_about_its_std() {
        let knobs = PoseErrorKnobs::of(Realism::Urban);
        let error = PoseError::new(&knobs, 7, "seq");
        let (bound, yaw_bound) = error.bounds();
        let samples: Vec<f64> = (0..20_000).map(|i| f64::from(i) * 0.1).collect();
        let mut squares = 0.0;
        for w in samples.windows(2) {
            let (a, b) = (
                error.estimate(&state(), w[0]),
                error.estimate(&state(), w[1]),
            );
            let dx = a.position_m[0] - 10.0;
            assert!(dx.abs() <= bound + 1e-12 && (a.yaw_rad - 0.3).abs() <= yaw_bound + 1e-12);
            // Over one sweep (0.1 s) the estimate moves by centimetres at most, not by its std.
            assert!(
                (b.position_m[0] - a.position_m[0]).abs() < 0.03,
                "jump at {}",
                w[0]
            );
            squares += dx * dx;
        }
        let std = (squares / samples.len() as f64).sqrt();
        assert!(
            (0.15..0.45).contains(&std),
            "position error std {std} m for 0.3 m"
        );
    }

    #[test]
    fn the_error_is_seeded_and_exact_on_the_ideal_rung() {
        let knobs = PoseErrorKnobs::of(Realism::Urban);
        assert_eq!(
            PoseError::new(&knobs, 7, "a"),
            PoseError::new(&knobs, 7, "a")
        );
        assert_ne!(
            PoseError::new(&knobs, 7, "a"),
            PoseError::new(&knobs, 8, "a")
        );
        let ideal = PoseError::new(&PoseErrorKnobs::of(Realism::Ideal), 7, "a");
        assert_eq!(ideal.estimate(&state(), 12.0), state());
    }
}
