//! The motion estimator's model file: one versioned JSON holding the three GPs, every feature
//! parameter the run-time maps must reproduce, and what the training saw.

use std::path::Path;

use patchflow_gp::GpModelRecord;
use serde::{Deserialize, Serialize};

use super::motion_estimator::{MotionEstimator, TrainingRecord};
use super::projection::Projection;
use super::regressor::{NoiseModel, Regressor, projected_names};
use crate::{
    FeatureKind, FeatureParams, GaborParams, GpKind, GpModel, GroundMode, LearnError, Result,
};

/// Format name written into every estimator model file.
pub const MOTION_MODEL_FORMAT: &str = "patchflow-motion-model";
/// Version of the estimator model file this build writes. Version 3 records the ground the height
/// slice is measured from (`features.ground`); version 2 files, from before the ground estimate,
/// are read with the flat ground their maps were cut above.
pub const MOTION_MODEL_VERSION: u32 = 3;
/// The last version without `features.ground`.
const FLAT_GROUND_VERSION: u32 = 2;

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ModelFile {
    format: String,
    version: u32,
    generator: String,
    gp: GpKind,
    feature: String,
    features: FeatureRecord,
    training: TrainingRecord,
    heading_sin: GpModelRecord,
    heading_cos: GpModelRecord,
    speed: GpModelRecord,
    /// Each regression's PLS projection and noise GP (sin, cos, speed), when the model has any
    /// (thesis Ch. 6 options); absent for the thesis' plain GPs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    extras: Option<Vec<RegressorExtras>>,
}

/// What a regression holds beside its GP.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RegressorExtras {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    projection: Option<Projection>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    noise_gp: Option<GpModelRecord>,
    #[serde(default)]
    noise_offset: f64,
}

/// Every field of [`FeatureParams`], so a model reproduces its maps exactly.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FeatureRecord {
    slice_min_m: f64,
    slice_max_m: f64,
    /// `GroundMode::name`; absent in version 2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    ground: Option<String>,
    cell_m: f64,
    /// [`FeatureParams::patch_cell_m`]; absent in files written before the patches had maps of
    /// their own, whose patches sampled the maps themselves (`cell_m`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    patch_cell_m: Option<f64>,
    half_extent_m: f64,
    prior: f64,
    spread: f64,
    cluster_gap_m: f64,
    speed_jitter_deg: f64,
    gabor_wavelength_m: f64,
    gabor_sigma_m: f64,
    gabor_gamma: f64,
}

impl From<&FeatureParams> for FeatureRecord {
    fn from(p: &FeatureParams) -> Self {
        Self {
            slice_min_m: p.slice_min_m,
            slice_max_m: p.slice_max_m,
            ground: Some(p.ground.name().to_owned()),
            cell_m: p.cell_m,
            patch_cell_m: Some(p.patch_cell_m),
            half_extent_m: p.half_extent_m,
            prior: p.prior,
            spread: p.spread,
            cluster_gap_m: p.cluster_gap_m,
            speed_jitter_deg: p.speed_jitter_deg,
            gabor_wavelength_m: p.gabor.wavelength_m,
            gabor_sigma_m: p.gabor.sigma_m,
            gabor_gamma: p.gabor.gamma,
        }
    }
}

impl From<FeatureRecord> for FeatureParams {
    fn from(r: FeatureRecord) -> Self {
        Self {
            slice_min_m: r.slice_min_m,
            slice_max_m: r.slice_max_m,
            ground: GroundMode::Flat, // set from the version by `ground_of`
            cell_m: r.cell_m,
            patch_cell_m: r.patch_cell_m.unwrap_or(r.cell_m),
            half_extent_m: r.half_extent_m,
            prior: r.prior,
            spread: r.spread,
            cluster_gap_m: r.cluster_gap_m,
            speed_jitter_deg: r.speed_jitter_deg,
            gabor: GaborParams {
                wavelength_m: r.gabor_wavelength_m,
                sigma_m: r.gabor_sigma_m,
                gamma: r.gabor_gamma,
            },
        }
    }
}

/// The ground a model's maps were cut above: named in version 3, flat in version 2.
fn ground_of(version: u32, name: Option<&str>) -> std::result::Result<GroundMode, String> {
    match (version, name) {
        (FLAT_GROUND_VERSION, None) => Ok(GroundMode::Flat),
        (FLAT_GROUND_VERSION, Some(_)) => Err("features.ground is not part of version 2".into()),
        (_, None) => Err("features.ground is missing".into()),
        (_, Some(name)) => GroundMode::parse(name)
            .ok_or_else(|| format!("unknown features.ground '{name}' (flat or estimated)")),
    }
}

