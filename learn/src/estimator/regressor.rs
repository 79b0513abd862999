//! One of the estimator's three regressions (sin, cos of the relative heading; speed): a GP on
//! the patches as the thesis fits it, or with the thesis' future work (Ch. 6) switched on — a PLS
//! projection of the patches with k-means inducing points, and Kersting et al.'s most-likely
//! heteroscedastic noise (a noise GP on held-out log residuals; gp.md §7).

use nalgebra::{DMatrix, DVector};
use patchflow_gp::{GpKind, GpModel, GpParams, GpPrediction, Predicted, Readout};

use super::kmeans::kmeans;
use super::params::EstimatorValidParams;
use super::projection::Projection;
use crate::{LearnError, Result};

/// Optimiser iterations of the noise GP. Each costs about as much as one of the mean GP's (the
/// inputs' 242 length-scales dominate); 50 instead of 100 moved no situation's SPGP-HET-ALL
/// figures by more than its spread over seeds 7-9 and saved a fifth of the training (docs/speed.md,
/// "Issue 24's time targets: stop 38").
const NOISE_GP_ITERS: usize = 50;
/// Pseudo-inputs of the noise GP at most.
const NOISE_GP_PSEUDO: usize = 40;
/// The noise GP of the most-likely heteroscedastic GP: log of the relative noise level.
#[derive(Debug, Clone)]
pub struct NoiseModel {
    /// GP of z(x) = log ½[(y − μ_loo)² + σ²_loo] on the regression's (projected) inputs.
    pub gp: GpModel,
    /// Mean of the noise GP's predictions on the training inputs: the noise at x is
    /// σ²·exp(z(x) − offset), σ² the mean GP's noise variance.
    pub offset: f64,
}

/// A fitted regression: the mean GP, and optionally its input projection and noise GP.
#[derive(Debug, Clone)]
pub struct Regressor {
    /// The GP (on projected inputs when [`Self::projection`] is set).
    pub gp: GpModel,
    /// PLS projection of the patch values, if used.
    pub projection: Option<Projection>,
    /// Noise GP, if the most-likely heteroscedastic fit was used.
    pub noise: Option<NoiseModel>,
}

impl Regressor {
    /// A plain GP (the thesis' regression, or a model file without extras).
    pub fn plain(gp: GpModel) -> Self {
        Self {
            gp,
            projection: None,
            noise: None,
        }
    }

    /// Fits `x` (N×D patch values) to `y` as `params` say; `seed` seeds the GP and k-means.
    pub fn fit(
        x: &DMatrix<f64>,
        y: &DVector<f64>,
        names: &[String],
        target: &str,
        params: &EstimatorValidParams,
        seed: u64,
    ) -> Result<Self> {
        let m = params.pseudo_inputs.min(x.nrows());
        let projection = match params.projection_dims {
            0 => None,
            k => Some(Projection::fit(x, y, k)?),
        };
        let (inputs, gp_names) = match &projection {
            None => (x.clone(), names.to_vec()),
            Some(p) => (p.apply(x)?, projected_names(p.dims)),
        };
        let mut base = GpParams::new(params.gp)
            .pseudo_inputs(m)
            .max_iters(params.max_iters)
            .seed(seed)
            .zero_mean(params.zero_mean);
        if projection.is_some() && params.gp != GpKind::Full {
            base = base
                .start_pseudo_inputs(standardised_centres(&inputs, m, seed))
                .optimise_pseudo_inputs(false);
        }
        let first = base.check()?.fit_named(&inputs, y, &gp_names, target)?;
        if !params.most_likely_noise || params.gp == GpKind::Full {
            return Ok(Self {
                gp: first,
                projection,
                noise: None,
            });
        }
        // Kersting et al. 2007, one round: held-out (leave-one-out) residuals of the first fit,
        // a noise GP on their log, then the mean GP again with that noise shape held fixed,
        // from the seeded start (a warm start from the first fit, GpParams::start_from, moved
        // situation 3 over the bar for the mean over seeds 7-9: docs/speed.md).
        // z_i = log((y_i − μ_i)² + var f_i): the held-out squared error less the first fit's
        // own homoscedastic σ², which Kersting's ½[(y − μ)² + var y] keeps and only further
        // rounds wash out; a constant bias of the log (E log χ²₁ ≈ −1.27) cancels in the offset,
        // since σ² is learned again.
        let loo = first.loo_moments(&inputs, y)?;
        let floor = 1e-6 * first.noise_variance().max(1e-12);
        let log_noise = DVector::from_fn(y.len(), |i, _| {
            ((y[i] - loo.mean[i]).powi(2) + loo.var_latent[i])
                .max(floor)
                .ln()
        });
        let noise_m = m.min(NOISE_GP_PSEUDO);
        let noise_gp = GpParams::new(GpKind::Spgp)
            .pseudo_inputs(noise_m)
            .max_iters(NOISE_GP_ITERS)
            .seed(seed.wrapping_add(100))
            .start_pseudo_inputs(standardised_centres(&inputs, noise_m, seed ^ 0x5eed))
            .optimise_pseudo_inputs(false)
            .check()?
            .fit_named(&inputs, &log_noise, &gp_names, "log_noise")?;
        let at_training = noise_gp.predict(&inputs)?.mean;
        let offset = at_training.mean();
        let weights = at_training.map(|z| (z - offset).clamp(-20.0, 20.0).exp());
        let gp = base
            .noise_weights(weights)
            .check()?
            .fit_named(&inputs, y, &gp_names, target)?;
        Ok(Self {
            gp,
            projection,
            noise: Some(NoiseModel {
                gp: noise_gp,
                offset,
            }),
        })
    }

