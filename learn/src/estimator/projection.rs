//! A supervised projection of the 242-value patches to a few tens of dimensions by partial least
//! squares (PLS1, NIPALS; thesis Ch. 6 names CCA and PCA, learning-beyond-thesis.md why PLS):
//! the directions of the standardised patch space that covary most with one GP's target, fitted
//! on that GP's training set only.

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use crate::{LearnError, Result};

/// Relative spread below which an input column counts as constant (scale 1, as the GPs do).
const CONSTANT_SPREAD: f64 = 1e-12;

/// x ↦ ((x − mean) / scale) · R, with R (D×K) from PLS1; each output column has unit variance on
/// the training set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Projection {
    /// Column means of the training inputs (D).
    pub mean: Vec<f64>,
    /// Column standard deviations (D; 1 for constant columns).
    pub scale: Vec<f64>,
    /// Output dimension K.
    pub dims: usize,
    /// R, row-major D×K.
    pub rotation: Vec<f64>,
}

impl Projection {
    /// Fits `dims` PLS1 directions of `x` (N×D) for the target `y` (N). Fewer come out when the
    /// residual target or inputs are exhausted first (never none).
    pub fn fit(x: &DMatrix<f64>, y: &DVector<f64>, dims: usize) -> Result<Self> {
        let (n, d) = (x.nrows(), x.ncols());
        if n < 2 || d == 0 || dims == 0 || y.len() != n {
            return Err(LearnError::invalid_params(format!(
                "a PLS projection needs 2 or more rows, 1 or more columns and directions, and one \
                 target per row; got {n}×{d}, {dims} directions, {} targets",
                y.len()
            )));
        }
        let mean: Vec<f64> = x.column_iter().map(|c| c.mean()).collect();
        let scale: Vec<f64> = x
            .column_iter()
            .zip(&mean)
            .map(|(c, m)| {
                let sd = (c.iter().map(|v| (v - m).powi(2)).sum::<f64>() / n as f64).sqrt();
                if sd > CONSTANT_SPREAD * m.abs().max(1.0) {
                    sd
                } else {
                    1.0
                }
            })
            .collect();
        let mut e = DMatrix::from_fn(n, d, |i, j| (x[(i, j)] - mean[j]) / scale[j]);
        let y_mean = y.mean();
        let mut f = y.map(|v| v - y_mean);
        let (mut w_cols, mut p_cols) = (Vec::new(), Vec::new());
        for _ in 0..dims.min(d) {
            let w = e.tr_mul(&f);
            let norm = w.norm();
            if norm <= 1e-12 * (n as f64) {
                break;
            }
            let w = w / norm;
            let t = &e * &w;
            let tt = t.dot(&t);
            if tt <= 1e-12 {
                break;
            }
            let p = e.tr_mul(&t) / tt;
            let q = f.dot(&t) / tt;
            e -= &t * p.transpose();
            f -= &t * q;
            w_cols.push(w);
            p_cols.push(p);
        }
        if w_cols.is_empty() {
            return Err(LearnError::degenerate_data(
                "the PLS projection found no direction that covaries with the target (constant \
                 target or inputs)"
                    .into(),
            ));
        }
        let k = w_cols.len();
        let w = DMatrix::from_columns(&w_cols);
        let p = DMatrix::from_columns(&p_cols);
        // R = W (PᵀW)⁻¹ maps standardised inputs straight to the scores T (PᵀW is unit upper
        // triangular, so it always inverts).
        let ptw = p.tr_mul(&w);
        let inv = ptw.try_inverse().ok_or_else(|| {
            LearnError::degenerate_data("the PLS loadings are linearly dependent".into())
        })?;
        let mut r = w * inv;
        // Unit variance per score column on the training set.
        let scores = DMatrix::from_fn(n, d, |i, j| (x[(i, j)] - mean[j]) / scale[j]) * &r;
        for (j, col) in scores.column_iter().enumerate() {
            let sd = (col.iter().map(|v| v * v).sum::<f64>() / n as f64).sqrt();
            if sd > 1e-12 {
                r.column_mut(j).scale_mut(1.0 / sd);
            }
        }
        let rotation = (0..d)
            .flat_map(|i| (0..k).map(move |j| (i, j)))
            .map(|(i, j)| r[(i, j)])
            .collect();
        Ok(Self {
            mean,
            scale,
            dims: k,
            rotation,
        })
    }

