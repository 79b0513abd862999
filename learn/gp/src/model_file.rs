//! Versioned GP model files (SPEC §7): JSON with `format`/`version`, the kind, the kernel's factors
//! (version 2, for kernels other than SE-ARD), lengthscales (not
//! squared), signal and noise variance, pseudo-inputs, pseudo-noise (SPGP-HET), jitter, the input
//! and target transforms, column names, the fit report and the cached posterior (for the full GP,
//! its standardised training data). All parameters are in the standardised space of the fit.

use std::path::Path;

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use super::full::FullPosterior;
use super::hyper::Hyper;
use super::kernel::Kernel;
use super::model::{FitReport, GpModel, Posterior};
use super::params::{GpKind, MAX_PSEUDO_INPUTS};
use super::shape::Factor;
use super::sparse_posterior::SparsePosterior;
use super::stationary::Stationary;
use super::train_data::TrainData;
use super::transform::Standardiser;
use crate::{GpError, Result};

/// The `format` tag of a GP model file.
pub const GP_MODEL_FORMAT: &str = "patchflow-gp-model";
/// The newest model-file version this build writes and reads. Version 2 adds the `kernel` field
/// for kernels other than SE-ARD; SE-ARD models are still written as version 1, unchanged, so
/// earlier builds read them and refuse the kernels they do not know.
pub const GP_MODEL_VERSION: u32 = 2;
/// The version of SE-ARD model files (no `kernel` field).
const SE_ARD_VERSION: u32 = 1;

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case")]
enum PosteriorFile {
    Sparse {
        weights: Vec<f64>,
        var_matrix: Vec<Vec<f64>>,
    },
    Full {
        x_train: Vec<Vec<f64>>,
        y_train: Vec<f64>,
    },
}

/// A GP model file's contents as typed fields, read straight from the file's bytes (no generic
/// JSON tree, which costs ~17× the file in memory) and checked by [`GpModel::from_record`]. A
/// larger model file (the motion estimator's) embeds it as a field.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct GpModelRecord {
    format: String,
    version: u32,
    kind: GpKind,
    input_names: Vec<String>,
    target_name: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    kernel: Option<Vec<Factor>>,
    lengthscales: Vec<f64>,
    signal_variance: f64,
    noise_variance: f64,
    pseudo_inputs: Vec<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pseudo_noise: Option<Vec<f64>>,
    jitter: f64,
    input_transform: Standardiser,
    target_transform: Standardiser,
    posterior: PosteriorFile,
    fit_report: FitReport,
}

fn rows(m: &DMatrix<f64>) -> Vec<Vec<f64>> {
    m.row_iter().map(|r| r.iter().copied().collect()).collect()
}

fn matrix(rows: &[Vec<f64>], cols: usize, what: &str) -> std::result::Result<DMatrix<f64>, String> {
    if let Some(i) = rows.iter().position(|r| r.len() != cols) {
        return Err(format!(
            "{what} row {i} has {} values, expected {cols}",
            rows[i].len()
        ));
    }
    Ok(DMatrix::from_fn(rows.len(), cols, |i, j| rows[i][j]))
}

fn check(ok: bool, why: &str) -> std::result::Result<(), String> {
    if ok { Ok(()) } else { Err(why.to_string()) }
}

fn finite(values: &[f64]) -> bool {
    values.iter().all(|v| v.is_finite())
}

