//! One fold of the cross-validation (thesis 4.3): which fold tests each sample, the GP inputs of
//! a sample set, training on the training split and its mirror images, errors on the test split
//! and the low-log-variance subset, and the per-fold RMSEs averaged as the thesis does.

use nalgebra::{DMatrix, DVector};
use patchflow_dataset::wrap_angle_rad;
use patchflow_learn::{
    FeatureKind, GaborBank, GpKind, GpParams, GpPrediction, Patch, SampleSet, rows_to_matrix,
};
use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_chacha::ChaCha8Rng;

use crate::cv::cv_params::CvParams;
use crate::cv::cv_report::{CvFeature, CvGp, CvRow};
use crate::error::EvalError;
use crate::scene::metrics::rmse;

/// Which fold each sample is tested in: a seeded shuffle dealt round-robin.
pub(crate) fn fold_assignment(n: usize, folds: usize, seed: u64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..n).collect();
    order.shuffle(&mut ChaCha8Rng::seed_from_u64(seed ^ 0xC0FF_EE00));
    let mut fold = vec![0; n];
    for (rank, &i) in order.iter().enumerate() {
        fold[i] = rank % folds;
    }
    fold
}

pub(crate) struct Split {
    train: Vec<usize>,
    test: Vec<usize>,
}

impl Split {
    pub(crate) fn new(folds: &[usize], fold: usize) -> Self {
        let (test, train) = (0..folds.len()).partition(|&i| folds[i] == fold);
        Self { train, test }
    }
}

/// The feature matrix of `set` for `feature`: the picked patch values themselves, or the Gabor
/// bank's responses to them, with the bank built for the cells the set's patches were drawn on
/// (0.20 m for the default, 0.10 m for the thesis).
pub(crate) fn features_of(
    set: &SampleSet,
    feature: CvFeature,
    pick: impl Fn(&patchflow_learn::TrainingSample) -> &Vec<f64>,
) -> Result<DMatrix<f64>, EvalError> {
    let gabor = GaborBank::new(&set.features.gabor, set.features.patch_cell_m);
    let d = match feature {
        CvFeature::Patch => FeatureKind::Patch.names().len(),
        CvFeature::Gabor => FeatureKind::Gabor.names().len(),
    };
    let rows: Vec<Vec<f64>> = set
        .samples
        .iter()
        .map(|sample| {
            let values = pick(sample);
            match feature {
                CvFeature::Patch => values.clone(),
                CvFeature::Gabor => {
                    let mut patch = Patch {
                        values: [0.0; patchflow_learn::PATCH_LEN],
                    };
                    patch.values.copy_from_slice(values);
                    gabor.responses(&patch).to_vec()
                }
            }
        })
        .collect();
    Ok(rows_to_matrix(rows.iter().map(Vec::as_slice), d)?)
}

/// Per-test-sample errors of one fold and which samples count as low-variance.
pub(crate) struct FoldErrors {
    errors: Vec<f64>,
    low_var: Vec<bool>,
}

impl FoldErrors {
    fn low_var_errors(&self) -> Vec<f64> {
        self.errors
            .iter()
            .zip(&self.low_var)
            .filter(|(_, low)| **low)
            .map(|(e, _)| *e)
            .collect()
    }
}

/// Inputs and targets of one sample set (the drawn samples, or their mirror images).
pub(crate) struct FoldData {
    pub(crate) heading_x: DMatrix<f64>,
    pub(crate) speed_x: DMatrix<f64>,
    pub(crate) sin: DVector<f64>,
    pub(crate) cos: DVector<f64>,
    pub(crate) speed: DVector<f64>,
}

/// One fold of one configuration: train on the training split (and its mirror images), test on
/// the test split.
pub(crate) struct Fold<'a> {
    pub(crate) data: &'a FoldData,
    pub(crate) mirror: Option<&'a FoldData>,
    pub(crate) split: &'a Split,
    pub(crate) gp: CvGp,
    pub(crate) params: &'a CvParams,
}

