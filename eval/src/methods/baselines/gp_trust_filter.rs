//! `GP-KF`'s track filter: an interacting multiple model (IMM; Blom and Bar-Shalom 1988;
//! Bar-Shalom, Li and Kirubarajan 2001, §11.6) over how far the GP's velocity can be trusted.
//!
//! The GP reads some objects well scan after scan and others wildly (a crossing car behind parked
//! cars: 40-90° off for several scans, docs/results.md); one fixed measurement noise either lets
//! the wild readings pull the track off or keeps the good ones from helping; and where the GP
//! reads well (a turn) its error is white, and a persistent-error model would hold it back as a
//! bias; and a car pulling away from a junction gains speed faster than a constant-velocity track
//! follows (a car at 2.5 m/s² read 1.7 m/s slow on exact positions, docs/estimator.md "Stop 55").
//! So each track runs four filters on the same centroids and GP readings:
//! - **white**: the GP's velocity with its white noise only (its state holds no persistent
//!   error); once the track has GP readings this mode lets the object turn
//!   ([`MANOEUVRE_ACCEL_NOISE_STD_MPS2`]), because a GP that reads well is what sees a turn;
//! - **trusted**: the GP's velocity with the noise [`VelocityMeasurement`] gives it (white and
//!   persistent error, thesis 3.1.4's Gaussian);
//! - **unreliable**: the same reading with the spread of the filter's own velocity prior
//!   (`KalmanParams::initial_velocity_std_mps` per axis), i.e. a reading that tells next to
//!   nothing, as a clutter measurement does;
//! - **accelerating**: Singer's (1970) fading acceleration in place of the constant velocity
//!   ([`JERK_NOISE_STD_MPS3`], [`ACCELERATION_TIME_CONSTANT_SECS`]) with the GP's reading as the
//!   trusted mode takes it, so that a track whose object speeds up or brakes follows it.
//!
//! Each scan the four are mixed (the IMM's interaction step) with a switching probability from the
//! GP error's correlation time (`1 − exp(−Δt/τ)`, shared equally among the other modes), each
//! predicts and updates, and each one's probability is weighed by how likely it found the scan's
//! centroid and velocity (the product of the sequential innovations' likelihoods). The track
//! reports the filter of the likeliest mode (its gate reads the moment-matched mixture; the
//! association the modes' mixed likelihood of a GP reading). On its first GP reading a track holds
//! no evidence yet and the GP's reading, taken as white, is likeliest, so the filter's estimate
//! is the GP's motion from the first scan (the mixture would give a speed between the GP's and
//! rest there; docs/results.md). GP-KF reports it once the mixture's heading is known to within
//! [`MAX_REPORTED_HEADING_STD_DEG`](report::MAX_REPORTED_HEADING_STD_DEG) and a learned reading
//! has agreed with the track ([`GpTrustFilter::heading_settled`]), and before that wherever the
//! estimate it reports states its heading that tightly and the mixture to within the bar
//! ([`GpTrustFilter::reported_heading_known`]); either way only where the estimate states its
//! speed within [`MAX_REPORTED_SPEED_STD_MPS`](report::MAX_REPORTED_SPEED_STD_MPS)
//! ([`GpTrustFilter::report`]). The filter learns per track how far the GP can be trusted from
//! what the centroids and the GP's own consistency say; it never reads the truth.

use nalgebra::Matrix2;

use crate::error::EvalError;
use crate::methods::baselines::innovation::{CentroidGate, Innovation};
use crate::methods::baselines::kalman::{
    ConstantVelocityKalman, KalmanParams, State, StateCovariance,
};
use crate::methods::baselines::track_filter::TrackFilter;
use crate::methods::baselines::velocity_measurement::VelocityMeasurement;
use crate::methods::estimate::MotionEstimate;

/// Number of modes.
const MODES: usize = 4;
/// Index of the mode that takes the GP's error as white (scan to scan).
const WHITE: usize = 0;
/// Index of the mode that trusts the GP's noise model with its persistent error.
const TRUSTED: usize = 1;
/// Index of the mode that takes the GP's reading as next to uninformative.
const UNRELIABLE: usize = 2;
/// Index of the mode in which the object's acceleration persists for a while (Singer's model) and
/// the GP's reading has its own noise model, as in the trusted mode.
const ACCELERATING: usize = 3;