impl GpModelRecord {
    fn into_model(self) -> std::result::Result<GpModel, String> {
        check(
            self.format == GP_MODEL_FORMAT,
            &format!("not a patchflow GP model (format '{}')", self.format),
        )?;
        check(
            self.version == SE_ARD_VERSION || self.version == GP_MODEL_VERSION,
            &format!(
                "model file version {}; this build reads versions {SE_ARD_VERSION} and \
                 {GP_MODEL_VERSION}",
                self.version
            ),
        )?;
        check(
            self.kernel.is_some() == (self.version == GP_MODEL_VERSION),
            "a kernel field belongs to version 2 files, and only there",
        )?;
        let d = self.input_names.len();
        check(
            d > 0 && self.lengthscales.len() == d,
            "lengthscales do not match the input columns",
        )?;
        check(
            self.lengthscales.iter().all(|l| l.is_finite() && *l > 0.0),
            "lengthscales must be positive",
        )?;
        let positive = |v: f64| v.is_finite() && v > 0.0;
        check(
            positive(self.signal_variance) && positive(self.noise_variance),
            "variances must be positive",
        )?;
        check(
            self.jitter.is_finite() && self.jitter >= 0.0,
            "jitter must be non-negative",
        )?;
        for (t, n, what) in [
            (&self.input_transform, d, "input"),
            (&self.target_transform, 1, "target"),
        ] {
            check(
                t.mean.len() == n && t.scale.len() == n,
                &format!("{what} transform has the wrong length"),
            )?;
            check(
                finite(&t.mean) && t.scale.iter().all(|s| positive(*s)),
                &format!("{what} transform is invalid"),
            )?;
        }
        check(
            self.pseudo_inputs.len() <= MAX_PSEUDO_INPUTS,
            &format!(
                "{} pseudo-inputs; a sparse GP has at most {MAX_PSEUDO_INPUTS}",
                self.pseudo_inputs.len()
            ),
        )?;
        let z = matrix(&self.pseudo_inputs, d, "pseudo_inputs")?;
        let m = z.nrows();
        check(finite(z.as_slice()), "pseudo-inputs must be finite")?;
        let pseudo_noise = self.pseudo_noise.map(DVector::from_vec);
        check(
            pseudo_noise.is_some() == (self.kind == GpKind::SpgpHet),
            "pseudo_noise is present iff kind is spgp-het",
        )?;
        if let Some(h) = &pseudo_noise {
            check(
                h.len() == m && h.iter().all(|v| v.is_finite() && *v >= 0.0),
                "pseudo_noise is invalid",
            )?;
        }
        let factors = self
            .kernel
            .unwrap_or_else(|| Stationary::se_ard().factors().to_vec());
        let kernel = Stationary::with_values(
            factors,
            DVector::from_vec(self.lengthscales),
            self.signal_variance,
        )
        .map_err(|e| e.to_string())?;
        let hyper = Hyper {
            kernel,
            noise_variance: self.noise_variance,
            pseudo_inputs: z,
            pseudo_noise,
        };
        let posterior = match (self.kind, self.posterior) {
            (
                GpKind::Spgp | GpKind::SpgpHet,
                PosteriorFile::Sparse {
                    weights,
                    var_matrix,
                },
            ) => {
                check(
                    m > 0 && weights.len() == m && var_matrix.len() == m,
                    "posterior does not match the pseudo-inputs",
                )?;
                let rows = var_matrix;
                let var_matrix = matrix(&rows, m, "var_matrix")?;
                drop(rows);
                check(
                    finite(&weights) && finite(var_matrix.as_slice()),
                    "posterior must be finite",
                )?;
                let posterior = SparsePosterior {
                    weights: DVector::from_vec(weights),
                    var_matrix,
                };
                posterior.check(&hyper, self.jitter)?;
                Posterior::Sparse(posterior)
            }
            (GpKind::Full, PosteriorFile::Full { x_train, y_train }) => {
                let x = matrix(&x_train, d, "x_train")?;
                check(
                    x.nrows() == y_train.len() && x.nrows() > 0,
                    "x_train and y_train differ in length",
                )?;
                check(
                    finite(x.as_slice()) && finite(&y_train),
                    "training data must be finite",
                )?;
                let data = TrainData::new(&x, &DVector::from_vec(y_train));
                let (p, _) =
                    FullPosterior::new(&data, &hyper, self.jitter).map_err(|e| e.to_string())?;
                Posterior::Full(p)
            }
            _ => return Err("the posterior does not match the model kind".into()),
        };
        Ok(GpModel {
            kind: self.kind,
            input_names: self.input_names,
            target_name: self.target_name,
            inputs: self.input_transform,
            target: self.target_transform,
            hyper,
            jitter: self.jitter,
            posterior,
            report: self.fit_report,
        })
    }
}

impl GpModel {
    /// The model as the typed record of its file, e.g. to embed it in a larger model file.
    pub fn to_record(&self) -> GpModelRecord {
        let h = &self.hyper;
        let se_ard = h.kernel.is_se_ard();
        GpModelRecord {
            format: GP_MODEL_FORMAT.into(),
            version: if se_ard {
                SE_ARD_VERSION
            } else {
                GP_MODEL_VERSION
            },
            kind: self.kind,
            input_names: self.input_names.clone(),
            target_name: self.target_name.clone(),
            kernel: (!se_ard).then(|| h.kernel.factors().to_vec()),
            lengthscales: h.kernel.lengthscales().iter().copied().collect(),
            signal_variance: h.kernel.signal_variance(),
            noise_variance: h.noise_variance,
            pseudo_inputs: rows(&h.pseudo_inputs),
            pseudo_noise: h.pseudo_noise.as_ref().map(|v| v.iter().copied().collect()),
            jitter: self.jitter,
            input_transform: self.inputs.clone(),
            target_transform: self.target.clone(),
            posterior: match &self.posterior {
                Posterior::Sparse(p) => PosteriorFile::Sparse {
                    weights: p.weights.iter().copied().collect(),
                    var_matrix: rows(&p.var_matrix),
                },
                Posterior::Full(p) => PosteriorFile::Full {
                    x_train: rows(&p.x),
                    y_train: p.y.iter().copied().collect(),
                },
            },
            fit_report: self.report.clone(),
        }
    }

