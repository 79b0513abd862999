//! `GP-KF`'s track filter: an interacting multiple model (IMM; Blom and Bar-Shalom 1988;
//! Bar-Shalom, Li and Kirubarajan 2001, §11.6) over how far the GP's velocity can be trusted.
//!
//! The GP reads some objects well scan after scan and others wildly (a crossing car behind parked
//! cars: 40-90° off for several scans, docs/results.md); one fixed measurement noise either lets
//! the wild readings pull the track off or keeps the good ones from helping; and where the GP
//! reads well (a turn) its error is white, and a persistent-error model would hold it back as a
//! bias. So each track runs three constant-velocity filters on the same centroids and GP readings:
//! - **white**: the GP's velocity with its white noise only (its state holds no persistent
//!   error); once the track has GP readings this mode lets the object turn
//!   ([`MANOEUVRE_ACCEL_NOISE_STD_MPS2`]), because a GP that reads well is what sees a turn;
//! - **trusted**: the GP's velocity with the noise [`VelocityMeasurement`] gives it (white and
//!   persistent error, thesis 3.1.4's Gaussian);
//! - **unreliable**: the same reading with the spread of the filter's own velocity prior
//!   (`KalmanParams::initial_velocity_std_mps` per axis), i.e. a reading that tells next to
//!   nothing, as a clutter measurement does.
//!
//! Each scan the three are mixed (the IMM's interaction step) with a switching probability from the
//! GP error's correlation time (`1 − exp(−Δt/τ)`, shared equally among the other modes), each
//! predicts and updates, and each one's probability is weighed by how likely it found the scan's
//! centroid and velocity (the product of the sequential innovations' likelihoods). The track
//! reports the filter of the likeliest mode (its gate reads the moment-matched mixture; the
//! association the modes' mixed likelihood of a GP reading). On its first GP reading a track holds
//! no evidence yet and the GP's reading, taken as white, is likeliest, so the filter's estimate
//! is the GP's motion from the first scan (the mixture would give a speed between the GP's and
//! rest there; docs/results.md). GP-KF reports it once the mixture's heading is known to within
//! [`MAX_REPORTED_HEADING_STD_DEG`] and a learned reading has agreed with the track
//! ([`GpTrustFilter::heading_settled`]), and before that wherever the estimate it reports states
//! its heading that tightly and the mixture to within the bar
//! ([`GpTrustFilter::reported_heading_known`]); either way only where the estimate states its
//! speed within [`MAX_REPORTED_SPEED_STD_MPS`] ([`GpTrustFilter::report`]). The filter learns per
//! track how far the GP can be trusted from what the centroids and the GP's own consistency say;
//! it never reads the truth.

use nalgebra::{Matrix2, Matrix6, Vector6};

use crate::error::EvalError;
use crate::methods::baselines::innovation::{CentroidGate, Innovation};
use crate::methods::baselines::kalman::{ConstantVelocityKalman, KalmanParams};
use crate::methods::baselines::track_filter::TrackFilter;
use crate::methods::baselines::velocity_measurement::VelocityMeasurement;
use crate::methods::estimate::MotionEstimate;

/// Number of modes.
const MODES: usize = 3;
/// Index of the mode that takes the GP's error as white (scan to scan).
const WHITE: usize = 0;
/// Index of the mode that trusts the GP's noise model with its persistent error.
const TRUSTED: usize = 1;
/// Index of the mode that takes the GP's reading as next to uninformative.
const UNRELIABLE: usize = 2;

/// The largest heading standard deviation with which a GP-KF track reports its motion: half the
/// 25° bar a heading estimate is held to (README; the thesis' real-data heading errors all lie
/// under it, Tables 4.6-4.14), so that the report's ±2σ interval lies inside that bar.
pub const MAX_REPORTED_HEADING_STD_DEG: f64 = 12.5;

/// The largest speed standard deviation with which a GP-KF track reports its motion, m/s: half
/// the 1.5 m/s bar a speed estimate is held to, so that the report's ±2σ interval lies inside that
/// bar, as [`MAX_REPORTED_HEADING_STD_DEG`] holds its heading. A settled track states about 0.6
/// m/s (the GP's persistent speed error), one on its second learned reading 0.8 (a reading's 1 m/s
/// floor, twice), so a young track reports from its third. A track that has just taken a cluster
/// whose centroid jumped can state its heading within 12.5° at 15 m/s and its speed only to 3 m/s:
/// a van turning out of a side street, read at 14.8 m/s for 6 (docs/estimator.md, "Stop 53").
pub const MAX_REPORTED_SPEED_STD_MPS: f64 = 0.75;

