//! `patchflow score` (SPEC §7): another method's predictions, a folder in the layout `patchflow
//! flow` writes, scored against a dataset by the code that scores the built-in methods, with the
//! built-in methods beside them when models are given.

mod external_tally;
mod method_scores;
mod prediction_folder;
mod score_report;

use std::collections::BTreeMap;

use patchflow_dataset::Dataset;
use patchflow_learn::{FeatureParams, MotionEstimator, MovingClassifier, ScanStream};

use crate::error::EvalError;
use crate::methods::baselines::baseline_params::BaselineParams;
use crate::methods::method::Method;
use crate::pipeline::dataset_evaluation::{evaluate_dataset, sequences_to_evaluate};
use crate::scene::result::SceneResult;
use crate::scene::scene_point::ScenePoints;

pub use external_tally::ExternalTally;
pub use method_scores::{MethodScores, MethodSource, MethodTally};
pub use prediction_folder::{MAX_PREDICTED_SPEED_MPS, PredictionFolder};
pub use score_report::{ScoreFiles, ScoreReport, SequenceScores};

/// Scores every prediction folder on every sequence of `dataset` that `evaluate` scores, and
/// with `estimators` (one per GP kind) also every built-in method (with `moving`, the moving
/// classifier `train` writes beside the model, also the methods that use it). The scored points are the
/// height-sliced points in the map window of the first estimator's feature parameters (the
/// defaults without one), exactly those `evaluate` scores. `on_scan` hears of every scan.
///
/// ```no_run
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// use patchflow_eval::{PredictionFolder, score_predictions};
/// let dataset = patchflow_dataset::Dataset::open(std::path::Path::new("data/situations"))?;
/// let mine = PredictionFolder::parse("predictions/nn=NN-FLOW")?;
/// let report = score_predictions(&dataset, &[mine], &[], None, &|| {})?;
/// report.write(std::path::Path::new("results/score"))?;
/// # Ok(())
/// # }
/// ```
pub fn score_predictions(
    dataset: &Dataset,
    folders: &[PredictionFolder],
    estimators: &[MotionEstimator],
    moving: Option<&MovingClassifier>,
    on_scan: &(dyn Fn() + Sync),
) -> Result<ScoreReport, EvalError> {
    let names = sequences_to_evaluate(dataset)?;
    check_names(folders, !estimators.is_empty())?;
    for folder in folders {
        folder.check_against(dataset, &names)?;
    }
    let features = estimators
        .first()
        .map_or_else(FeatureParams::default, |e| e.feature_params().clone());
    // The built-in methods, by `evaluate`'s own code.
    let built_in = if estimators.is_empty() {
        Vec::new()
    } else {
        evaluate_dataset(
            dataset,
            estimators,
            &BaselineParams::default(),
            moving,
            on_scan,
        )?
        .scenes
    };
    let mut sequences = BTreeMap::new();
    let mut pooled: BTreeMap<String, MethodTally> = BTreeMap::new();
    let mut pooled_scans = 0;
    for name in &names {
        let (scans, mut tallies) = score_sequence(dataset, name, folders, &features, on_scan)?;
        if let Some(scene) = built_in.iter().find(|s| &s.name == name) {
            tallies.extend(built_in_tallies(scene));
        }
        let mut methods = BTreeMap::new();
        for (method, tally) in tallies {
            methods.insert(method.clone(), tally.scores()?);
            match pooled.get_mut(&method) {
                Some(all) => all.merge(&tally),
                None => {
                    pooled.insert(method, tally);
                }
            }
        }
        pooled_scans += scans;
        sequences.insert(name.clone(), SequenceScores { scans, methods });
    }
    let methods = pooled
        .into_iter()
        .map(|(method, tally)| Ok((method, tally.scores()?)))
        .collect::<Result<_, EvalError>>()?;
    Ok(ScoreReport {
        dataset: dataset.root().display().to_string(),
        scored_points: match estimators.first() {
            Some(_) => "the height slice and map window of the first model's features".into(),
            None => "the height slice and map window of the default features".into(),
        },
        sequences,
        pooled: SequenceScores {
            scans: pooled_scans,
            methods,
        },
    })
}

/// Every prediction folder on one sequence, scan by scan as `evaluate` replays it.
fn score_sequence(
    dataset: &Dataset,
    name: &str,
    folders: &[PredictionFolder],
    features: &FeatureParams,
    on_scan: &(dyn Fn() + Sync),
) -> Result<(usize, BTreeMap<String, MethodTally>), EvalError> {
    let sequence = dataset.sequence(name)?;
    let mut tallies: Vec<ExternalTally> = vec![ExternalTally::default(); folders.len()];
    let mut stream = ScanStream::new(&sequence, vec![features.clone()])?;
    let mut scans = 0;
    while let Some((index, sweep)) = stream.read_next()? {
        let scan_features = stream.features_of(&sweep)?;
        let dt_secs = sweep.stamp_secs - sequence.stamps_secs()[index - 1];
        let points = ScenePoints::new(&scan_features[0], &sweep, dt_secs);
        for (k, folder) in folders.iter().enumerate() {
            let flow = folder.read_flow(name, index, sweep.len())?;
            let moving = folder.read_moving(name, index, sweep.len())?;
            let mask = moving.as_deref();
            tallies[k].add_scan(index - 1, &scan_features[0], &sweep, &points, &flow, mask);
        }
        scans += 1;
        on_scan();
    }
    let mut out = BTreeMap::new();
    for (folder, tally) in folders.iter().zip(tallies) {
        let source = MethodSource::Predictions(folder.root.display().to_string());
        let mut method = MethodTally::new(source, true);
        method.flow = tally.flow;
        method.mask = tally.mask;
        method.add_objects(&tally.object_truth, &tally.object_estimates);
        out.insert(folder.name.clone(), method);
    }
    Ok((scans, out))
}

/// The built-in methods' tallies of one evaluated sequence.
fn built_in_tallies(scene: &SceneResult) -> BTreeMap<String, MethodTally> {
    let mut out: BTreeMap<String, MethodTally> = BTreeMap::new();
    let source = |m: Method| match m.is_oracle() {
        true => MethodSource::Oracle,
        false => MethodSource::BuiltIn,
    };
    for (&method, flow) in &scene.scene_flow {
        let mut tally = MethodTally::new(source(method), method.has_heading());
        tally.flow = flow.clone();
        out.insert(method.name().to_owned(), tally);
    }
    for object in &scene.objects {
        for (&method, estimate) in &object.estimates {
            let tally = out
                .entry(method.name().to_owned())
                .or_insert_with(|| MethodTally::new(source(method), method.has_heading()));
            tally.add_objects(&[object.truth], &[*estimate]);
        }
    }
    out
}

/// Method names must be distinct, and distinct from the built-in ones when those are scored.
fn check_names(folders: &[PredictionFolder], with_built_in: bool) -> Result<(), EvalError> {
    for (k, folder) in folders.iter().enumerate() {
        let clash = folders[..k].iter().any(|f| f.name == folder.name)
            || (with_built_in && Method::ALL.iter().any(|m| m.name() == folder.name));
        if clash {
            return Err(EvalError::BadParameter {
                name: "predictions",
                reason: format!(
                    "two methods named {:?} ({}): name each folder as PATH=NAME",
                    folder.name,
                    folder.root.display()
                ),
            });
        }
    }
    Ok(())
}
