//! Several sparse GPs fitted on the same inputs, predicted at the same rows in one pass: each
//! block of rows is checked and standardised once and then serves every model while it is in
//! cache (the motion estimator's sin and cos GPs and their noise GPs read the same heading
//! patches). Every model gets the bits its own [`GpModel::predict_row_groups`] (or
//! [`GpModel::predict_mean_rows`]) gives.

use nalgebra::DVector;
use rayon::prelude::*;

use super::batch_prediction::{blocks, small_product_rows};
use super::kernel::{Kernel, OwnedPoints};
use super::model::{GpModel, GpPrediction, Posterior};
use super::sparse_posterior::SparsePosterior;
use crate::Result;

/// What a joint prediction reads out of one model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Readout {
    /// Mean and both variances ([`GpModel::predict_row_groups`]).
    Full,
    /// The mean alone ([`GpModel::predict_mean_rows`]).
    Mean,
}

/// One model's part of a joint prediction.
#[derive(Debug, Clone, PartialEq)]
pub enum Predicted {
    /// Mean and variances.
    Full(GpPrediction),
    /// The mean alone, in target units.
    Mean(DVector<f64>),
}

impl Predicted {
    /// The predictive mean, in target units.
    pub fn mean(&self) -> &DVector<f64> {
        match self {
            Self::Full(p) => &p.mean,
            Self::Mean(mean) => mean,
        }
    }
}

impl<K: Kernel> GpModel<K> {
    /// Predicts every model of `jobs` at the same rows (row-major, groups of `group_rows` rows
    /// as in [`GpModel::predict_row_groups`]), each as its [`Readout`] says, in the order given.
    /// Sparse models whose input transforms are equal share each block's standardised rows;
    /// any other set of models is predicted one model after another. Either way each model's
    /// result has the bits of its own call.
    pub fn predict_jointly(
        jobs: &[(&Self, Readout)],
        rows: &[f64],
        group_rows: &[usize],
    ) -> Result<Vec<Predicted>> {
        let Some(&(first, _)) = jobs.first() else {
            return Ok(Vec::new());
        };
        let posteriors: Option<Vec<&SparsePosterior>> = jobs
            .iter()
            .map(|(model, _)| match &model.posterior {
                Posterior::Sparse(p) if model.inputs == first.inputs => Some(p),
                _ => None,
            })
            .collect();
        let Some(posteriors) = posteriors else {
            return jobs
                .iter()
                .map(|&(m, r)| m.predict_alone(r, rows, group_rows))
                .collect();
        };
        let d = first.input_names.len();
        let t = first.grouped_rows(rows, d, group_rows)?;
        let pseudo: Vec<OwnedPoints> = jobs
            .iter()
            .map(|(m, _)| OwnedPoints::of_rows(&m.hyper.pseudo_inputs, &m.hyper.kernel))
            .collect();
        // Which rows take nalgebra's small-product loop for W K_MB, per model (as its own call).
        let small: Vec<Vec<bool>> = posteriors
            .iter()
            .map(|p| small_product_rows(p.weights.len(), group_rows))
            .collect();
        let starts = blocks(&vec![false; t]);
        let per_block = starts
            .into_par_iter()
            .map(|b| {
                let block_rows = &rows[b.start * d..(b.start + b.len) * d];
                let coords = first
                    .standardised_columns(block_rows, d)
                    .map_err(|bad| bad.offset(b.start * d))?;
                Ok(jobs
                    .iter()
                    .zip(&posteriors)
                    .zip(&pseudo)
                    .zip(&small)
                    .map(|((((model, readout), p), z), small)| {
                        let small = &small[b.start..b.start + b.len];
                        let small = (*readout == Readout::Full).then_some(small);
                        model.sparse_block(p, z.points(), &coords, small)
                    })
                    .collect::<Vec<_>>())
            })
            .collect::<Vec<_>>();
        let per_block = first.without_bad_inputs(rows, per_block)?;
        debug_assert!(per_block.iter().all(|b| b.len() == jobs.len()));
        jobs.iter()
            .enumerate()
            .map(|(k, &(model, readout))| {
                let mean = per_block.iter().flat_map(|b| b[k].0.iter().copied());
                let mean = DVector::from_iterator(t, mean);
                match readout {
                    Readout::Full => {
                        let var = per_block.iter().flat_map(|b| b[k].1.iter().copied());
                        let var = DVector::from_iterator(t, var);
                        model.prediction(&mean, &var).map(Predicted::Full)
                    }
                    Readout::Mean => model.mean_in_target_units(&mean).map(Predicted::Mean),
                }
            })
            .collect()
    }

    /// One model's own call for `readout`.
    fn predict_alone(
        &self,
        readout: Readout,
        rows: &[f64],
        group_rows: &[usize],
    ) -> Result<Predicted> {
        Ok(match readout {
            Readout::Full => Predicted::Full(self.predict_row_groups(rows, group_rows)?),
            Readout::Mean => {
                let t = group_rows.iter().sum::<usize>();
                if t * self.input_names.len() != rows.len() {
                    // The grouped call names the mismatch.
                    self.predict_row_groups(rows, group_rows)?;
                }
                Predicted::Mean(self.predict_mean_rows(rows)?)
            }
        })
    }
}

#[cfg(test)]
#[path = "joint_prediction_tests.rs"]
mod tests;