    /// The model as a JSON value.
    pub fn to_json_value(&self) -> Result<serde_json::Value> {
        serde_json::to_value(self.to_record()).map_err(|e| GpError::Model {
            path: "<GP model>".into(),
            reason: e.to_string(),
        })
    }

    /// Reads a model from its typed record, checking every field; `origin` names the file it came
    /// from in errors.
    pub fn from_record(record: GpModelRecord, origin: &Path) -> Result<Self> {
        record.into_model().map_err(|reason| GpError::Model {
            path: origin.to_path_buf(),
            reason,
        })
    }

    /// Reads a model from a JSON value; `origin` names the file it came from in errors.
    pub fn from_json_value(value: serde_json::Value, origin: &Path) -> Result<Self> {
        let err = |reason: String| GpError::Model {
            path: origin.to_path_buf(),
            reason,
        };
        let format = value.get("format").and_then(|f| f.as_str()).unwrap_or("");
        if format != GP_MODEL_FORMAT {
            return Err(err(format!("not a patchflow GP model (format '{format}')")));
        }
        let record: GpModelRecord =
            serde_json::from_value(value).map_err(|e| err(format!("corrupt GP model: {e}")))?;
        Self::from_record(record, origin)
    }

    /// Writes the model to `path` (atomically: a temporary file renamed into place).
    pub fn save(&self, path: &Path) -> Result<()> {
        let io = |source| GpError::Io {
            path: path.to_path_buf(),
            source,
        };
        let mut bytes = serde_json::to_vec(&self.to_record()).map_err(|e| GpError::Model {
            path: path.to_path_buf(),
            reason: e.to_string(),
        })?;
        bytes.push(b'\n');
        let tmp = path.with_extension("json.tmp");
        std::fs::write(&tmp, bytes).map_err(io)?;
        std::fs::rename(&tmp, path).map_err(io)
    }

    /// Reads a model written by [`GpModel::save`].
    pub fn load(path: &Path) -> Result<Self> {
        let io = |source| GpError::Io {
            path: path.to_path_buf(),
            source,
        };
        // Checked before opening: a FIFO would block the read, a device never end it.
        let meta = std::fs::metadata(path).map_err(io)?;
        let len = meta.len();
        let refuse = |reason: String| GpError::Model {
            path: path.to_path_buf(),
            reason,
        };
        if !meta.is_file() {
            return Err(refuse(
                "not a regular file (a folder, pipe or device)".into(),
            ));
        }
        if len > MAX_GP_MODEL_BYTES {
            return Err(refuse(format!(
                "too large ({len} bytes, limit {MAX_GP_MODEL_BYTES})"
            )));
        }
        let bytes = std::fs::read(path).map_err(io)?;
        let record = GpModelRecord::parse(&bytes).map_err(refuse)?;
        drop(bytes);
        Self::from_record(record, path)
    }
}

/// The fields a reader looks at first, to say what a file is when it is not a GP model.
#[derive(Deserialize)]
struct Header {
    #[serde(default)]
    format: Option<String>,
}

impl GpModelRecord {
    /// Parses a GP model file's bytes straight into the record; a file of another format or
    /// broken JSON is named as such.
    fn parse(bytes: &[u8]) -> std::result::Result<Self, String> {
        serde_json::from_slice(bytes).map_err(|e| {
            if e.is_syntax() || e.is_eof() {
                return format!("not valid JSON: {e}");
            }
            let format = serde_json::from_slice::<Header>(bytes)
                .ok()
                .and_then(|h| h.format)
                .unwrap_or_default();
            if format != GP_MODEL_FORMAT {
                format!("not a patchflow GP model (format '{format}')")
            } else {
                format!("corrupt GP model: {e}")
            }
        })
    }
}

/// Largest GP model file read: 512 MiB, as for a motion model of three GPs.
const MAX_GP_MODEL_BYTES: u64 = 512 << 20;

#[cfg(test)]
#[path = "model_file_tests.rs"]
mod tests;
