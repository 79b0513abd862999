//! The radial profiles ρ(r²) of the stationary kernels and the groups of input columns they act
//! on: a kernel is s · Π_g ρ_g(r_g²) over consecutive column groups.

use serde::{Deserialize, Serialize};

use super::exp::exp;

/// √3, the Matérn 3/2 rate.
const SQRT_3: f64 = 1.732_050_807_568_877_2;

/// The radial profile ρ(r²) of one group of input columns.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Shape {
    /// exp(−r²/2).
    SquaredExponential,
    /// (1 + √3 r) exp(−√3 r): once differentiable sample paths, heavier tails than SE.
    Matern32,
}

impl Shape {
    /// ρ(r²).
    #[inline(always)]
    pub(crate) fn profile(self, r2: f64) -> f64 {
        match self {
            Self::SquaredExponential => exp(-0.5 * r2),
            Self::Matern32 => {
                let sr = SQRT_3 * r2.sqrt();
                (1.0 + sr) * exp(-sr)
            }
        }
    }

    /// v ← s · ρ(v) for every squared distance v, in a loop the compiler vectorises when it runs
    /// in a vectorised context (e.g. the epilogue of the distance product).
    #[inline(always)]
    pub(crate) fn apply_scaled_profile(self, r2: &mut [f64], s: f64) {
        match self {
            Self::SquaredExponential => r2.iter_mut().for_each(|v| *v = s * exp(-0.5 * *v)),
            Self::Matern32 => r2.iter_mut().for_each(|v| *v = s * self.profile(*v)),
        }
    }

    /// −2 ρ'(r²)/ρ(r²): 1 for SE, 3/(1 + √3 r) for Matérn 3/2.
    pub(crate) fn slope(self, r2: f64) -> f64 {
        match self {
            Self::SquaredExponential => 1.0,
            Self::Matern32 => 3.0 / (1.0 + SQRT_3 * r2.sqrt()),
        }
    }
}

/// One group of consecutive input columns with its profile.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Factor {
    /// The profile.
    pub shape: Shape,
    /// Number of columns, or `None` for all remaining columns (last group only).
    pub dims: Option<usize>,
}

/// A resolved group: columns `start .. start + len`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Group {
    /// First column.
    pub start: usize,
    /// Number of columns.
    pub len: usize,
    /// The profile.
    pub shape: Shape,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scaled_profile_is_the_signal_variance_times_the_profile() {
        for shape in [Shape::SquaredExponential, Shape::Matern32] {
            let mut v = vec![0.0, 0.5, 1.0, 2.0, 9.0];
            let want: Vec<f64> = v.iter().map(|r2| 2.5 * shape.profile(*r2)).collect();
            shape.apply_scaled_profile(&mut v, 2.5);
            assert_eq!(v, want, "{shape:?}");
        }
        let mut v = vec![2.0];
        Shape::SquaredExponential.apply_scaled_profile(&mut v, 3.0);
        assert!((v[0] - 3.0 * (-1.0f64).exp()).abs() < 1e-15);
    }
}
