//! `GP-KF`'s report rules: when a track's estimate goes on the table ([`GpTrustFilter::report`]),
//! and which learned readings count as agreeing with a track. A track reports only what its own
//! uncertainty supports, in place of `KF-AUTO`'s count of hits (docs/estimator.md, "Stop 50" to
//! "Stop 53").

use crate::error::EvalError;
use crate::methods::baselines::track_filter::TrackFilter;
use crate::methods::baselines::velocity_measurement::VelocityMeasurement;
use crate::methods::estimate::MotionEstimate;

use super::GpTrustFilter;

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

/// Whether `estimate` states its heading to within [`MAX_REPORTED_HEADING_STD_DEG`]: the one
/// test behind both of GP-KF's report rules ([`GpTrustFilter::heading_settled`] on the mixture,
/// [`GpTrustFilter::reported_heading_known`] on the reported mode).
pub(super) fn heading_within_report_bar(estimate: &MotionEstimate) -> bool {
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

impl GpTrustFilter {
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
    pub(super) fn mixture_estimate(&self) -> MotionEstimate {
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
    pub(super) fn agrees(&self, measurement: &VelocityMeasurement) -> Result<bool, EvalError> {
        let stated = MotionEstimate::from_velocity_with_covariance(
            measurement.velocity_xy_mps,
            measurement.covariance,
        );
        let tight = stated.heading_var.is_none() || heading_within_report_bar(&stated);
        let innovation = self.combined.velocity_innovation(measurement)?;
        Ok(tight && innovation.mahalanobis_sq <= READING_GATE_CHI2)
    }
}
