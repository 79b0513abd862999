//! Constant-velocity Kalman filter on a cluster centroid (thesis 3.2.2, eqs. 3.42-3.45).
//!
//! State `(x, y, vx, vy)` in the world frame. Motion model `x_t = F x_{t−1} + w` with
//! `F = [[I, Δt·I], [0, I]]` and discrete white-noise acceleration `Q = σ_a²·[[Δt⁴/4, Δt³/2],
//! [Δt³/2, Δt²]] ⊗ I₂` (Bar-Shalom; reference/baselines.md §2.1). Measurement: the cluster
//! centroid, `z = H x + v`, `H = [I 0]`, `R = σ_z² I`.
//!
//! Defaults and why: `σ_a = 2 m/s²` (half to one times the peak acceleration of a car in urban
//! traffic); `σ_z = 0.5 m`, dominated not by range noise (~2 cm) but by the partial-view centroid
//! shift as the visible side of a 4.5 m car changes (the thesis picks σ_z "considering the maximum
//! error of the estimated center of mass"). Initialisation from the first measurement with zero
//! velocity and a large velocity standard deviation (10 m/s), so the second measurement acts as a
//! two-point initiation; an estimate is reported from the second update on.
//! The covariance update uses the Joseph form, which keeps P symmetric positive definite.
//!
//! `GP-KF` also measures the velocity directly ([`VelocityMeasurement`]), and that sensor's error
//! persists from scan to scan, so the state carries it: `(x, y, vx, vy, bx, by)`, the measured
//! velocity is `v + b + w`, and `b` is first-order Gauss-Markov with the measurement's persistent
//! covariance and correlation time (Gelb 1974, §4.5). Until a velocity is measured `b` is zero
//! with zero covariance, so a filter fed centroids only (`KF`, `KF-AUTO`) is the four-state
//! filter above, value for value.
//!
//! `GP-KF` also runs Singer's (1970) fading-acceleration filter among its modes, so the state
//! ends in the acceleration `(ax, ay)`: [`ConstantVelocityKalman::predict`] sets it to zero, value
//! and covariance (the constant-velocity model, augmented as an interacting multiple model mixes
//! it); [`ConstantVelocityKalman::predict_singer`] carries it (`kalman_motion.rs`).

use nalgebra::{ArrayStorage, Matrix2, SMatrix, SVector, Vector2};

use crate::error::EvalError;
use crate::methods::baselines::innovation::{CentroidGate, Innovation};
use crate::methods::baselines::velocity_measurement::VelocityMeasurement;
use crate::methods::estimate::MotionEstimate;

/// Length of the state `(x, y, vx, vy, bx, by, ax, ay)`.
const STATE: usize = 8;
/// The state vector.
pub(crate) type State = SVector<f64, STATE>;
/// The state's covariance.
pub(crate) type StateCovariance = SMatrix<f64, STATE, STATE>;
/// A measurement's gain.
type Gain = SMatrix<f64, STATE, 2>;
/// A measurement's model, two rows of the state.
type MeasurementModel = SMatrix<f64, 2, STATE>;

/// Noise and initialisation of the constant-velocity filter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KalmanParams {
    /// Standard deviation of the white acceleration noise σ_a, m/s².
    pub accel_noise_std_mps2: f64,
    /// Standard deviation of the centroid measurement per axis σ_z, metres.
    pub centroid_noise_std_m: f64,
    /// Initial standard deviation of each velocity component, m/s.
    pub initial_velocity_std_mps: f64,
    /// Updates (measurements taken in) before the filter reports an estimate.
    pub min_updates_for_estimate: usize,
}

impl Default for KalmanParams {
    fn default() -> Self {
        Self {
            accel_noise_std_mps2: 2.0,
            centroid_noise_std_m: 0.5,
            initial_velocity_std_mps: 10.0,
            min_updates_for_estimate: 2,
        }
    }
}

impl KalmanParams {
    /// Checks that every noise is positive and finite.
    pub fn validate(&self) -> Result<(), EvalError> {
        positive(
            "KalmanParams.accel_noise_std_mps2",
            self.accel_noise_std_mps2,
        )?;
        positive(
            "KalmanParams.centroid_noise_std_m",
            self.centroid_noise_std_m,
        )?;
        positive(
            "KalmanParams.initial_velocity_std_mps",
            self.initial_velocity_std_mps,
        )
    }
}

/// A constant-velocity Kalman filter tracking one centroid.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstantVelocityKalman {
    state: State,
    covariance: StateCovariance,
    /// The persistent error of the velocity measurements taken so far (their latest covariance
    /// and correlation time), once there was one.
    persistent: Option<(Matrix2<f64>, f64)>,
    params: KalmanParams,
    updates: usize,
    velocity_updates: usize,
}

