//! The motion models of [`ConstantVelocityKalman`]: constant velocity (thesis eq. 3.44) for every
//! Kalman baseline and `GP-KF`'s constant-velocity modes, Singer's fading acceleration for
//! `GP-KF`'s accelerating mode; both carry the velocity sensor's persistent error as a first-order
//! Gauss-Markov process (Gelb 1974, §4.5).

use super::{ConstantVelocityKalman, StateCovariance};

impl ConstantVelocityKalman {
    /// Motion model (eq. 3.44): propagate state and covariance by `dt_secs`.
    pub fn predict(&mut self, dt_secs: f64) {
        self.predict_with_accel_noise(dt_secs, self.params.accel_noise_std_mps2);
    }

    /// [`Self::predict`] with the acceleration noise `accel_noise_std_mps2` instead of the
    /// filter's own (`GP-KF`'s white mode, which lets a well-read object turn). The constant-
    /// velocity model takes no acceleration: its state's acceleration becomes zero, value and
    /// covariance.
    pub(crate) fn predict_with_accel_noise(&mut self, dt_secs: f64, accel_noise_std_mps2: f64) {
        let dt = dt_secs;
        let decay = self.persistent_decay(dt);
        let mut f = Self::transition_without_kinematics(decay);
        let mut q = self.persistent_error_noise(decay);
        let q_var = accel_noise_std_mps2.powi(2);
        let (q_pp, q_pv, q_vv) = (
            dt.powi(4) / 4.0 * q_var,
            dt.powi(3) / 2.0 * q_var,
            dt * dt * q_var,
        );
        for axis in 0..2 {
            f[(axis, axis + 2)] = dt;
            f[(axis + 6, axis + 6)] = 0.0;
            q[(axis, axis)] = q_pp;
            q[(axis, axis + 2)] = q_pv;
            q[(axis + 2, axis)] = q_pv;
            q[(axis + 2, axis + 2)] = q_vv;
        }
        self.state = f * self.state;
        self.covariance = f * self.covariance * f.transpose() + q;
    }

    /// The Singer (1970) motion model (`GP-KF`'s accelerating mode): the acceleration is a
    /// first-order Gauss-Markov process, `ȧ = −a/τ + j` with `τ = time_constant_secs` and a
    /// white jerk `j` of power spectral density `jerk_noise_std_mps3²` × 1 s, so that an
    /// acceleration fades over about `τ` and, held by the noise alone, has the standard deviation
    /// `jerk_noise_std_mps3 · √(τ/2)`. Exact discretisation per axis: the transition of
    /// [`singer_gain`] and the process noise of [`singer_process_noise`] (Li and Jilkov 2003,
    /// "Survey of maneuvering target tracking, Part I"; as `τ` grows it becomes the
    /// Wiener-process acceleration model, Bar-Shalom, Li and Kirubarajan 2001, §6.2.3). The
    /// same jerk drives both axes: a car speeds up along its heading and a cyclist turns, and
    /// this mode takes either.
    pub(crate) fn predict_singer(
        &mut self,
        dt_secs: f64,
        jerk_noise_std_mps3: f64,
        time_constant_secs: f64,
    ) {
        let alpha = time_constant_secs.recip();
        let decay = self.persistent_decay(dt_secs);
        let mut f = Self::transition_without_kinematics(decay);
        let mut q = self.persistent_error_noise(decay);
        let gain = singer_gain(dt_secs, alpha);
        let noise = singer_process_noise(dt_secs, alpha);
        let psd = jerk_noise_std_mps3.powi(2);
        // Per axis, (position, velocity, acceleration) sit at state entries (axis, axis + 2,
        // axis + 6).
        let offsets = [0, 2, 6];
        for axis in 0..2 {
            f[(axis, axis + 2)] = dt_secs;
            for (row, g) in offsets.iter().zip(gain) {
                f[(row + axis, axis + 6)] = g;
            }
            for (row, noise_row) in offsets.iter().zip(&noise) {
                for (col, value) in offsets.iter().zip(noise_row) {
                    q[(row + axis, col + axis)] = value * psd;
                }
            }
        }
        self.state = f * self.state;
        self.covariance = f * self.covariance * f.transpose() + q;
    }

