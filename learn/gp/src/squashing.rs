//! The probit squashing of probabilistic least-squares classification (GPML §6.5, eq. 6.42):
//! p(y = +1 | μ, σ²) = Φ((αμ + β) / √(1 + α²σ²)), with α, β chosen to maximise the leave-one-out
//! predictive log probability Σ_i log Φ(y_i (αμ_{−i} + β) / √(1 + α²σ²_{−i})).
//!
//! σ² is the *latent* variance: the formula is ∫ Φ(αf + β) N(f | μ, σ²) df, the probit link applied
//! to the uncertain latent function, and the link itself models the label noise (GPML's `infLOO`
//! also hands the latent leave-one-out variance to the probit likelihood). With the variance of y,
//! label noise would be counted twice and α could not saturate the probabilities of noisy labels.

use nalgebra::DVector;
use serde::{Deserialize, Serialize};

use super::lbfgs::{LbfgsOptions, minimize};
use super::loo::LooMoments;
use super::normal::{cdf, log_cdf, mills_ratio};
use crate::{GpError, Result};

/// Optimiser limits of the two-parameter fit; the objective is smooth and cheap (O(N) per call).
const FIT_OPTIONS: LbfgsOptions = LbfgsOptions {
    max_iters: 200,
    max_evals: 600,
    memory: 5,
    grad_tol: 1e-9,
    rel_tol: 1e-13,
};

/// The fitted affine map and probit link from a GP's predictive moments to a class probability.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Squashing {
    /// Scale α applied to the predictive mean (grows as the labels become more reliable).
    pub alpha: f64,
    /// Offset β (a class prior in probit units).
    pub beta: f64,
}

impl Default for Squashing {
    /// α = 1, β = 0: Φ(μ / √(1 + σ²)), the squashing of an uncalibrated regression on ±1 labels.
    fn default() -> Self {
        Self {
            alpha: 1.0,
            beta: 0.0,
        }
    }
}

impl Squashing {
    /// The probit argument (αμ + β) / √(1 + α²σ²).
    fn argument(&self, mean: f64, var: f64) -> f64 {
        (self.alpha * mean + self.beta) / (1.0 + self.alpha * self.alpha * var).sqrt()
    }

    /// p(y = +1) for a predictive mean `mean` and variance `var` (GPML eq. 6.42).
    pub fn probability(&self, mean: f64, var: f64) -> f64 {
        cdf(self.argument(mean, var))
    }

    /// −Σ_i log p(y_i | μ_{−i}, σ²_{−i}) and its gradient in (α, β).
    fn loo_objective(&self, loo: &LooMoments, labels: &[bool]) -> (f64, DVector<f64>) {
        let (mut f, mut d_alpha, mut d_beta) = (0.0, 0.0, 0.0);
        for ((&mu, &var), &label) in loo.mean.iter().zip(loo.var_latent.iter()).zip(labels) {
            let sign = if label { 1.0 } else { -1.0 };
            let scale = 1.0 + self.alpha * self.alpha * var;
            let t = sign * self.argument(mu, var);
            f -= log_cdf(t);
            let dl_dt = -mills_ratio(t);
            // ∂t/∂α = y(μ − αβσ²)/(1 + α²σ²)^{3/2}, ∂t/∂β = y/(1 + α²σ²)^{1/2}.
            d_alpha += dl_dt * sign * (mu - self.alpha * self.beta * var) / (scale * scale.sqrt());
            d_beta += dl_dt * sign / scale.sqrt();
        }
        (f, DVector::from_vec(vec![d_alpha, d_beta]))
    }

    /// Maximises the leave-one-out log predictive probability of `labels` (true = class +1) over
    /// (α, β); returns the squashing and the maximised log probability.
    pub(crate) fn fit(loo: &LooMoments, labels: &[bool]) -> Result<(Self, f64)> {
        let outcome = minimize(
            |theta| {
                let s = Self {
                    alpha: theta[0],
                    beta: theta[1],
                };
                Ok(s.loo_objective(loo, labels))
            },
            DVector::from_vec(vec![1.0, 0.0]),
            FIT_OPTIONS,
        )?;
        let fitted = Self {
            alpha: outcome.x[0],
            beta: outcome.x[1],
        };
        if !(fitted.alpha.is_finite() && fitted.beta.is_finite() && outcome.f.is_finite()) {
            return Err(GpError::Numerical(
                "the leave-one-out fit of the probit squashing diverged".into(),
            ));
        }
        Ok((fitted, -outcome.f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn moments() -> (LooMoments, Vec<bool>) {
        let mean = DVector::from_vec(vec![0.9, 0.4, -0.2, -0.8, 0.1, -0.5, 0.7]);
        let var = DVector::from_vec(vec![0.3, 0.5, 0.4, 0.2, 0.9, 0.6, 0.35]);
        let labels = vec![true, true, false, false, false, true, true];
        let var_y = var.map(|v| v + 0.1);
        (
            LooMoments {
                mean,
                var_latent: var,
                var_y,
            },
            labels,
        )
    }

    #[test]
    fn the_loo_gradient_matches_central_differences() {
        let (loo, labels) = moments();
        let s = Squashing {
            alpha: 1.7,
            beta: -0.3,
        };
        let (_, g) = s.loo_objective(&loo, &labels);
        let h = 1e-6;
        for (i, want) in g.iter().enumerate() {
            let shifted = |d: f64| {
                let mut t = s;
                if i == 0 {
                    t.alpha += d;
                } else {
                    t.beta += d;
                }
                t.loo_objective(&loo, &labels).0
            };
            let fd = (shifted(h) - shifted(-h)) / (2.0 * h);
            assert!((fd - want).abs() < 1e-7, "param {i}: {fd} vs {want}");
        }
    }

    #[test]
    fn the_fit_is_a_stationary_point_that_beats_the_default() {
        let (loo, labels) = moments();
        let (fitted, log_p) = Squashing::fit(&loo, &labels).expect("fits");
        let (f_default, _) = Squashing::default().loo_objective(&loo, &labels);
        assert!(log_p >= -f_default, "{log_p} < {}", -f_default);
        let (_, g) = fitted.loo_objective(&loo, &labels);
        assert!(g.amax() < 1e-6, "gradient {g}");
    }

    #[test]
    fn probabilities_lie_in_the_unit_interval_and_follow_the_mean() {
        let s = Squashing {
            alpha: 3.0,
            beta: 0.2,
        };
        let (lo, hi) = (s.probability(-1.0, 0.1), s.probability(1.0, 0.1));
        assert!(0.0 < lo && lo < 0.5 && 0.5 < hi && hi < 1.0);
        // More predictive variance pulls the probability towards Φ(β/…) ≈ ½.
        assert!(s.probability(1.0, 10.0) < hi);
    }
}