/// Column `[1, 0]` or `[0, 1]` of a measurement model: the state entry counts on the x or y axis.
const X: [f64; 2] = [1.0, 0.0];
const Y: [f64; 2] = [0.0, 1.0];
const NONE: [f64; 2] = [0.0, 0.0];
/// A centroid measurement sees the position (column-major: one `[x, y]` pair per state entry).
const H: MeasurementModel =
    MeasurementModel::from_array_storage(ArrayStorage([X, Y, NONE, NONE, NONE, NONE, NONE, NONE]));
/// A velocity measurement sees the velocity plus the measuring GP's persistent error.
const H_VELOCITY: MeasurementModel =
    MeasurementModel::from_array_storage(ArrayStorage([NONE, NONE, X, Y, X, Y, NONE, NONE]));

impl ConstantVelocityKalman {
    /// A filter started at the first centroid measurement, at rest, with a wide velocity prior.
    ///
    /// ```
    /// use patchflow_eval::{ConstantVelocityKalman, KalmanParams};
    /// let mut kf = ConstantVelocityKalman::new([0.0, 0.0], KalmanParams::default()).unwrap();
    /// for k in 1..20 {
    ///     kf.predict(0.1);
    ///     kf.update([k as f64 * 0.5, 0.0]).unwrap();
    /// }
    /// assert!((kf.velocity()[0] - 5.0).abs() < 0.1);
    /// ```
    pub fn new(first_centroid_xy: [f64; 2], params: KalmanParams) -> Result<Self, EvalError> {
        params.validate()?;
        let pos_var = params.centroid_noise_std_m.powi(2);
        let vel_var = params.initial_velocity_std_mps.powi(2);
        Ok(Self {
            state: State::from_column_slice(&[
                first_centroid_xy[0],
                first_centroid_xy[1],
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
            ]),
            covariance: StateCovariance::from_diagonal(&State::from_column_slice(&[
                pos_var, pos_var, vel_var, vel_var, 0.0, 0.0, 0.0, 0.0,
            ])),
            persistent: None,
            params,
            updates: 1,
            velocity_updates: 0,
        })
    }

    /// The innovation of a centroid measurement against the current (predicted) state.
    pub fn innovation(&self, centroid_xy: [f64; 2]) -> Result<Innovation, EvalError> {
        Ok(self.centroid_gate()?.innovation(centroid_xy))
    }

    /// The predicted centroid `Hx` and `S = HPHᵀ + R` with its inverse, for any centroid.
    pub fn centroid_gate(&self) -> Result<CentroidGate, EvalError> {
        CentroidGate::new(
            H * self.state,
            H * self.covariance * H.transpose() + self.measurement_covariance(),
            "KalmanParams.centroid_noise_std_m",
        )
    }

    /// Sensor model (eq. 3.45): correct the state with a centroid measurement.
    pub fn update(&mut self, centroid_xy: [f64; 2]) -> Result<Innovation, EvalError> {
        let gate = self.centroid_gate()?;
        let innovation = gate.innovation(centroid_xy);
        let gain: Gain = self.covariance * H.transpose() * gate.inverse();
        self.state += gain * innovation.residual_m;
        let i_kh = StateCovariance::identity() - gain * H;
        self.covariance = i_kh * self.covariance * i_kh.transpose()
            + gain * self.measurement_covariance() * gain.transpose();
        self.updates += 1;
        Ok(innovation)
    }

    /// The innovation of a velocity measurement against the velocity this track predicts the
    /// sensor to read (its velocity plus the sensor's persistent error), `S = H_v P H_vᵀ + Σ`:
    /// how well a cluster's measured velocity fits this track, before any update.
    pub fn velocity_innovation(
        &self,
        measurement: &VelocityMeasurement,
    ) -> Result<Innovation, EvalError> {
        Ok(self.velocity_innovation_and_inverse(measurement)?.0)
    }

    /// [`Self::velocity_innovation`] and its `S⁻¹`.
    fn velocity_innovation_and_inverse(
        &self,
        measurement: &VelocityMeasurement,
    ) -> Result<(Innovation, Matrix2<f64>), EvalError> {
        check_persistence(measurement)?;
        let prior = self.with_persistent_error_prior(measurement);
        let predicted = H_VELOCITY * prior.state;
        let residual = Vector2::new(
            measurement.velocity_xy_mps[0] - predicted[0],
            measurement.velocity_xy_mps[1] - predicted[1],
        );
        Innovation::with_inverse(
            residual,
            H_VELOCITY * prior.covariance * H_VELOCITY.transpose() + measurement.covariance,
            "VelocityMeasurement.covariance",
        )
    }

