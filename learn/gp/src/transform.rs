//! Standardisation of inputs (per column) and targets, recorded in the model so predictions apply
//! exactly the transform the model was fitted in. Constant columns keep scale 1, so they map to 0
//! instead of dividing by zero.

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use super::kernel::Kernel;

/// Relative spread below which a column counts as constant.
const CONSTANT_SPREAD: f64 = 1e-12;

/// x' = (x − mean) / scale, per column (one entry for a target).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Standardiser {
    /// Column means of the training data.
    pub mean: Vec<f64>,
    /// Column standard deviations (population), or 1 for constant columns.
    pub scale: Vec<f64>,
}

fn mean_and_scale(values: impl Iterator<Item = f64> + Clone, n: usize) -> (f64, f64) {
    let mean = values.clone().sum::<f64>() / n as f64;
    let var = values.map(|v| (v - mean).powi(2)).sum::<f64>() / n as f64;
    let sd = var.sqrt();
    let scale = if sd > CONSTANT_SPREAD * mean.abs().max(1.0) {
        sd
    } else {
        1.0
    };
    (mean, scale)
}

impl Standardiser {
    /// Fits one transform per column of `x` (N×D, N ≥ 1).
    pub fn of_columns(x: &DMatrix<f64>) -> Self {
        let (mean, scale) = x
            .column_iter()
            .map(|c| mean_and_scale(c.iter().copied(), c.len()))
            .unzip();
        Self { mean, scale }
    }

    /// The input transform a fit with `kernel` uses: per-column standardisation, or the identity
    /// for kernels that work in the inputs' own units.
    pub(crate) fn for_kernel<K: Kernel>(x: &DMatrix<f64>, kernel: &K) -> Self {
        if kernel.standardise_inputs() {
            Self::of_columns(x)
        } else {
            Self {
                mean: vec![0.0; x.ncols()],
                scale: vec![1.0; x.ncols()],
            }
        }
    }

    /// Fits the transform of a target vector (N ≥ 1).
    pub fn of_vector(y: &DVector<f64>) -> Self {
        let (m, s) = mean_and_scale(y.iter().copied(), y.len());
        Self {
            mean: vec![m],
            scale: vec![s],
        }
    }

    /// The transform of a target whose prior mean is 0: no centring, scaled by the root mean
    /// square (1 for an all-zero target).
    pub fn of_vector_uncentred(y: &DVector<f64>) -> Self {
        let rms = (y.iter().map(|v| v * v).sum::<f64>() / y.len().max(1) as f64).sqrt();
        let scale = if rms > CONSTANT_SPREAD { rms } else { 1.0 };
        Self {
            mean: vec![0.0],
            scale: vec![scale],
        }
    }

    /// Number of columns transformed.
    pub fn len(&self) -> usize {
        self.mean.len()
    }

    /// Whether the transform has no columns.
    pub fn is_empty(&self) -> bool {
        self.mean.is_empty()
    }

    /// Applies the transform to the columns of `x`.
    pub fn apply(&self, x: &DMatrix<f64>) -> DMatrix<f64> {
        DMatrix::from_fn(x.nrows(), x.ncols(), |i, j| {
            (x[(i, j)] - self.mean[j]) / self.scale[j]
        })
    }

    /// Applies the (single-column) transform to a vector.
    pub fn apply_vector(&self, y: &DVector<f64>) -> DVector<f64> {
        y.map(|v| (v - self.mean[0]) / self.scale[0])
    }

    /// Maps standardised values back (single column).
    pub fn invert_vector(&self, y: &DVector<f64>) -> DVector<f64> {
        y.map(|v| v * self.scale[0] + self.mean[0])
    }

    /// Maps standardised variances back (single column).
    pub fn invert_variance(&self, var: &DVector<f64>) -> DVector<f64> {
        var.map(|v| v * self.scale[0] * self.scale[0])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_column_maps_to_zero_and_the_others_to_unit_spread() {
        let x = DMatrix::from_row_slice(4, 2, &[1.0, 5.0, 2.0, 5.0, 3.0, 5.0, 4.0, 5.0]);
        let t = Standardiser::of_columns(&x);
        let z = t.apply(&x);
        assert_eq!(t.scale[1], 1.0);
        assert!(z.column(1).iter().all(|v| *v == 0.0));
        let sd = (z.column(0).map(|v| v * v).sum() / 4.0).sqrt();
        assert!((sd - 1.0).abs() < 1e-12 && z.column(0).sum().abs() < 1e-12);
    }

    #[test]
    fn targets_round_trip_through_the_transform() {
        let y = DVector::from_vec(vec![3.0, -1.0, 7.5]);
        let t = Standardiser::of_vector(&y);
        assert!((t.invert_vector(&t.apply_vector(&y)) - y).amax() < 1e-12);
    }
}