/// The largest heading standard deviation of the moment-matched mixture with which a track whose
/// mixture has not settled ([`MAX_REPORTED_HEADING_STD_DEG`]) may report its likeliest mode: the
/// 25° bar itself. On a track's first learned reading the modes disagree (the trusted one adds the
/// GP's persistent error, the unreliable one ignores the reading), so the mixture is wider than
/// that however tightly the GP states its reading (33° for 5°), and a new track waits for a second
/// reading that agrees with its centroids (14°). Reporting the first reading, as stop 50 did, put
/// the GP's raw reading of a track that had just restarted on the table: the oncoming truck,
/// whose track breaks as it passes beside the sensor, read 28-39° (RMSE) on two of three world
/// draws (docs/estimator.md, "Stop 51").
pub const MAX_UNSETTLED_MIXTURE_HEADING_STD_DEG: f64 = 25.0;

/// The validation gate of a learned reading against the velocity the track predicts the sensor
/// to read (χ² with 2 degrees of freedom at 99 %, the tracker's gate for centroids): a reading
/// beyond it contradicts the track, and does not count towards its report
/// ([`GpTrustFilter::heading_settled`]).
pub const READING_GATE_CHI2: f64 = 9.21;

/// The white mode's acceleration noise once the track has GP readings, m/s²: about half a g, the
/// lateral acceleration of a car turning at a city junction. Where the GP reads an object well,
/// its reading is what follows a turn, and the centroid filter's 2 m/s² (a car's longitudinal
/// acceleration) would hold the velocity to the straight line the car has left.
pub const MANOEUVRE_ACCEL_NOISE_STD_MPS2: f64 = 5.0;

/// Whether `estimate` states its heading to within [`MAX_REPORTED_HEADING_STD_DEG`]: the one
/// test behind both of GP-KF's report rules ([`GpTrustFilter::heading_settled`] on the mixture,
/// [`GpTrustFilter::reported_heading_known`] on the reported mode).
fn heading_within_report_bar(estimate: &MotionEstimate) -> bool {
    heading_std_within(estimate, MAX_REPORTED_HEADING_STD_DEG)
}

/// Whether `estimate` states its speed to within [`MAX_REPORTED_SPEED_STD_MPS`].
fn speed_within_report_bar(estimate: &MotionEstimate) -> bool {
    estimate
        .speed_var
        .is_some_and(|var| var.sqrt() <= MAX_REPORTED_SPEED_STD_MPS)
}

/// Whether `estimate` states its heading's standard deviation to be at most `std_deg`.
fn heading_std_within(estimate: &MotionEstimate, std_deg: f64) -> bool {
    estimate
        .heading_var
        .is_some_and(|var| var.sqrt() <= std_deg.to_radians())
}

/// Three constant-velocity filters, GP white, trusted and unreliable, and their probabilities.
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
}

impl GpTrustFilter {
    /// The probability that the GP's readings on this track are as trustworthy as their noise
    /// model says, given everything measured so far (read by the tests).
    #[cfg(test)]
    pub(crate) fn gp_trust(&self) -> f64 {
        1.0 - self.posterior()[UNRELIABLE]
    }

    /// Whether the track's own uncertainty supports a report (track confirmation by covariance,
    /// in place of `KF-AUTO`'s count of hits): the heading standard deviation of the
    /// moment-matched mixture (the IMM's estimate, which counts the GP's persistent error and the
    /// chance that its reading tells nothing) is at most [`MAX_REPORTED_HEADING_STD_DEG`]. A track
    /// started on one GP reading does not qualify however tight the GP says it is: the GP's
    /// stated variance is not calibrated on one scan (docs/results.md), and the persistent error
    /// its noise model adds (20°) is wider than the bar. Nor does a track that has fused no
    /// learned reading (GP or moving classifier) however many centroids settle it: its heading is
    /// `KF-AUTO`'s, read off a centroid that moves as the visible part of an object grows (an
    /// oncoming truck's, read 173° off before its first GP reading, docs/estimator.md "Stop 44").
    /// Nor, for the same reason, does a track none of whose learned readings agreed with it (fell
    /// within [`READING_GATE_CHI2`] of the velocity it predicted and stated a heading, if any,
    /// within [`MAX_REPORTED_HEADING_STD_DEG`]): a track chained through clutter from a single
    /// return moves as fast as its jumps, with a tight heading, and where it takes an object's
    /// cluster the GP contradicts it (an oncoming truck at 8 m/s read by such a track at 17 m/s
    /// and −30° while the GP read it at 95-105°, the truck driving at 180°; docs/estimator.md,
    /// "Stop 52").
    pub fn heading_settled(&self) -> bool {
        self.agreeing_readings > 0 && heading_within_report_bar(&self.mixture_estimate())
    }