/// Largest model file read: 512 MiB, above three full GPs at their sample limit.
const MAX_MODEL_BYTES: u64 = 512 << 20;

/// The fields read first, to say what a file is when it is not a model this build reads.
#[derive(Deserialize)]
struct Header {
    #[serde(default)]
    format: Option<String>,
    #[serde(default)]
    version: Option<u64>,
}

/// Why `bytes` are not a motion model this build reads: another format or version (from the
/// header alone), broken JSON, or a field of the wrong type or shape.
fn refusal(bytes: &[u8], err: &serde_json::Error) -> String {
    if err.is_syntax() || err.is_eof() {
        return format!("not valid JSON: {err}");
    }
    let header = serde_json::from_slice::<Header>(bytes).unwrap_or(Header {
        format: None,
        version: None,
    });
    let format = header.format.unwrap_or_default();
    let version = header.version.unwrap_or(0);
    if format != MOTION_MODEL_FORMAT {
        format!(
            "not a patchflow motion model (format '{format}'; a single GP from `patchflow gp fit` is not an estimator)"
        )
    } else if version != u64::from(MOTION_MODEL_VERSION)
        && version != u64::from(FLAT_GROUND_VERSION)
    {
        format!(
            "motion model version {version} is not supported (this build reads versions {FLAT_GROUND_VERSION} and {MOTION_MODEL_VERSION}); retrain it with `patchflow train`"
        )
    } else {
        format!("corrupt motion model: {err}")
    }
}

fn feature_name(kind: FeatureKind) -> &'static str {
    match kind {
        FeatureKind::Patch => "patch",
        FeatureKind::Gabor => "gabor",
    }
}

impl MotionEstimator {
    /// Writes the model to `path` atomically (a temporary file renamed into place).
    pub fn save(&self, path: &Path) -> Result<()> {
        let file = ModelFile {
            format: MOTION_MODEL_FORMAT.to_owned(),
            version: MOTION_MODEL_VERSION,
            generator: concat!("patchflow ", env!("CARGO_PKG_VERSION")).to_owned(),
            gp: self.gp,
            feature: feature_name(self.feature).to_owned(),
            features: FeatureRecord::from(self.features.params()),
            training: self.training.clone(),
            heading_sin: self.heading_sin.gp.to_record(),
            heading_cos: self.heading_cos.gp.to_record(),
            speed: self.speed.gp.to_record(),
            extras: self.extras_record(),
        };
        let model_err = |reason: String| LearnError::model(path, reason);
        let mut bytes = serde_json::to_vec(&file).map_err(|e| model_err(e.to_string()))?;
        bytes.push(b'\n');
        patchflow_dataset::write_atomic(path, &bytes)?;
        Ok(())
    }

