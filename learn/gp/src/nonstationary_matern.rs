//! The one-dimensional non-stationary Matérn 3/2 covariance of the DGPOM paper's eq. 5 (after
//! Melkumyan & Ramos 2011): with length-scales l₁ = l(x), l₂ = l(x') at the two inputs and
//! distance d,
//!
//! k = σ² (l₁ e^{−√3 d/l₁} − l₂ e^{−√3 d/l₂}),  σ² = 2√(l₁l₂) / (l₁² − l₂²),
//!
//! a divided difference of g(l) = l e^{−√3 d/l}. As l₂ → l₁ it tends to the stationary Matérn 3/2
//! (1 + √3 d/l) e^{−√3 d/l}, and read as written it is 0/0 there. So it is evaluated in a form
//! without the difference: with u_i = √3 d/l_i, l₁ ≤ l₂ and δ = u₂ − u₁ ≤ 0,
//!
//! k = P · e^{−u₂} (1 + u₂ φ₁(δ)),  P = 2√(l₁l₂)/(l₁ + l₂),
//!
//! where φ₁(δ) = (e^δ − 1)/δ and φ₂(δ) = (e^δ − 1 − δ)/δ² (φ₁ = 1 + δφ₂) are computed by their
//! series near 0, so equal length-scales need no special case and nothing overflows. The
//! derivatives with respect to log l₁ and log l₂ come in the same form:
//! ∂/∂log l₁ of the exponential part is e^{−u₂} u₁u₂ (φ₁ − φ₂), of log l₂ it is e^{−u₂} u₁u₂ φ₂.

/// √3, the Matérn 3/2 rate.
const SQRT_3: f64 = 1.732_050_807_568_877_2;

/// Below this |δ| the φ functions are summed from their series (terms to δ¹⁷, error < 1e-17).
const SERIES_LIMIT: f64 = 1.0;

/// The non-stationary Matérn 3/2 at distance `d` between inputs with length-scales `l1` and
/// `l2` (eq. 5), and its derivatives with respect to log l₁ and log l₂: `(k, ∂k/∂log l₁,
/// ∂k/∂log l₂)`. At d = 0 it is P = 2√(l₁l₂)/(l₁ + l₂) (1 when l₁ = l₂).
pub(crate) fn nonstationary_matern32(d: f64, l1: f64, l2: f64) -> (f64, f64, f64) {
    if l1 <= l2 {
        ordered(d.abs(), l1, l2)
    } else {
        let (k, d2, d1) = ordered(d.abs(), l2, l1);
        (k, d1, d2)
    }
}

/// The kernel and its log-length-scale derivatives for l₁ ≤ l₂.
fn ordered(d: f64, l1: f64, l2: f64) -> (f64, f64, f64) {
    // P = 2√r/(1 + r) with r = l₁/l₂; ∂P/∂log l₁ = P(l₂ − l₁)/(2(l₁ + l₂)) = −∂P/∂log l₂.
    let r = l1 / l2;
    let p = 2.0 * r.sqrt() / (1.0 + r);
    let dp = p * (1.0 - r) / (2.0 * (1.0 + r));
    if d == 0.0 {
        return (p, dp, -dp); // the exponential part is 1 and flat at d = 0
    }
    let c = SQRT_3 * d;
    let (u1, u2) = (c / l1, c / l2);
    let (phi1, phi2) = phis(u2 - u1);
    let e = (-u2).exp();
    let exponential = e * (1.0 + u2 * phi1);
    let d_exp_1 = e * u1 * u2 * (phi1 - phi2);
    let d_exp_2 = e * u1 * u2 * phi2;
    (
        p * exponential,
        dp * exponential + p * d_exp_1,
        -dp * exponential + p * d_exp_2,
    )
}

/// 1/(k+2)! for k = 0 … 17: the series coefficients of φ₂.
const PHI2_SERIES: [f64; 18] = {
    let mut c = [0.0; 18];
    let mut f = 2.0;
    let mut k = 0;
    while k < 18 {
        c[k] = 1.0 / f;
        f *= (k + 3) as f64;
        k += 1;
    }
    c
};

