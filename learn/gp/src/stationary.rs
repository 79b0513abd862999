//! Stationary ARD kernels: k(x, x') = s · Π_g ρ_g(r_g²) with r_g² = Σ_{d∈g} (x_d − x'_d)²/ℓ_d² over
//! consecutive groups g of input columns, each with a radial profile ρ_g: the squared exponential
//! (thesis eq. 3.11, ℓ not squared as in gp.md §0) or Matérn 3/2. One SE group is SE-ARD; a
//! spatial group over (x, y) times a temporal group over t is a space-time kernel with its own
//! temporal length-scale (GPOM in R^{D+1}).
//!
//! Squared distances go through gemm: r² = ‖a‖²_ℓ + ‖b‖²_ℓ − 2 (A diag(ℓ⁻²)) Bᵀ, so the O(PQD)
//! part is one matrix-matrix product; so are the gradients (gp.md §2.3, with E = −2 G ∘ ∂K/∂r²).

use nalgebra::{DMatrix, DVector};

use super::ard_distance::{sq_distances, sq_distances_then};
use super::ard_gradient::{group_gradient, line_sums, product_with_sums};
use super::kernel::{Kernel, Points};
use super::log_range::LogRange;
use super::shape::{Factor, Group, Shape};
use crate::{GpError, Result};

/// Largest magnitude of a log-parameter; keeps exp() finite when the optimiser strays.
const LOG_LIMIT: f64 = 40.0;
/// Smallest starting signal variance (a constant target still gets a usable kernel).
const MIN_SIGNAL_VARIANCE: f64 = 1e-2;

/// A product of stationary ARD profiles over groups of input columns, with one signal variance.
#[derive(Debug, Clone, PartialEq)]
pub struct Stationary {
    factors: Vec<Factor>,
    lengthscales: DVector<f64>,
    signal_variance: f64,
    /// The factors resolved to column ranges for the length-scales' D (empty before sizing).
    groups: Vec<Group>,
    /// Columns whose length-scale is held inside a range (in the units the kernel sees).
    ranges: Vec<(usize, LogRange)>,
}

impl Default for Stationary {
    /// SE-ARD.
    fn default() -> Self {
        Self::se_ard()
    }
}

impl Stationary {
    fn of(factors: Vec<Factor>) -> Self {
        Self {
            factors,
            lengthscales: DVector::zeros(0),
            signal_variance: 1.0,
            groups: Vec::new(),
            ranges: Vec::new(),
        }
    }

    /// Squared exponential with one length-scale per input (thesis eq. 3.11).
    pub fn se_ard() -> Self {
        Self::of(vec![Factor {
            shape: Shape::SquaredExponential,
            dims: None,
        }])
    }

    /// Matérn 3/2 of the ARD-scaled distance.
    pub fn matern32_ard() -> Self {
        Self::of(vec![Factor {
            shape: Shape::Matern32,
            dims: None,
        }])
    }

    /// `space` over the first `space_dims` columns times `time` over the remaining ones (e.g.
    /// (x, y) and t), each with its own length-scales: the temporal one is learned separately.
    pub fn space_time(space_dims: usize, space: Shape, time: Shape) -> Self {
        Self::of(vec![
            Factor {
                shape: space,
                dims: Some(space_dims),
            },
            Factor {
                shape: time,
                dims: None,
            },
        ])
    }

    /// A kernel with given groups and values (e.g. read from a model file); checks the shapes.
    pub fn with_values(
        factors: Vec<Factor>,
        lengthscales: DVector<f64>,
        signal_variance: f64,
    ) -> Result<Self> {
        let mut k = Self {
            factors,
            lengthscales,
            signal_variance,
            groups: Vec::new(),
            ranges: Vec::new(),
        };
        k.groups = k.resolve(k.lengthscales.len())?;
        if !(k.lengthscales.iter().all(|l| l.is_finite() && *l > 0.0)
            && signal_variance.is_finite()
            && signal_variance > 0.0)
        {
            return Err(GpError::InvalidParams(
                "length-scales and signal variance must be positive".into(),
            ));
        }
        Ok(k)
    }

