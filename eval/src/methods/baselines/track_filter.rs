//! What the multi-target tracker needs of a track's filter: a prediction, a centroid gate and
//! update, a velocity likelihood and update, and the motion estimate it reports. `KF-AUTO` tracks
//! with one constant-velocity filter ([`ConstantVelocityKalman`]); `GP-KF` with an interacting
//! multiple model over how far the GP can be trusted ([`crate::methods::baselines::gp_trust_filter::GpTrustFilter`]).

use crate::error::EvalError;
use crate::methods::baselines::innovation::{CentroidGate, Innovation};
use crate::methods::baselines::kalman::{ConstantVelocityKalman, KalmanParams};
use crate::methods::baselines::velocity_measurement::VelocityMeasurement;
use crate::methods::estimate::MotionEstimate;

/// A track's filter, as the tracker drives it.
pub trait TrackFilter: Clone + std::fmt::Debug {
    /// A filter started at the first centroid measurement.
    fn start(first_centroid_xy: [f64; 2], params: KalmanParams) -> Result<Self, EvalError>;
    /// Propagates the filter by `dt_secs`.
    fn predict(&mut self, dt_secs: f64);
    /// The innovation of a centroid against the predicted state.
    fn innovation(&self, centroid_xy: [f64; 2]) -> Result<Innovation, EvalError>;
    /// The predicted state's gate for any centroid (the association reads it for every cluster).
    fn centroid_gate(&self) -> Result<CentroidGate, EvalError>;
    /// Corrects the filter with a centroid.
    fn update(&mut self, centroid_xy: [f64; 2]) -> Result<Innovation, EvalError>;
    /// `ln p(reading | this track)`: how likely the track, as predicted, finds a measured
    /// velocity (the association compares it with a new track's, [`crate::methods::baselines::tracker`]).
    fn velocity_log_likelihood(&self, measurement: &VelocityMeasurement) -> Result<f64, EvalError>;
    /// Corrects the filter with a measured velocity.
    fn update_velocity(&mut self, measurement: &VelocityMeasurement) -> Result<(), EvalError>;
    /// The motion estimate, once the filter reports one.
    fn estimate(&self) -> Option<MotionEstimate>;
    /// Velocity measurements taken in so far.
    fn velocity_updates(&self) -> usize;
    /// The estimated position of the point the track measures, world frame, metres.
    fn position(&self) -> [f64; 2];
    /// Moves the estimated position by `delta_xy` and nothing else: the track measures another
    /// point of its object from now on (`reference_point`), which is not motion.
    fn shift_position(&mut self, delta_xy: [f64; 2]);
}

impl TrackFilter for ConstantVelocityKalman {
    fn start(first_centroid_xy: [f64; 2], params: KalmanParams) -> Result<Self, EvalError> {
        Self::new(first_centroid_xy, params)
    }

    fn predict(&mut self, dt_secs: f64) {
        ConstantVelocityKalman::predict(self, dt_secs);
    }

    fn innovation(&self, centroid_xy: [f64; 2]) -> Result<Innovation, EvalError> {
        ConstantVelocityKalman::innovation(self, centroid_xy)
    }

    fn centroid_gate(&self) -> Result<CentroidGate, EvalError> {
        ConstantVelocityKalman::centroid_gate(self)
    }

    fn update(&mut self, centroid_xy: [f64; 2]) -> Result<Innovation, EvalError> {
        ConstantVelocityKalman::update(self, centroid_xy)
    }

    fn velocity_log_likelihood(&self, measurement: &VelocityMeasurement) -> Result<f64, EvalError> {
        Ok(self.velocity_innovation(measurement)?.log_likelihood())
    }

    fn update_velocity(&mut self, measurement: &VelocityMeasurement) -> Result<(), EvalError> {
        ConstantVelocityKalman::update_velocity(self, measurement).map(|_| ())
    }

    fn estimate(&self) -> Option<MotionEstimate> {
        ConstantVelocityKalman::estimate(self)
    }

    fn velocity_updates(&self) -> usize {
        ConstantVelocityKalman::velocity_updates(self)
    }

    fn position(&self) -> [f64; 2] {
        ConstantVelocityKalman::position(self)
    }

    fn shift_position(&mut self, delta_xy: [f64; 2]) {
        ConstantVelocityKalman::shift_position(self, delta_xy);
    }
}
