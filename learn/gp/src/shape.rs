//! The radial profiles ρ(r²) of the stationary kernels and the groups of input columns they act
//! on: a kernel is s · Π_g ρ_g(r_g²) over consecutive column groups.

use serde::{Deserialize, Serialize};

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
    pub(crate) fn profile(self, r2: f64) -> f64 {
        match self {
            Self::SquaredExponential => (-0.5 * r2).exp(),
            Self::Matern32 => {
                let sr = SQRT_3 * r2.sqrt();
                (1.0 + sr) * (-sr).exp()
            }
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