    /// SE-ARD with the given length-scales and signal variance (tests).
    #[cfg(test)]
    pub(crate) fn se(lengthscales: &[f64], signal_variance: f64) -> Self {
        let mut k = Self::se_ard();
        k.groups = k.resolve(lengthscales.len()).unwrap_or_default();
        k.lengthscales = DVector::from_column_slice(lengthscales);
        k.signal_variance = signal_variance;
        k
    }

    /// The kernel with the length-scale of input `column` held smoothly inside [lo, hi]
    /// ([`LogRange`]), in the units the kernel sees: a fit that standardises its inputs (the
    /// default) sees each column over its standard deviation, so a range in the inputs' own
    /// units is divided by that first. Errors unless 0 < lo < hi, finite.
    pub fn bounded(mut self, column: usize, lo: f64, hi: f64) -> Result<Self> {
        let range = LogRange::new(lo, hi)?;
        self.ranges.retain(|(c, _)| *c != column);
        self.ranges.push((column, range));
        Ok(self)
    }

    /// The range input `column`'s length-scale is held in, if any.
    pub fn range(&self, column: usize) -> Option<LogRange> {
        self.ranges
            .iter()
            .find(|(c, _)| *c == column)
            .map(|(_, r)| *r)
    }

    /// The column groups and their profiles.
    pub fn factors(&self) -> &[Factor] {
        &self.factors
    }

    /// Length-scales ℓ_d (not squared), one per input column.
    pub fn lengthscales(&self) -> &DVector<f64> {
        &self.lengthscales
    }

    /// Whether this is the single-group squared exponential (the thesis' kernel).
    pub fn is_se_ard(&self) -> bool {
        self.factors
            == [Factor {
                shape: Shape::SquaredExponential,
                dims: None,
            }]
    }

    /// The groups for `d` input columns; errors if the factors do not cover exactly `d`.
    fn resolve(&self, d: usize) -> Result<Vec<Group>> {
        let mut out = Vec::with_capacity(self.factors.len());
        let mut start = 0;
        for (i, f) in self.factors.iter().enumerate() {
            let last = i + 1 == self.factors.len();
            let len = match f.dims {
                Some(n) => n,
                None if last => d.saturating_sub(start),
                None => {
                    return Err(GpError::InvalidParams(
                        "only the last kernel factor may take the remaining columns".into(),
                    ));
                }
            };
            if len == 0 {
                return Err(GpError::InvalidParams(format!(
                    "kernel factor {} covers no input column ({d} inputs)",
                    i + 1
                )));
            }
            out.push(Group {
                start,
                len,
                shape: f.shape,
            });
            start += len;
        }
        if start != d || out.is_empty() {
            return Err(GpError::InvalidParams(format!(
                "the kernel's factors cover {start} input columns, the data has {d}"
            )));
        }
        Ok(out)
    }

    /// ℓ⁻² per column.
    fn inverse_squares(&self) -> DVector<f64> {
        self.lengthscales.map(|l| 1.0 / (l * l))
    }
}

impl Kernel for Stationary {
    fn n_params(&self) -> usize {
        self.lengthscales.len() + 1
    }

    fn params(&self) -> Vec<f64> {
        let mut v: Vec<f64> = self.lengthscales.iter().map(|l| l.ln()).collect();
        for &(c, r) in &self.ranges {
            if let Some(x) = v.get_mut(c) {
                *x = r.raw(*x);
            }
        }
        v.push(self.signal_variance.ln());
        v
    }

    fn set_params(&mut self, theta: &[f64]) {
        let ex = |x: f64| x.clamp(-LOG_LIMIT, LOG_LIMIT).exp();
        let d = self.lengthscales.len();
        self.lengthscales = DVector::from_iterator(
            d,
            theta[..d].iter().enumerate().map(|(c, x)| {
                self.range(c)
                    .map_or_else(|| ex(*x), |r| r.log_value(*x).exp())
            }),
        );
        self.signal_variance = ex(theta[d]);
    }