    /// Input dimension D.
    pub fn input_dims(&self) -> usize {
        self.mean.len()
    }

    /// Projects rows given one after another (T×D row-major) to T×K row-major.
    pub fn apply_rows(&self, rows: &[f64]) -> Result<Vec<f64>> {
        let d = self.input_dims();
        if d == 0 || !rows.len().is_multiple_of(d) {
            return Err(LearnError::invalid_params(format!(
                "{} values are not whole rows of the projection's {d} inputs",
                rows.len()
            )));
        }
        let k = self.dims;
        let mut out = vec![0.0; rows.len() / d * k];
        for (row, o) in rows.chunks_exact(d).zip(out.chunks_exact_mut(k)) {
            for (i, &v) in row.iter().enumerate() {
                let z = (v - self.mean[i]) / self.scale[i];
                if z != 0.0 {
                    for (acc, r) in o.iter_mut().zip(&self.rotation[i * k..(i + 1) * k]) {
                        *acc += z * r;
                    }
                }
            }
        }
        Ok(out)
    }

    /// Projects the rows of `x` (N×D) to N×K.
    pub fn apply(&self, x: &DMatrix<f64>) -> Result<DMatrix<f64>> {
        let flat: Vec<f64> = x
            .row_iter()
            .flat_map(|r| r.iter().copied().collect::<Vec<_>>())
            .collect();
        let out = self.apply_rows(&flat)?;
        Ok(DMatrix::from_row_slice(x.nrows(), self.dims, &out))
    }

    /// Whether the stored numbers are consistent (for model files).
    pub fn is_consistent(&self) -> bool {
        let d = self.mean.len();
        d > 0
            && self.scale.len() == d
            && self.dims > 0
            && self.rotation.len() == d * self.dims
            && self.scale.iter().all(|s| s.is_finite() && *s > 0.0)
            && self
                .mean
                .iter()
                .chain(&self.rotation)
                .all(|v| v.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn the_first_direction_recovers_a_planted_direction_among_noise_columns() {
        // y depends on x·u for a planted u over 3 of 40 columns; the other 37 columns are noise,
        // which leaves the first direction off by their sample covariance with y (~1/√n).
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let (n, d) = (3000, 40);
        let x = DMatrix::from_fn(n, d, |_, _| rng.random_range(-1.0..1.0));
        let mut u = DVector::zeros(d);
        u[4] = 0.8;
        u[17] = -0.6;
        u[30] = 0.3;
        let y = DVector::from_fn(n, |i, _| {
            (x.row(i) * &u)[0] + 0.05 * rng.random_range(-1.0..1.0)
        });
        let p = Projection::fit(&x, &y, 3).unwrap();
        let first = DVector::from_fn(d, |i, _| p.rotation[i * p.dims] / p.scale[i]);
        let cos = first.dot(&u).abs() / (first.norm() * u.norm());
        assert!(cos > 0.98, "cosine with the planted direction {cos}");
    }

    #[test]
    fn scores_have_unit_variance_and_rows_project_like_the_matrix() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let x = DMatrix::from_fn(200, 12, |_, _| rng.random_range(0.0..1.0));
        let y = DVector::from_fn(200, |i, _| x[(i, 0)] - 2.0 * x[(i, 5)]);
        let p = Projection::fit(&x, &y, 4).unwrap();
        let t = p.apply(&x).unwrap();
        for col in t.column_iter() {
            let var = col.iter().map(|v| v * v).sum::<f64>() / 200.0;
            assert!((var - 1.0).abs() < 1e-9, "variance {var}");
        }
        let row: Vec<f64> = x.row(7).iter().copied().collect();
        let one = p.apply_rows(&row).unwrap();
        assert!((0..p.dims).all(|j| (one[j] - t[(7, j)]).abs() < 1e-12));
        assert!(p.is_consistent());
    }

    #[test]
    fn a_constant_target_is_an_error() {
        let x = DMatrix::from_fn(10, 3, |i, j| (i * j) as f64);
        assert!(Projection::fit(&x, &DVector::from_element(10, 2.0), 2).is_err());
    }
}
