//! One classifier of the moving classifier's bag: GP probabilistic least squares (GPML §6.5)
//! fitted to one seeded draw of as many moving as static training clusters.
//!
//! Why a bag: which clusters a single draw holds decides its quality, and a few clusters more or
//! less in the training tracks reshuffle the whole draw. On `bench`'s maps one draw of 400 moving
//! and 400 static clusters reads the five situations at 0.44-0.68 moving IoU depending on its seed
//! alone (seeds 7-12); the mean of three draws' probabilities reads them at 0.67-0.77
//! (docs/estimator.md, "Stop 44").

use nalgebra::DMatrix;
use patchflow_gp::{GpModel, PlsParams, Squashing};
use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_chacha::ChaCha8Rng;

use super::cluster_inputs::MOVING_INPUTS;
use crate::{GpKind, GpParams, LearnError, Result};

/// A GP fitted to one balanced draw of training clusters, with its squashing into probabilities.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct MovingDraw {
    pub(super) gp: GpModel,
    pub(super) squashing: Squashing,
    /// Clusters the GP was fitted on.
    pub(super) rows: usize,
    /// How many of them moved.
    pub(super) moving_rows: usize,
}

impl MovingDraw {
    /// Fits the GP to at most `max_rows / 2` moving clusters (one row of `inputs` each, `labels`
    /// whether it moves) and as many static ones, drawn uniformly with `seed`; also returns every
    /// cluster's held-out probability of moving: leave-one-out (GPML eq. 5.12) for the fitted
    /// ones, a prediction for the rest.
    pub(super) fn fit(
        inputs: &[[f64; MOVING_INPUTS]],
        labels: &[bool],
        max_rows: usize,
        seed: u64,
    ) -> Result<(Self, Vec<f64>)> {
        let mut order: Vec<usize> = (0..inputs.len()).collect();
        order.shuffle(&mut ChaCha8Rng::seed_from_u64(seed));
        let (moving, still): (Vec<usize>, Vec<usize>) = order.into_iter().partition(|&i| labels[i]);
        let n = moving.len().min(still.len()).min(max_rows.max(2) / 2);
        if n == 0 {
            return Err(LearnError::degenerate_data(format!(
                "{} clusters, {} of them moving: the moving classifier needs both classes",
                inputs.len(),
                moving.len()
            )));
        }
        let fitted: Vec<usize> = moving
            .iter()
            .take(n)
            .chain(still.iter().take(n))
            .copied()
            .collect();
        let x = DMatrix::from_fn(fitted.len(), MOVING_INPUTS, |i, d| inputs[fitted[i]][d]);
        let fitted_labels: Vec<bool> = fitted.iter().map(|&i| labels[i]).collect();
        let pls = PlsParams::new(GpParams::new(GpKind::Full).seed(seed)).fit(&x, &fitted_labels)?;
        let squashing = pls.squashing();
        let mut probability = vec![f64::NAN; inputs.len()];
        for (k, &i) in fitted.iter().enumerate() {
            probability[i] = squashing.probability(pls.loo().mean[k], pls.loo().var_latent[k]);
        }
        let rest: Vec<usize> = (0..inputs.len())
            .filter(|i| probability[*i].is_nan())
            .collect();
        if !rest.is_empty() {
            let x = DMatrix::from_fn(rest.len(), MOVING_INPUTS, |i, d| inputs[rest[i]][d]);
            let p = pls.predict(&x)?;
            for (k, &i) in rest.iter().enumerate() {
                probability[i] = p.probability[k];
            }
        }
        let draw = Self {
            gp: pls.regression().clone(),
            squashing,
            rows: fitted.len(),
            moving_rows: n,
        };
        Ok((draw, probability))
    }

    /// The probability that each row of `x` (one cluster's inputs per row) moves.
    pub(super) fn probabilities(&self, x: &DMatrix<f64>) -> Result<Vec<f64>> {
        let prediction = self.gp.predict(x)?;
        Ok((0..x.nrows())
            .map(|k| {
                self.squashing
                    .probability(prediction.mean[k], prediction.var_latent[k])
            })
            .collect())
    }
}