/// The white mode's acceleration noise once the track has GP readings, m/s²: about half a g, the
/// lateral acceleration of a car turning at a city junction. Where the GP reads an object well,
/// its reading is what follows a turn, and the centroid filter's 2 m/s² (a car's longitudinal
/// acceleration) would hold the velocity to the straight line the car has left.
pub const MANOEUVRE_ACCEL_NOISE_STD_MPS2: f64 = 5.0;

/// The accelerating mode's jerk noise, m/s³ (the spectral density's square root): its
/// acceleration changes by about this much in a second, so that a car pulling away reaches its
/// 2-3 m/s² within a second of starting. With [`ACCELERATION_TIME_CONSTANT_SECS`] the
/// acceleration the mode expects has the standard deviation 2.5 · √(1/2) ≈ 1.8 m/s², a car's
/// ordinary pull-away or braking (2-3 m/s²; the simulator's default 2.5).
pub const JERK_NOISE_STD_MPS3: f64 = 2.5;

/// The accelerating mode's manoeuvre time constant τ, seconds (Singer 1970): how long an
/// acceleration persists, e-fold. A car in town speeds up or brakes for one to three seconds (to
/// 30 km/h at 2.5 m/s² in 3.3 s) and a driver's pedal changes within a second; one second keeps
/// an acceleration through a scan's 0.1 s (90 % of it) and lets it fade once the car stops
/// accelerating, where a constant acceleration overshoots (docs/estimator.md, "Stop 55": set
/// before measuring, the one value tried).
pub const ACCELERATION_TIME_CONSTANT_SECS: f64 = 1.0;

/// How far the object's motion changes before the GP's persistent error is another, m/s: between
/// scans each mode carries the error over by `exp(−|Δv| / scale)` as well as by its correlation
/// time, `Δv` the change of the track's velocity over the last scan. The GP's error is a function
/// of what it reads, and its patches change with the object's motion: the speed GP reads every
/// slow vehicle near 6 m/s, so the error a track learns while a van creeps at 0-3.5 m/s (read at
/// 5.5-7.6) is not the error once it is under way, and carried over it held the track 1.5-2.5 m/s
/// slow (docs/estimator.md, "Stop 56" and "Stop 58"). 2 m/s, the lowest speed of the patches'
/// design range (thesis 4.3), was set before measuring.
pub const PERSISTENT_ERROR_MOTION_SCALE_MPS: f64 = 2.0;

#[path = "gp_trust_report.rs"]
mod report;
#[cfg(test)]
use report::{MAX_REPORTED_SPEED_STD_MPS, READING_GATE_CHI2, heading_within_report_bar};

/// Four filters, GP white, trusted and unreliable, and accelerating, and their probabilities.
#[derive(Debug, Clone, PartialEq)]
pub struct GpTrustFilter {
    modes: [ConstantVelocityKalman; MODES],
    /// Mode probabilities before this scan's measurements (after the last prediction).
    predicted: [f64; MODES],
    /// Log-likelihood of this scan's measurements so far, per mode.
    log_likelihood: [f64; MODES],
    /// Correlation time of the GP's error, once a velocity was measured, seconds.
    switch_secs: Option<f64>,
    /// Per-axis standard deviation of a reading in the unreliable mode, m/s.
    unreliable_std_mps: f64,
    /// The moment-matched mixture given the measurements so far, one filter; kept current by
    /// every step, because the gate reads it once per cluster of the scan.
    combined: ConstantVelocityKalman,
    /// Learned readings that agreed with the track when they came ([`Self::agrees`]).
    agreeing_readings: usize,
    /// The mixture's velocity when the last prediction began, m/s (none before the first).
    last_velocity_xy_mps: Option<[f64; 2]>,
    /// [`PERSISTENT_ERROR_MOTION_SCALE_MPS`] (the tests switch it off with an infinite scale).
    motion_scale_mps: f64,
}