    /// Predicts at consecutive groups of patch rows (as [`GpModel::predict_row_groups`]);
    /// with a noise GP, `var_y` is the latent variance plus σ²·exp(z(x) − offset).
    pub fn predict_row_groups(&self, rows: &[f64], group_rows: &[usize]) -> Result<GpPrediction> {
        let mut out = Self::predict_together(&[self], rows, group_rows)?;
        out.pop()
            .ok_or_else(|| LearnError::invalid_params("a regression predicted nothing".into()))
    }

    /// [`Self::predict_row_groups`] of every regression in `regressions` at the same rows, in
    /// their order. Regressions on the raw patch values share one pass over the rows (their GPs
    /// and noise GPs through [`GpModel::predict_jointly`]; each gets the bits of its own call).
    pub fn predict_together(
        regressions: &[&Self],
        rows: &[f64],
        group_rows: &[usize],
    ) -> Result<Vec<GpPrediction>> {
        if regressions.iter().any(|r| r.projection.is_some()) {
            return regressions
                .iter()
                .map(|r| {
                    let projected = match &r.projection {
                        Some(p) => p.apply_rows(rows)?,
                        None => rows.to_vec(),
                    };
                    r.predict_inputs(&projected, group_rows)
                })
                .collect();
        }
        let mut jobs = Vec::new();
        for r in regressions {
            jobs.push((&r.gp, Readout::Full));
            if let Some(noise) = &r.noise {
                jobs.push((&noise.gp, Readout::Mean));
            }
        }
        let mut predicted = GpModel::predict_jointly(&jobs, rows, group_rows)?.into_iter();
        regressions
            .iter()
            .map(|r| {
                let Some(Predicted::Full(prediction)) = predicted.next() else {
                    return Err(LearnError::invalid_params(
                        "a joint prediction lost its order".into(),
                    ));
                };
                let z = match &r.noise {
                    Some(_) => predicted.next().map(|p| p.mean().clone()),
                    None => None,
                };
                Ok(r.with_noise(prediction, z.as_ref()))
            })
            .collect()
    }

    /// The prediction at rows already in the GP's inputs (projected where there is a projection).
    fn predict_inputs(&self, rows: &[f64], group_rows: &[usize]) -> Result<GpPrediction> {
        let prediction = self.gp.predict_row_groups(rows, group_rows)?;
        let z = match &self.noise {
            Some(noise) => Some(noise.gp.predict_mean_rows(rows)?),
            None => None,
        };
        Ok(self.with_noise(prediction, z.as_ref()))
    }

    /// `prediction` with the noise GP's log noise `z` (when there is a noise GP) in `var_y`:
    /// the latent variance plus σ²·exp(z(x) − offset).
    fn with_noise(&self, mut prediction: GpPrediction, z: Option<&DVector<f64>>) -> GpPrediction {
        if let (Some(noise), Some(z)) = (&self.noise, z) {
            let sigma2 = self.gp.noise_variance();
            prediction.var_y = DVector::from_fn(z.len(), |i, _| {
                prediction.var_latent[i] + sigma2 * (z[i] - noise.offset).clamp(-20.0, 20.0).exp()
            });
        }
        prediction
    }

    /// The names of the patch columns the regression reads (the GP's own when unprojected).
    pub fn reads_columns(&self) -> usize {
        self.projection
            .as_ref()
            .map_or(self.gp.input_names().len(), Projection::input_dims)
    }
}

/// Input names of a GP on `k` PLS scores.
pub fn projected_names(k: usize) -> Vec<String> {
    (0..k).map(|j| format!("pls{j}")).collect()
}

/// k-means centres of `x`'s rows in the standardised units the GP fit works in.
fn standardised_centres(x: &DMatrix<f64>, m: usize, seed: u64) -> DMatrix<f64> {
    let t = patchflow_gp::Standardiser::of_columns(x);
    kmeans(&t.apply(x), m, seed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::EstimatorParams;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn the_noise_gp_follows_a_planted_heteroscedastic_pattern() {
        // y = sin(x0) with noise sd 0.02 for x1 < 0 and 0.5 for x1 > 0 (x2..x5 irrelevant).
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let n = 600;
        let x: DMatrix<f64> = DMatrix::from_fn(n, 6, |_, _| rng.random_range(-2.0..2.0));
        let y = DVector::from_fn(n, |i, _| {
            let sd = if x[(i, 1)] > 0.0 { 0.5 } else { 0.02 };
            x[(i, 0)].sin() + sd * (rng.random_range(-1.0..1.0) * 3f64.sqrt())
        });
        let params = EstimatorParams {
            gp: GpKind::Spgp,
            pseudo_inputs: 30,
            max_iters: 80,
            most_likely_noise: true,
            ..EstimatorParams::default()
        }
        .check()
        .unwrap();
        let names: Vec<String> = (0..6).map(|d| format!("x{d}")).collect();
        let r = Regressor::fit(&x, &y, &names, "y", &params, 3).unwrap();
        let test = |x1: f64| -> f64 {
            let rows: Vec<f64> = (0..20)
                .flat_map(|k| [-1.0 + 0.1 * k as f64, x1, 0.0, 0.0, 0.0, 0.0])
                .collect();
            let p = r.predict_row_groups(&rows, &[20]).unwrap();
            p.var_y.mean()
        };
        let (quiet, loud) = (test(-1.0), test(1.0));
        // True variances 0.0004 and 0.25: the ratio must come out large, within a loose bound.
        assert!(loud > 5.0 * quiet, "noisy side {loud}, quiet side {quiet}");
        assert!(
            loud > 0.08 && loud < 0.6,
            "noisy side's variance {loud} (truth 0.25)"
        );
    }
}
