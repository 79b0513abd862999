//! The standard normal CDF Φ, its logarithm and the ratio φ/Φ, accurate far into the lower tail
//! where the probit squashing of GP classification (GPML eq. 6.42) evaluates them.

/// √2.
const SQRT_2: f64 = std::f64::consts::SQRT_2;
/// ½ log 2π.
const HALF_LOG_2PI: f64 = 0.918_938_533_204_672_8;
/// Below this z, erfc(−z/√2) underflows; the asymptotic series takes over.
const TAIL: f64 = -37.0;

/// Φ(z) = ½ erfc(−z/√2).
pub(crate) fn cdf(z: f64) -> f64 {
    0.5 * libm::erfc(-z / SQRT_2)
}

/// log Φ(z), finite for every finite z.
pub(crate) fn log_cdf(z: f64) -> f64 {
    if z >= TAIL {
        cdf(z).ln()
    } else {
        // Φ(z) = φ(z)/|z| · (1 − z⁻² + 3z⁻⁴ − 15z⁻⁶ + …) (Abramowitz & Stegun 26.2.12).
        let w = 1.0 / (z * z);
        -0.5 * z * z - HALF_LOG_2PI - (-z).ln() + (w * (-1.0 + w * (3.0 - 15.0 * w))).ln_1p()
    }
}

/// φ(z)/Φ(z), the derivative of log Φ(z).
pub(crate) fn mills_ratio(z: f64) -> f64 {
    (-0.5 * z * z - HALF_LOG_2PI - log_cdf(z)).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cdf_matches_known_values() {
        // Φ(0) = ½, Φ(1.959963984540054) = 0.975, Φ(−3) = 0.0013498980316301.
        assert!((cdf(0.0) - 0.5).abs() < 1e-16);
        assert!((cdf(1.959_963_984_540_054) - 0.975).abs() < 1e-15);
        assert!((cdf(-3.0) / 0.001_349_898_031_630_094_6 - 1.0).abs() < 1e-13);
    }

    #[test]
    fn log_cdf_is_continuous_across_the_tail_switch_and_finite_far_out() {
        let inside = (0.5 * libm::erfc(-TAIL / SQRT_2)).ln();
        let z = TAIL - 1e-9;
        assert!((log_cdf(z) - inside).abs() < 1e-7 * inside.abs());
        assert!(log_cdf(-1e6).is_finite() && log_cdf(-1e6) < -4e11);
        assert!(log_cdf(40.0) == 0.0 || log_cdf(40.0).abs() < 1e-300);
    }

    #[test]
    fn the_mills_ratio_is_the_derivative_of_log_cdf() {
        for z in [-50.0, -36.5, -37.5, -5.0, -0.3, 0.0, 2.0, 8.0] {
            let h = 1e-6 * f64::max(1.0, f64::abs(z));
            let fd = (log_cdf(z + h) - log_cdf(z - h)) / (2.0 * h);
            let got = mills_ratio(z);
            assert!(
                (fd - got).abs() < 1e-6 * got.abs().max(1e-3),
                "z {z}: {fd} vs {got}"
            );
        }
    }
}