impl Fold<'_> {
    pub(crate) fn heading(&self) -> Result<FoldErrors, EvalError> {
        let seed = self.params.seed;
        let sin_pred = self.fit_predict(|d| (&d.heading_x, &d.sin), seed.wrapping_add(1))?;
        let cos_pred = self.fit_predict(|d| (&d.heading_x, &d.cos), seed.wrapping_add(2))?;
        let errors = self
            .split
            .test
            .iter()
            .enumerate()
            .map(|(k, &i)| {
                let predicted = sin_pred.mean[k].atan2(cos_pred.mean[k]);
                let truth = self.data.sin[i].atan2(self.data.cos[i]);
                wrap_angle_rad(predicted - truth).to_degrees()
            })
            .collect();
        let (low_sin, low_cos) = (
            low_log_variance(&sin_pred.var_y),
            low_log_variance(&cos_pred.var_y),
        );
        let low_var = low_sin
            .iter()
            .zip(&low_cos)
            .map(|(a, b)| *a && *b)
            .collect();
        Ok(FoldErrors { errors, low_var })
    }

    pub(crate) fn speed(&self) -> Result<FoldErrors, EvalError> {
        let seed = self.params.seed.wrapping_add(3);
        let predicted = self.fit_predict(|d| (&d.speed_x, &d.speed), seed)?;
        let errors = self
            .split
            .test
            .iter()
            .enumerate()
            .map(|(k, &i)| predicted.mean[k] - self.data.speed[i])
            .collect();
        Ok(FoldErrors {
            errors,
            low_var: low_log_variance(&predicted.var_y),
        })
    }

    /// Fits a GP to the training rows that `pick` selects (with their mirror images) and
    /// predicts the test rows.
    fn fit_predict(
        &self,
        pick: impl Fn(&FoldData) -> (&DMatrix<f64>, &DVector<f64>),
        seed: u64,
    ) -> Result<GpPrediction, EvalError> {
        let kind = match self.gp {
            CvGp::Spgp => GpKind::Spgp,
            CvGp::SpgpHet => GpKind::SpgpHet,
        };
        let train = &self.split.train;
        let (x, y) = pick(self.data);
        let (mut x_train, mut y_train) = (x.select_rows(train), y.select_rows(train));
        if let Some(mirror) = self.mirror {
            let (xm, ym) = pick(mirror);
            let n = train.len();
            x_train = x_train.insert_rows(n, n, 0.0);
            x_train.rows_mut(n, n).copy_from(&xm.select_rows(train));
            y_train = y_train.insert_rows(n, n, 0.0);
            y_train.rows_mut(n, n).copy_from(&ym.select_rows(train));
        }
        let model = GpParams::new(kind)
            .pseudo_inputs(self.params.pseudo_inputs.min(x_train.nrows()))
            .max_iters(self.params.max_iters)
            .seed(seed)
            .fit(&x_train, &y_train)?;
        Ok(model.predict(&x.select_rows(&self.split.test))?)
    }
}