    /// Carries the persistent error over by `rho` (in (0, 1]) and restores the stationary spread
    /// it loses: a first-order Gauss-Markov step of the error alone, as the prediction takes one
    /// over time (`GpTrustFilter` takes one more as the object's motion changes).
    pub(crate) fn fade_persistent_error(&mut self, rho: f64) {
        if self.persistent.is_none() {
            return;
        }
        let f = Self::transition_without_kinematics(rho);
        let q = self.persistent_error_noise(rho);
        self.state = f * self.state;
        self.covariance = f * self.covariance * f.transpose() + q;
    }

    /// The transition of the velocity sensor's persistent error (first-order Gauss-Markov), which
    /// keeps the fraction `decay` of it, with every other entry held: the motion models add their
    /// kinematics to it.
    fn transition_without_kinematics(decay: f64) -> StateCovariance {
        let mut f = StateCovariance::identity();
        f[(4, 4)] = decay;
        f[(5, 5)] = decay;
        f
    }

    /// The process noise of the velocity sensor's persistent error over a step that keeps the
    /// fraction `decay` of it, zero elsewhere.
    fn persistent_error_noise(&self, decay: f64) -> StateCovariance {
        let mut q = StateCovariance::zeros();
        if let Some((stationary, _)) = self.persistent {
            q.fixed_view_mut::<2, 2>(4, 4)
                .copy_from(&(stationary * (1.0 - decay * decay)));
        }
        q
    }

    /// How much of the velocity sensor's persistent error remains after `dt_secs`.
    fn persistent_decay(&self, dt_secs: f64) -> f64 {
        self.persistent.map_or(1.0, |(_, persistence_secs)| {
            (-dt_secs / persistence_secs).exp()
        })
    }
}

/// How an acceleration held at the start of an interval of `s` seconds moves the (position,
/// velocity, acceleration) of the Singer model with `alpha = 1/τ` by its end: the last column of
/// its transition, `((αs − 1 + e^(−αs))/α², (1 − e^(−αs))/α, e^(−αs))`. Written with `exp_m1`,
/// which keeps its precision for `αs` near zero (where it becomes `(s²/2, s, 1)`).
pub(crate) fn singer_gain(s: f64, alpha: f64) -> [f64; 3] {
    let decay_minus_one = (-alpha * s).exp_m1();
    [
        (alpha * s + decay_minus_one) / (alpha * alpha),
        -decay_minus_one / alpha,
        1.0 + decay_minus_one,
    ]
}

/// The Singer model's process noise over `dt_secs` per unit jerk spectral density, per axis
/// (position, velocity, acceleration): `∫₀^Δt g(s) g(s)ᵀ ds` with `g` = [`singer_gain`] (Van
/// Loan 1978). Integrated by 5-point Gauss-Legendre on panels over which the acceleration decays
/// by at most a fifth (`α·h ≤ 0.25`), which is exact to rounding for the exponentials and
/// low-order polynomials `g` holds, where the closed form (Singer 1970) cancels terms of order
/// `α⁻⁵` down to `Δt⁵/20` and loses its digits for a short step or a long `τ`.
pub(crate) fn singer_process_noise(dt_secs: f64, alpha: f64) -> [[f64; 3]; 3] {
    const NODES: [f64; 5] = [
        -0.906_179_845_938_664,
        -0.538_469_310_105_683_1,
        0.0,
        0.538_469_310_105_683_1,
        0.906_179_845_938_664,
    ];
    const WEIGHTS: [f64; 5] = [
        0.236_926_885_056_189_1,
        0.478_628_670_499_366_5,
        0.568_888_888_888_888_9,
        0.478_628_670_499_366_5,
        0.236_926_885_056_189_1,
    ];
    let panels = (alpha * dt_secs / 0.25).ceil().max(1.0);
    let half = dt_secs / panels / 2.0;
    let mut q = [[0.0; 3]; 3];
    for panel in 0..panels as usize {
        let centre = (2 * panel + 1) as f64 * half;
        for (node, weight) in NODES.iter().zip(WEIGHTS) {
            let g = singer_gain(centre + node * half, alpha);
            for (i, row) in q.iter_mut().enumerate() {
                for (j, value) in row.iter_mut().enumerate() {
                    *value += weight * half * g[i] * g[j];
                }
            }
        }
    }
    q
}