/// φ₁(δ) = (e^δ − 1)/δ and φ₂(δ) = (e^δ − 1 − δ)/δ², with φ₁(0) = 1 and φ₂(0) = ½.
fn phis(delta: f64) -> (f64, f64) {
    if delta.abs() >= SERIES_LIMIT {
        let em1 = delta.exp_m1();
        return (em1 / delta, (em1 - delta) / (delta * delta));
    }
    // φ₂ = Σ δᵏ/(k+2)! by Horner's rule; φ₁ = 1 + δφ₂.
    let phi2 = PHI2_SERIES
        .iter()
        .rev()
        .fold(0.0_f64, |acc, c| acc * delta + c);
    (1.0 + delta * phi2, phi2)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn matern32(d: f64, l: f64) -> f64 {
        let u = SQRT_3 * d.abs() / l;
        (1.0 + u) * (-u).exp()
    }

    /// Eq. 5 exactly as printed (fine away from l₁ = l₂).
    fn as_printed(d: f64, l1: f64, l2: f64) -> f64 {
        let sigma2 = 2.0 * (l1 * l2).sqrt() / (l1 * l1 - l2 * l2);
        let g = |l: f64| l * (-SQRT_3 * d.abs() / l).exp();
        sigma2 * (g(l1) - g(l2))
    }

    #[test]
    fn equal_length_scales_give_the_stationary_matern_without_a_division_by_zero() {
        for d in [0.0, 0.3, 1.0, 2.5, 40.0] {
            for l in [0.05, 0.7, 3.0, 1e4] {
                let (k, d1, d2) = nonstationary_matern32(d, l, l);
                assert!((k - matern32(d, l)).abs() < 1e-15, "d {d}, l {l}: {k}");
                // ∂/∂log l of the Matérn is u² e^{−u}, split evenly between the two inputs.
                let u = SQRT_3 * d / l;
                let half = 0.5 * u * u * (-u).exp();
                assert!((d1 - half).abs() < 1e-14 && (d2 - half).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn distinct_length_scales_match_the_printed_formula() {
        for (d, l1, l2) in [
            (1.0, 0.5, 2.0),
            (0.2, 3.0, 1.0),
            (4.0, 1.0, 7.0),
            (0.0, 2.0, 0.3),
        ] {
            let (k, _, _) = nonstationary_matern32(d, l1, l2);
            let printed = as_printed(d, l1, l2);
            assert!(
                (k - printed).abs() < 1e-13,
                "{d} {l1} {l2}: {k} vs {printed}"
            );
        }
    }

    #[test]
    fn the_kernel_is_symmetric_and_continuous_as_the_length_scales_meet() {
        let (d, l) = (1.3, 0.9);
        let at = nonstationary_matern32(d, l, l).0;
        for eps in [1e-3, 1e-6, 1e-9, 1e-12] {
            let (a, b) = (
                nonstationary_matern32(d, l, l * (1.0 + eps)),
                nonstationary_matern32(d, l * (1.0 + eps), l),
            );
            assert_eq!(a.0, b.0);
            assert_eq!((a.1, a.2), (b.2, b.1));
            assert!((a.0 - at).abs() < 2.0 * eps, "eps {eps}: {} vs {at}", a.0);
        }
    }

    #[test]
    fn the_log_length_scale_derivatives_match_central_differences() {
        let h: f64 = 1e-6;
        for (d, l1, l2) in [
            (1.0, 0.5, 2.0),
            (0.7, 1.0, 1.0 + 1e-7),
            (3.0, 4.0, 1.5),
            (0.4, 0.2, 0.2),
            (2.0, 1e-2, 5.0),
        ] {
            let (_, d1, d2) = nonstationary_matern32(d, l1, l2);
            let f = |a: f64, b: f64| nonstationary_matern32(d, a, b).0;
            let n1 = (f(l1 * h.exp(), l2) - f(l1 * (-h).exp(), l2)) / (2.0 * h);
            let n2 = (f(l1, l2 * h.exp()) - f(l1, l2 * (-h).exp())) / (2.0 * h);
            assert!((d1 - n1).abs() < 1e-8, "{d} {l1} {l2}: ∂1 {d1} vs {n1}");
            assert!((d2 - n2).abs() < 1e-8, "{d} {l1} {l2}: ∂2 {d2} vs {n2}");
        }
    }

    #[test]
    fn a_gram_matrix_over_points_with_varying_length_scales_is_positive_semidefinite() {
        // Times 0 … 5 s and length-scales from 0.1 to 10 s, interleaved.
        let points: Vec<(f64, f64)> = (0..24)
            .map(|i| {
                (
                    f64::from(i % 6),
                    10f64.powf(f64::from((i * 7) % 11) / 5.0 - 1.0),
                )
            })
            .collect();
        let n = points.len();
        let k = nalgebra::DMatrix::from_fn(n, n, |i, j| {
            nonstationary_matern32(points[i].0 - points[j].0, points[i].1, points[j].1).0
        });
        let min = k.symmetric_eigenvalues().min();
        assert!(min > -1e-12, "smallest eigenvalue {min}");
    }

    #[test]
    fn the_series_and_the_closed_form_of_phi_agree_at_the_switch() {
        for delta in [-SERIES_LIMIT, -0.999_999, -1.000_001] {
            let (a1, a2) = phis(delta);
            let em1 = delta.exp_m1();
            assert!((a1 - em1 / delta).abs() < 1e-15);
            assert!((a2 - (em1 - delta) / (delta * delta)).abs() < 1e-14);
        }
    }
}