/// The low-log-variance rule: variance more than one standard deviation below the mean of the
/// variances (thesis 4.3.1: "we fit a Gaussian distribution to the predicted variances"). The
/// Gaussian is fitted to the logarithms: variances are positive and right-skewed, and for map
/// patches a few large ones pull the raw mean − 1 std below the smallest variance, which would
/// leave the subset empty. The BEST merge (`learn/src/estimator/merge.rs`) keeps the thesis'
/// raw-variance rule, since it falls back to ALL when its subset is empty.
pub(crate) fn low_log_variance(var: &DVector<f64>) -> Vec<bool> {
    let log_var: Vec<f64> = var.iter().map(|v| v.max(f64::MIN_POSITIVE).ln()).collect();
    let n = log_var.len().max(1) as f64;
    let mean = log_var.iter().sum::<f64>() / n;
    let std = (log_var.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
    log_var.iter().map(|v| *v < mean - std).collect()
}

/// Per-fold RMSEs, averaged at the end as in the thesis.
#[derive(Default)]
pub(crate) struct FoldAccumulator {
    heading: Vec<f64>,
    heading_low: Vec<f64>,
    speed: Vec<f64>,
    speed_low: Vec<f64>,
    n_test: usize,
    n_low_var: usize,
}

impl FoldAccumulator {
    pub(crate) fn add_heading(&mut self, fold: FoldErrors) {
        let low = fold.low_var_errors();
        self.n_test += fold.errors.len();
        self.n_low_var += low.len();
        self.heading.extend(rmse(&fold.errors));
        self.heading_low.extend(rmse(&low));
    }

    pub(crate) fn add_speed(&mut self, fold: FoldErrors) {
        let low = fold.low_var_errors();
        self.speed.extend(rmse(&fold.errors));
        self.speed_low.extend(rmse(&low));
    }

    pub(crate) fn row(&self, feature: CvFeature, prior: f64, gp: CvGp) -> CvRow {
        let mean = |v: &[f64]| (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64);
        CvRow {
            feature,
            prior,
            gp,
            heading_rmse_deg: mean(&self.heading).unwrap_or(f64::NAN),
            heading_rmse_low_var_deg: mean(&self.heading_low),
            speed_rmse_mps: mean(&self.speed),
            speed_rmse_low_var_mps: mean(&self.speed_low),
            n_test: self.n_test,
            n_low_var: self.n_low_var,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn right_skewed_variances_still_have_a_low_variance_subset() {
        // Log-normal variances: raw mean − 1 std of these lies below the smallest one.
        let z = [-2.0, -1.0, -1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 2.0];
        let var = DVector::<f64>::from_iterator(z.len(), z.iter().map(|z: &f64| z.exp()));
        assert!(var.mean() - var.variance().sqrt() < var.min());
        let low = low_log_variance(&var);
        let expected: Vec<bool> = z.iter().map(|z| *z < -1.5).collect();
        assert_eq!(low, expected);
    }

    #[test]
    fn gabor_features_use_the_bank_of_the_cells_the_patches_were_drawn_on() {
        let values: Vec<f64> = (0..patchflow_learn::PATCH_LEN)
            .map(|i| ((i * 7) % 11) as f64 / 10.0 - 0.5)
            .collect();
        let sample = patchflow_learn::TrainingSample {
            sequence: "s".into(),
            scan: 1,
            point: 0,
            actor: 1,
            weight: 1.0,
            bearing_rad: 0.0,
            sin_rel: 1.0,
            cos_rel: 0.0,
            heading_rad: 1.0,
            speed_mps: 5.0,
            heading_features: values.clone(),
            speed_features: values.clone(),
        };
        let features = patchflow_learn::EstimatorParams::default().features;
        assert_eq!(features.patch_cell_m, 0.2);
        let set = SampleSet {
            kind: FeatureKind::Patch,
            features: features.clone(),
            pool_size: 1,
            samples: vec![sample],
        };
        let x = features_of(&set, CvFeature::Gabor, |s| &s.heading_features).unwrap();
        let mut patch = Patch {
            values: [0.0; patchflow_learn::PATCH_LEN],
        };
        patch.values.copy_from_slice(&values);
        let responses = |cell_m: f64| GaborBank::new(&features.gabor, cell_m).responses(&patch);
        let row: Vec<f64> = x.row(0).iter().copied().collect();
        assert_eq!(row, responses(0.2).to_vec());
        assert_ne!(row, responses(0.1).to_vec());
    }

    #[test]
    fn equal_variances_have_no_low_variance_subset() {
        let low = low_log_variance(&DVector::from_element(5, 0.3));
        assert!(low.iter().all(|l| !l));
    }
}