    /// Reads a model written by [`MotionEstimator::save`]; another format or version, or a
    /// corrupt file, is an error naming the file.
    pub fn load(path: &Path) -> Result<Self> {
        let model_err = |reason: String| LearnError::model(path, reason);
        let bytes = patchflow_dataset::read_limited(path, MAX_MODEL_BYTES)?;
        // Straight into typed fields: a generic JSON tree of a large model costs ~17× its size.
        let file: ModelFile =
            serde_json::from_slice(&bytes).map_err(|e| model_err(refusal(&bytes, &e)))?;
        drop(bytes);
        if file.format != MOTION_MODEL_FORMAT
            || (file.version != MOTION_MODEL_VERSION && file.version != FLAT_GROUND_VERSION)
        {
            return Err(model_err(format!(
                "format '{}' version {} is not a motion model this build reads (versions {FLAT_GROUND_VERSION} and {MOTION_MODEL_VERSION} of {MOTION_MODEL_FORMAT})",
                file.format, file.version
            )));
        }
        let feature = match file.feature.as_str() {
            "patch" => FeatureKind::Patch,
            "gabor" => FeatureKind::Gabor,
            other => return Err(model_err(format!("unknown feature kind '{other}'"))),
        };
        let ground = ground_of(file.version, file.features.ground.as_deref()).map_err(model_err)?;
        let features = FeatureParams {
            ground,
            ..FeatureParams::from(file.features)
        };
        let features = features.check().map_err(|e| model_err(e.to_string()))?;
        let gps = [file.heading_sin, file.heading_cos, file.speed];
        let extras: Vec<Option<RegressorExtras>> = match file.extras {
            None => vec![None, None, None],
            Some(e) if e.len() == 3 => e.into_iter().map(Some).collect(),
            Some(e) => {
                return Err(model_err(format!(
                    "extras for {} regressions, expected 3",
                    e.len()
                )));
            }
        };
        let mut regressors = Vec::with_capacity(3);
        for (gp, extra) in gps.into_iter().zip(extras) {
            let mut r = Regressor::plain(GpModel::from_record(gp, path)?);
            if let Some(extra) = extra {
                if let Some(p) = &extra.projection
                    && !p.is_consistent()
                {
                    return Err(model_err("an inconsistent PLS projection".into()));
                }
                r.projection = extra.projection;
                if let Some(noise) = extra.noise_gp {
                    r.noise = Some(NoiseModel {
                        gp: GpModel::from_record(noise, path)?,
                        offset: extra.noise_offset,
                    });
                }
            }
            regressors.push(r);
        }
        let [heading_sin, heading_cos, speed]: [Regressor; 3] = regressors
            .try_into()
            .map_err(|_| model_err("expected three regressions".into()))?;
        let estimator = Self {
            gp: file.gp,
            feature,
            heading_sin,
            heading_cos,
            speed,
            features,
            training: file.training,
        };
        estimator.check_content().map_err(model_err)?;
        Ok(estimator)
    }

    /// What the regressions hold beside their GPs, `None` for the thesis' plain GPs.
    fn extras_record(&self) -> Option<Vec<RegressorExtras>> {
        let regressors = self.regressors();
        if regressors
            .iter()
            .all(|r| r.projection.is_none() && r.noise.is_none())
        {
            return None;
        }
        let extras = regressors.into_iter().map(|r| RegressorExtras {
            projection: r.projection.clone(),
            noise_gp: r.noise.as_ref().map(|n| n.gp.to_record()),
            noise_offset: r.noise.as_ref().map_or(0.0, |n| n.offset),
        });
        Some(extras.collect())
    }

    /// The labels written in the file must agree with what the GPs are: `gp` with each GP's
    /// kind (so a file cannot be edited to report one method's results under another's name),
    /// `feature` with their input columns, and the targets in their order.
    fn check_content(&self) -> std::result::Result<(), String> {
        let feature_names = self.feature.names();
        for (r, target) in self
            .regressors()
            .into_iter()
            .zip(["sin_rel", "cos_rel", "speed"])
        {
            let gp = &r.gp;
            let names = match &r.projection {
                None => feature_names.clone(),
                Some(p) => {
                    if p.input_dims() != feature_names.len() {
                        return Err(format!(
                            "the {target} projection reads {} values, the {} feature has {}",
                            p.input_dims(),
                            feature_name(self.feature),
                            feature_names.len()
                        ));
                    }
                    projected_names(p.dims)
                }
            };
            if let Some(noise) = &r.noise
                && noise.gp.input_names() != names.as_slice()
            {
                return Err(format!(
                    "the {target} noise GP reads other inputs than its GP"
                ));
            }
            if gp.kind() != self.gp {
                return Err(format!(
                    "the file says gp {}, but its {target} GP is {}",
                    self.gp,
                    gp.kind()
                ));
            }
            if gp.input_names() != names.as_slice() {
                return Err(format!(
                    "the {target} GP reads {} inputs that are not the {} feature's {} columns",
                    gp.input_names().len(),
                    feature_name(self.feature),
                    names.len()
                ));
            }
            if gp.target_name() != target {
                return Err(format!(
                    "expected the {target} GP, found one predicting {:?}",
                    gp.target_name()
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_version_2_model_is_read_with_the_flat_ground_and_version_3_names_its_own() {
        assert_eq!(ground_of(2, None), Ok(GroundMode::Flat));
        assert_eq!(ground_of(3, Some("estimated")), Ok(GroundMode::Estimated));
        assert_eq!(ground_of(3, Some("flat")), Ok(GroundMode::Flat));
        assert!(ground_of(3, None).is_err() && ground_of(2, Some("flat")).is_err());
        assert!(ground_of(3, Some("level")).unwrap_err().contains("level"));
    }
}