impl GpTrustFilter {
    /// The probability that the GP's readings on this track are as trustworthy as their noise
    /// model says, given everything measured so far (read by the tests).
    #[cfg(test)]
    pub(crate) fn gp_trust(&self) -> f64 {
        1.0 - self.posterior()[UNRELIABLE]
    }

    /// Mode probabilities given this scan's measurements.
    fn posterior(&self) -> [f64; MODES] {
        let top = self.log_likelihood.iter().copied().fold(f64::MIN, f64::max);
        let w: [f64; MODES] =
            std::array::from_fn(|j| self.predicted[j] * (self.log_likelihood[j] - top).exp());
        let sum: f64 = w.iter().sum();
        if sum > 0.0 && sum.is_finite() {
            w.map(|x| x / sum)
        } else {
            self.predicted
        }
    }

    /// The mixture's mean and covariance under `weights` (moment matching).
    fn mixture(&self, weights: [f64; MODES]) -> (State, StateCovariance) {
        let moments = self.modes.each_ref().map(ConstantVelocityKalman::moments);
        let mean = (0..MODES).fold(State::zeros(), |acc, j| acc + moments[j].0 * weights[j]);
        let covariance = (0..MODES).fold(StateCovariance::zeros(), |acc, j| {
            let d = moments[j].0 - mean;
            acc + (moments[j].1 + d * d.transpose()) * weights[j]
        });
        (mean, covariance)
    }

    /// The reading as each mode takes it: with white error only (white), with its own noise
    /// model, white and persistent (trusted and accelerating), and with the filter's velocity
    /// prior (unreliable).
    fn readings(&self, measurement: &VelocityMeasurement) -> [VelocityMeasurement; MODES] {
        let white = VelocityMeasurement {
            persistent_covariance: Matrix2::zeros(),
            ..*measurement
        };
        let unreliable = VelocityMeasurement {
            covariance: Matrix2::identity() * self.unreliable_std_mps.powi(2),
            ..*measurement
        };
        let mut readings = [*measurement; MODES];
        readings[WHITE] = white;
        readings[UNRELIABLE] = unreliable;
        readings
    }

    /// Sets [`Self::combined`] to the mixture given this scan's measurements so far.
    fn refresh_combined(&mut self) {
        let (mean, covariance) = self.mixture(self.posterior());
        self.combined = self.modes[TRUSTED].clone();
        self.combined.set_moments(mean, covariance);
    }
}

impl TrackFilter for GpTrustFilter {
    fn start(first_centroid_xy: [f64; 2], params: KalmanParams) -> Result<Self, EvalError> {
        let filter = ConstantVelocityKalman::new(first_centroid_xy, params)?;
        Ok(Self {
            combined: filter.clone(),
            modes: std::array::from_fn(|_| filter.clone()),
            predicted: [1.0 / MODES as f64; MODES],
            log_likelihood: [0.0; MODES],
            switch_secs: None,
            unreliable_std_mps: params.initial_velocity_std_mps,
            agreeing_readings: 0,
            last_velocity_xy_mps: None,
            motion_scale_mps: PERSISTENT_ERROR_MOTION_SCALE_MPS,
        })
    }

