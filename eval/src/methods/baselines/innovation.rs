//! The innovation of a measurement against a track's prediction (`y = z − Hx`, `S = HPHᵀ + R`),
//! and a track's gate for centroids: the predicted centroid, `S` and `S⁻¹`, which depend on the
//! track alone. The tracker scores every track against every cluster of a scan; building the gate
//! once per track, not once per pair, leaves one 2 × 2 product per pair (docs/speed.md, "Issue
//! 24's time targets: stop 47").

use nalgebra::{Matrix2, Vector2};

use crate::error::EvalError;

/// The innovation of a measurement against the predicted state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Innovation {
    /// Residual: metres for a centroid, m/s for a velocity.
    pub residual_m: Vector2<f64>,
    /// Its covariance, m² (or (m/s)²).
    pub covariance: Matrix2<f64>,
    /// Squared Mahalanobis distance `yᵀ S⁻¹ y` (χ² with 2 dof under the model).
    pub mahalanobis_sq: f64,
}

impl Innovation {
    /// The innovation of `residual_m` under `covariance`, and `S⁻¹`, which the update's gain
    /// reuses; a singular `S` is an error naming `noise`, the parameter that sets it.
    pub(crate) fn with_inverse(
        residual_m: Vector2<f64>,
        covariance: Matrix2<f64>,
        noise: &'static str,
    ) -> Result<(Self, Matrix2<f64>), EvalError> {
        let inverse = invert(&covariance, noise)?;
        Ok((Self::of(residual_m, covariance, &inverse), inverse))
    }

    fn of(residual_m: Vector2<f64>, covariance: Matrix2<f64>, inverse: &Matrix2<f64>) -> Self {
        Self {
            residual_m,
            covariance,
            mahalanobis_sq: residual_m.dot(&(inverse * residual_m)),
        }
    }

    /// `ln N(y; 0, S)`: how likely the filter found the measurement.
    pub fn log_likelihood(&self) -> f64 {
        let det = self.covariance.determinant().max(f64::MIN_POSITIVE);
        -0.5 * (self.mahalanobis_sq + det.ln()) - (2.0 * std::f64::consts::PI).ln()
    }
}

/// What a predicted track expects of a centroid measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CentroidGate {
    predicted_xy: Vector2<f64>,
    covariance: Matrix2<f64>,
    inverse: Matrix2<f64>,
}

impl CentroidGate {
    /// The gate of a track predicting the centroid `predicted_xy` with innovation covariance
    /// `covariance`; a singular covariance is an error naming `noise`, the parameter that sets it.
    pub fn new(
        predicted_xy: Vector2<f64>,
        covariance: Matrix2<f64>,
        noise: &'static str,
    ) -> Result<Self, EvalError> {
        Ok(Self {
            predicted_xy,
            covariance,
            inverse: invert(&covariance, noise)?,
        })
    }

    /// `S⁻¹`, which the update's gain reuses.
    pub fn inverse(&self) -> &Matrix2<f64> {
        &self.inverse
    }

    /// The innovation of the centroid `centroid_xy`.
    pub fn innovation(&self, centroid_xy: [f64; 2]) -> Innovation {
        let z = Vector2::new(centroid_xy[0], centroid_xy[1]);
        Innovation::of(z - self.predicted_xy, self.covariance, &self.inverse)
    }

    /// The squared Mahalanobis distance of `centroid_xy`, as [`Self::innovation`] gives it.
    pub fn mahalanobis_sq(&self, centroid_xy: [f64; 2]) -> f64 {
        self.innovation(centroid_xy).mahalanobis_sq
    }
}

/// `S⁻¹`, or an error naming `noise` when `S` is singular.
fn invert(covariance: &Matrix2<f64>, noise: &'static str) -> Result<Matrix2<f64>, EvalError> {
    covariance
        .try_inverse()
        .ok_or_else(|| EvalError::BadParameter {
            name: noise,
            reason: "innovation covariance is singular".into(),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gate_scales_the_residual_by_the_inverse_covariance() {
        let gate = CentroidGate::new(
            Vector2::new(1.0, 2.0),
            Matrix2::new(4.0, 0.0, 0.0, 0.25),
            "noise",
        )
        .unwrap();
        // Residual (2, 0.5): 2²/4 + 0.5²/0.25 = 2, to rounding.
        assert!((gate.mahalanobis_sq([3.0, 2.5]) - 2.0).abs() < 1e-12);
        assert_eq!(gate.innovation([1.0, 2.0]).mahalanobis_sq, 0.0);
    }

    #[test]
    fn the_gate_gives_the_innovation_its_residual_and_covariance_would() {
        let covariance = Matrix2::new(0.7, 0.2, 0.2, 0.4);
        let gate = CentroidGate::new(Vector2::new(-3.0, 5.0), covariance, "noise").unwrap();
        let (direct, _) =
            Innovation::with_inverse(Vector2::new(4.5, -1.25), covariance, "noise").unwrap();
        assert_eq!(gate.innovation([1.5, 3.75]), direct, "bit for bit");
    }

    #[test]
    fn a_singular_covariance_is_an_error_naming_its_parameter() {
        let err = CentroidGate::new(Vector2::zeros(), Matrix2::zeros(), "noise").unwrap_err();
        assert!(err.to_string().contains("noise"), "{err}");
    }
}