    fn initialise(&mut self, xt: &DMatrix<f64>, target_variance: f64) -> Result<()> {
        let (dims, n) = (xt.nrows(), xt.ncols());
        self.groups = self.resolve(dims)?;
        // With D inputs of unit spread the squared scaled distance between two samples is about
        // 2·Σ_d 1/ℓ_d²; ℓ_d = spread_d·√D keeps it near 2 whatever D is (Snelson's range/2 suits
        // D = 1; gp.md §5.3).
        let root_d = (dims as f64).sqrt();
        self.lengthscales = DVector::from_iterator(
            dims,
            xt.row_iter().map(|row| {
                let mean = row.mean();
                let spread =
                    (row.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
                if spread > 1e-12 {
                    spread * root_d
                } else {
                    root_d
                }
            }),
        );
        for &(c, r) in &self.ranges {
            if let Some(l) = self.lengthscales.get_mut(c) {
                *l = r.hold(*l);
            }
        }
        self.signal_variance = target_variance.max(MIN_SIGNAL_VARIANCE);
        Ok(())
    }

    fn signal_variance(&self) -> f64 {
        self.signal_variance
    }

    fn log_signal_variance_index(&self) -> usize {
        self.lengthscales.len()
    }

    fn cross(&self, a: Points<'_>, b: Points<'_>) -> DMatrix<f64> {
        let inv_sq = self.inverse_squares();
        let s = self.signal_variance;
        let Some((&first, rest)) = self.groups.split_first() else {
            return DMatrix::from_element(a.len(), b.len(), s); // no input columns
        };
        // The first profile is applied inside the distance product, on columns still in cache.
        let mut k = sq_distances_then(
            a,
            b,
            &inv_sq,
            first,
            #[inline(always)]
            |r2| first.shape.apply_scaled_profile(r2, s),
        );
        for &g in rest {
            let r2 = sq_distances(a, b, &inv_sq, g);
            k.zip_apply(&r2, |kv, r| *kv *= g.shape.profile(r));
        }
        k
    }

    fn diag(&self, a: Points<'_>) -> DVector<f64> {
        DVector::from_element(a.len(), self.signal_variance)
    }

    fn cross_gradient(
        &self,
        a: Points<'_>,
        b: Points<'_>,
        k: &DMatrix<f64>,
        adjoint: &DMatrix<f64>,
        mut d_a: Option<&mut DMatrix<f64>>,
    ) -> DVector<f64> {
        let inv_sq = self.inverse_squares();
        let d = self.lengthscales.len();
        let mut grad = vec![0.0; d + 1];
        let (gk, gk_sums) = product_with_sums(adjoint, k);
        grad[d] = gk_sums.total(); // ∂𝓛/∂log s = Σ G ∘ K
        for &g in &self.groups {
            let e = match g.shape {
                Shape::SquaredExponential => None, // E = G ∘ K
                Shape::Matern32 => {
                    let mut e = sq_distances(a, b, &inv_sq, g);
                    e.zip_apply(&gk, |r2, gkv| *r2 = gkv * g.shape.slope(*r2));
                    let sums = line_sums(&e);
                    Some((e, sums))
                }
            };
            let e = e.as_ref().map_or((&gk, &gk_sums), |(e, s)| (e, s));
            group_gradient(a, b, e, &inv_sq, g, &mut grad, d_a.as_deref_mut());
        }
        // A held length-scale moves by its range's slope per raw step.
        for &(c, r) in &self.ranges {
            if let (Some(gc), Some(l)) = (grad.get_mut(c), self.lengthscales.get(c)) {
                *gc *= r.slope_at(l.ln());
            }
        }
        DVector::from_vec(grad)
    }

    fn diag_gradient(&self, a: Points<'_>, adjoint: &DVector<f64>) -> DVector<f64> {
        let d = self.lengthscales.len();
        let _ = a;
        let mut grad = DVector::zeros(d + 1);
        grad[d] = self.signal_variance * adjoint.sum();
        grad
    }
}

#[cfg(test)]
#[path = "stationary_tests.rs"]
mod tests;