    /// The motion of the moment-matched mixture (the IMM's estimate) with its covariance.
    fn mixture_estimate(&self) -> MotionEstimate {
        MotionEstimate::from_velocity_with_covariance(
            self.combined.velocity(),
            self.combined.velocity_covariance(),
        )
    }

    /// Whether the estimate the track reports (its likeliest mode's) states its heading to within
    /// [`MAX_REPORTED_HEADING_STD_DEG`], once a learned reading has agreed with the track (as for
    /// [`Self::heading_settled`]), while the mixture knows it to within
    /// [`MAX_UNSETTLED_MIXTURE_HEADING_STD_DEG`]. By this rule a track's heading is known from its
    /// second learned reading that agrees with its centroids, where the GP states it tightly (its
    /// speed from the third, [`MAX_REPORTED_SPEED_STD_MPS`]): GP-KF then covers most of the scans
    /// the estimator covers (docs/estimator.md, "Stop 50", "Stop 51" and "Stop 53"); a track on
    /// its first reading, or on readings the GP states loosely, waits for
    /// [`Self::heading_settled`].
    pub fn reported_heading_known(&self) -> bool {
        self.agreeing_readings > 0
            && heading_std_within(
                &self.mixture_estimate(),
                MAX_UNSETTLED_MIXTURE_HEADING_STD_DEG,
            )
            && self
                .estimate()
                .is_some_and(|e| heading_within_report_bar(&e))
    }

    /// What the track reports of its object on a scan where the moving classifier has not called
    /// the object moving: its likeliest mode's estimate where its heading has settled
    /// ([`Self::heading_settled`]) or, unless the scan sees the object through a gap, where the
    /// reported heading is known ([`Self::reported_heading_known`]), and where that estimate
    /// states its speed within [`MAX_REPORTED_SPEED_STD_MPS`]; else nothing.
    pub fn report(&self, seen_through_gap: bool) -> Option<MotionEstimate> {
        let reports =
            self.heading_settled() || (!seen_through_gap && self.reported_heading_known());
        reports
            .then(|| self.estimate())
            .flatten()
            .filter(speed_within_report_bar)
    }

    /// Whether a learned reading agrees with the track before it is fused: it falls within the
    /// validation gate ([`READING_GATE_CHI2`]) of the velocity the mixture predicts the sensor to
    /// read, and states its heading within [`MAX_REPORTED_HEADING_STD_DEG`] where it states one
    /// (a reading at rest, the moving classifier's, states none). A loosely stated reading fits
    /// any track and confirms none.
    fn agrees(&self, measurement: &VelocityMeasurement) -> Result<bool, EvalError> {
        let stated = MotionEstimate::from_velocity_with_covariance(
            measurement.velocity_xy_mps,
            measurement.covariance,
        );
        let tight = stated.heading_var.is_none() || heading_within_report_bar(&stated);
        let innovation = self.combined.velocity_innovation(measurement)?;
        Ok(tight && innovation.mahalanobis_sq <= READING_GATE_CHI2)
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
    fn mixture(&self, weights: [f64; MODES]) -> (Vector6<f64>, Matrix6<f64>) {
        let moments = self.modes.each_ref().map(ConstantVelocityKalman::moments);
        let mean = (0..MODES).fold(Vector6::zeros(), |acc, j| acc + moments[j].0 * weights[j]);
        let covariance = (0..MODES).fold(Matrix6::zeros(), |acc, j| {
            let d = moments[j].0 - mean;
            acc + (moments[j].1 + d * d.transpose()) * weights[j]
        });
        (mean, covariance)
    }

    /// The reading as each mode takes it: with white error only, with its own noise model
    /// (white and persistent), and with the filter's velocity prior.
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
        })
    }

    /// The IMM's interaction (mixing) and mode-matched prediction.
    fn predict(&mut self, dt_secs: f64) {
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
        let mixed: [(Vector6<f64>, Matrix6<f64>); MODES] = std::array::from_fn(|j| {
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
            match self.switch_secs {
                // A track with GP readings: where they are white, they may follow a turn.
                Some(_) if j == WHITE => {
                    mode.predict_with_accel_noise(dt_secs, MANOEUVRE_ACCEL_NOISE_STD_MPS2);
                }
                _ => mode.predict(dt_secs),
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