    /// Corrects the state with a direct velocity measurement (`GP-KF`: the GP's merged heading
    /// and speed, thesis 3.1.4), `z = [0 I I] x + w`, `w ~ N(0, Σ)` (the last block is the
    /// sensor's persistent error, see the module's doc); Joseph-form covariance update.
    /// Returns the velocity innovation.
    pub fn update_velocity(
        &mut self,
        measurement: &VelocityMeasurement,
    ) -> Result<Innovation, EvalError> {
        let (innovation, s_inv) = self.velocity_innovation_and_inverse(measurement)?;
        *self = self.with_persistent_error_prior(measurement);
        let h = H_VELOCITY;
        let gain: Gain = self.covariance * h.transpose() * s_inv;
        self.state += gain * innovation.residual_m;
        let i_kh = StateCovariance::identity() - gain * h;
        self.covariance = i_kh * self.covariance * i_kh.transpose()
            + gain * measurement.covariance * gain.transpose();
        self.velocity_updates += 1;
        Ok(innovation)
    }

    /// The state and its covariance (for mixing the filters of an interacting multiple model).
    pub(crate) fn moments(&self) -> (State, StateCovariance) {
        (self.state, self.covariance)
    }

    /// Replaces the state and its covariance (an interacting multiple model's mixed start).
    pub(crate) fn set_moments(&mut self, state: State, covariance: StateCovariance) {
        self.state = state;
        self.covariance = covariance;
    }

    /// The filter as a velocity measurement finds it: at the first one, the measuring GP's
    /// persistent error enters the state at zero with that measurement's covariance; each one
    /// sets the covariance and correlation time the error drifts with.
    fn with_persistent_error_prior(&self, measurement: &VelocityMeasurement) -> Self {
        let mut prior = self.clone();
        if prior.persistent.is_none() {
            prior
                .covariance
                .fixed_view_mut::<2, 2>(4, 4)
                .copy_from(&measurement.persistent_covariance);
        }
        prior.persistent = Some((
            measurement.persistent_covariance,
            measurement.persistence_secs,
        ));
        prior
    }

    /// Moves the estimated position by `delta_xy`, velocity and covariance unchanged (the track
    /// measures another point of its object from now on, `reference_point`).
    pub fn shift_position(&mut self, delta_xy: [f64; 2]) {
        self.state[0] += delta_xy[0];
        self.state[1] += delta_xy[1];
    }

    /// Filtered position, metres.
    pub fn position(&self) -> [f64; 2] {
        [self.state[0], self.state[1]]
    }

    /// Filtered velocity, m/s.
    pub fn velocity(&self) -> [f64; 2] {
        [self.state[2], self.state[3]]
    }

    /// Covariance of the velocity, (m/s)².
    pub fn velocity_covariance(&self) -> Matrix2<f64> {
        self.covariance.fixed_view::<2, 2>(2, 2).into_owned()
    }

    /// Velocity measurements taken in so far.
    pub fn velocity_updates(&self) -> usize {
        self.velocity_updates
    }

    /// Measurements taken in so far (the first one included).
    pub fn updates(&self) -> usize {
        self.updates
    }

    /// The motion estimate (heading, speed and their variances), once enough updates were made
    /// or a velocity was measured (from the first scan on, for `GP-KF`).
    pub fn estimate(&self) -> Option<MotionEstimate> {
        let enough = self.updates >= self.params.min_updates_for_estimate;
        (enough || self.velocity_updates > 0).then(|| {
            MotionEstimate::from_velocity_with_covariance(
                self.velocity(),
                self.velocity_covariance(),
            )
        })
    }

    fn measurement_covariance(&self) -> Matrix2<f64> {
        Matrix2::identity() * self.params.centroid_noise_std_m.powi(2)
    }
}

/// A measurement's correlation time must be positive (zero would be white noise, which the
/// white covariance already is) and finite.
fn check_persistence(measurement: &VelocityMeasurement) -> Result<(), EvalError> {
    positive(
        "VelocityMeasurement.persistence_secs",
        measurement.persistence_secs,
    )
}

/// Errors, naming the parameter, unless `value` is positive and finite.
fn positive(name: &'static str, value: f64) -> Result<(), EvalError> {
    if value > 0.0 && value.is_finite() {
        Ok(())
    } else {
        Err(EvalError::BadParameter {
            name,
            reason: format!("must be positive and finite, got {value}"),
        })
    }
}

#[path = "kalman_motion.rs"]
mod motion;

#[cfg(test)]
#[path = "kalman_tests.rs"]
mod tests;
