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

    /// How far from the predicted centroid a point inside the gate of squared Mahalanobis
    /// distance `chi2` can lie, metres: every point farther away lies beyond the gate, which
    /// lets the tracker skip fitting a cluster's measured point where none of the cluster could
    /// pass it. Conservative: a little wider than the gate's ellipse, and infinite when in doubt
    /// (a covariance whose inverse as computed is not positive definite, a non-finite value).
    pub fn reach_m(&self, chi2: f64) -> f64 {
        // rᵀS⁻¹r ≥ λmin(S⁻¹)·|r|², with λmin of the symmetric part of the inverse as computed.
        let m = &self.inverse;
        let (a, d, b) = (m[(0, 0)], m[(1, 1)], 0.5 * (m[(0, 1)] + m[(1, 0)]));
        let lambda_min = 0.5 * (a + d) - (0.25 * (a - d) * (a - d) + b * b).sqrt();
        // A relative margin far above the rounding of either side.
        let reach_m = (chi2 * (1.0 + 1e-6) / lambda_min).sqrt();
        if lambda_min > 0.0 && reach_m.is_finite() {
            reach_m
        } else {
            f64::INFINITY
        }
    }

    /// Whether every point within `radius_m` of `centre_xy` lies farther than `reach_m` from
    /// the predicted centroid (`false` for non-finite values).
    pub fn beyond(&self, centre_xy: [f64; 2], radius_m: f64, reach_m: f64) -> bool {
        let (dx, dy) = (
            centre_xy[0] - self.predicted_xy.x,
            centre_xy[1] - self.predicted_xy.y,
        );
        let near_m = radius_m + reach_m;
        dx * dx + dy * dy > near_m * near_m
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
    fn a_disk_the_gate_excludes_holds_no_point_inside_the_gate() {
        let gate = CentroidGate::new(
            Vector2::new(1.0, -2.0),
            Matrix2::new(0.9, 0.35, 0.35, 0.3),
            "noise",
        )
        .unwrap();
        let chi2 = 9.21;
        let (mut excluded, mut kept) = (0, 0);
        for k in 0..400 {
            let angle = 0.37 * k as f64;
            let distance_m = 0.02 * k as f64;
            let centre = [
                1.0 + distance_m * angle.cos(),
                -2.0 + distance_m * angle.sin(),
            ];
            let radius_m = 0.5 + 0.3 * (k % 5) as f64;
            if !gate.beyond(centre, radius_m, gate.reach_m(chi2)) {
                kept += 1;
                continue;
            }
            excluded += 1;
            // The disk's points on a polar lattice, its rim included: all outside the gate.
            for i in 0..=8 {
                for j in 0..32 {
                    let (r, a) = (
                        radius_m * i as f64 / 8.0,
                        j as f64 * std::f64::consts::TAU / 32.0,
                    );
                    let p = [centre[0] + r * a.cos(), centre[1] + r * a.sin()];
                    assert!(
                        gate.mahalanobis_sq(p) > chi2,
                        "disk {k}: {p:?} inside the gate"
                    );
                }
            }
        }
        assert!(
            excluded > 100 && kept > 20,
            "excluded {excluded}, kept {kept}"
        );
    }

    #[test]
    fn a_disk_reaching_into_the_gate_or_not_finite_is_never_excluded() {
        let gate = CentroidGate::new(Vector2::new(0.0, 0.0), Matrix2::identity(), "noise").unwrap();
        let reach = gate.reach_m(9.0);
        assert!((reach - 3.0).abs() < 1e-5, "{reach}");
        // The nearest point of the disk at distance 2.9 < 3 = √9.
        assert!(!gate.beyond([4.0, 0.0], 1.1, reach));
        assert!(gate.beyond([4.0, 0.0], 0.9, reach));
        assert!(!gate.beyond([f64::NAN, 0.0], 0.0, reach));
        assert!(!gate.beyond([40.0, 0.0], f64::NAN, reach));
        assert!(!gate.beyond([40.0, 0.0], 0.0, f64::INFINITY));
    }

    #[test]
    fn a_singular_covariance_is_an_error_naming_its_parameter() {
        let err = CentroidGate::new(Vector2::zeros(), Matrix2::zeros(), "noise").unwrap_err();
        assert!(err.to_string().contains("noise"), "{err}");
    }
}