    /// The IMM's interaction (mixing) and mode-matched prediction.
    fn predict(&mut self, dt_secs: f64) {
        let velocity = self.combined.velocity();
        let carried = self.last_velocity_xy_mps.map_or(1.0, |last| {
            let change_mps = (velocity[0] - last[0]).hypot(velocity[1] - last[1]);
            (-change_mps / self.motion_scale_mps).exp()
        });
        self.last_velocity_xy_mps = Some(velocity);
        let previous = self.posterior();
        let switch = self
            .switch_secs
            .map_or(0.0, |tau| 1.0 - (-dt_secs / tau).exp());
        let to = |i: usize, j: usize| {
            if i == j {
                1.0 - switch
            } else {
                switch / (MODES - 1) as f64
            }
        };
        let predicted: [f64; MODES] =
            std::array::from_fn(|j| (0..MODES).map(|i| to(i, j) * previous[i]).sum::<f64>());
        let mixed: [(State, StateCovariance); MODES] = std::array::from_fn(|j| {
            let (mut mean, mut covariance) = if predicted[j] > 0.0 {
                self.mixture(std::array::from_fn(|i| {
                    to(i, j) * previous[i] / predicted[j]
                }))
            } else {
                // A mode nothing can switch into keeps its own state.
                self.modes[j].moments()
            };
            if j == WHITE {
                // This mode's GP has no persistent error: its state holds none.
                mean.fixed_rows_mut::<2>(4).fill(0.0);
                covariance.fixed_rows_mut::<2>(4).fill(0.0);
                covariance.fixed_columns_mut::<2>(4).fill(0.0);
            }
            (mean, covariance)
        });
        for (j, (mode, (mean, covariance))) in self.modes.iter_mut().zip(mixed).enumerate() {
            mode.set_moments(mean, covariance);
            if carried < 1.0 {
                mode.fade_persistent_error(carried);
            }
            if j == ACCELERATING {
                mode.predict_singer(
                    dt_secs,
                    JERK_NOISE_STD_MPS3,
                    ACCELERATION_TIME_CONSTANT_SECS,
                );
            } else if j == WHITE && self.switch_secs.is_some() {
                // A track with GP readings: where they are white, they may follow a turn.
                mode.predict_with_accel_noise(dt_secs, MANOEUVRE_ACCEL_NOISE_STD_MPS2);
            } else {
                mode.predict(dt_secs);
            }
        }
        self.predicted = predicted;
        self.log_likelihood = [0.0; MODES];
        self.refresh_combined();
    }

    fn innovation(&self, centroid_xy: [f64; 2]) -> Result<Innovation, EvalError> {
        self.combined.innovation(centroid_xy)
    }

    fn centroid_gate(&self) -> Result<CentroidGate, EvalError> {
        self.combined.centroid_gate()
    }

    fn update(&mut self, centroid_xy: [f64; 2]) -> Result<Innovation, EvalError> {
        let innovation = self.innovation(centroid_xy)?;
        for (mode, ll) in self.modes.iter_mut().zip(&mut self.log_likelihood) {
            *ll += mode.update(centroid_xy)?.log_likelihood();
        }
        self.refresh_combined();
        Ok(innovation)
    }

    /// The IMM's likelihood of the reading: each mode's, weighed by its probability so far.
    fn velocity_log_likelihood(&self, measurement: &VelocityMeasurement) -> Result<f64, EvalError> {
        let readings = self.readings(measurement);
        let p = self.posterior();
        let mut ll = [f64::NEG_INFINITY; MODES];
        for j in 0..MODES {
            if p[j] > 0.0 {
                let innovation = self.modes[j].velocity_innovation(&readings[j])?;
                ll[j] = p[j].ln() + innovation.log_likelihood();
            }
        }
        let top = ll.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Ok(top + ll.iter().map(|l| (l - top).exp()).sum::<f64>().ln())
    }

    fn update_velocity(&mut self, measurement: &VelocityMeasurement) -> Result<(), EvalError> {
        if self.agrees(measurement)? {
            self.agreeing_readings += 1;
        }
        let readings = self.readings(measurement);
        let modes = self.modes.iter_mut().zip(&readings);
        for ((mode, reading), ll) in modes.zip(&mut self.log_likelihood) {
            *ll += mode.update_velocity(reading)?.log_likelihood();
        }
        self.switch_secs = Some(measurement.persistence_secs);
        self.refresh_combined();
        Ok(())
    }

    fn estimate(&self) -> Option<MotionEstimate> {
        let p = self.posterior();
        let likeliest = (0..MODES).fold(0, |best, j| if p[j] > p[best] { j } else { best });
        self.modes[likeliest].estimate()
    }

    fn velocity_updates(&self) -> usize {
        self.modes[TRUSTED].velocity_updates()
    }

    fn position(&self) -> [f64; 2] {
        self.combined.position()
    }

    fn shift_position(&mut self, delta_xy: [f64; 2]) {
        for mode in &mut self.modes {
            mode.shift_position(delta_xy);
        }
        self.combined.shift_position(delta_xy);
    }
}

#[cfg(test)]
#[path = "gp_trust_filter_tests.rs"]
mod tests;
