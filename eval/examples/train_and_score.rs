//! One experiment of the training loop without the whole-scene pass of `evaluate`: trains an
//! SPGP-HET estimator (or loads model files) and scores the target alone in every situation of a
//! dataset, as `bench` scores its further training seeds (`patchflow_eval::stages::
//! evaluate_targets`): SPGP-HET-ALL heading RMSE (°) and speed RMSE (m/s) and the mean speed
//! error per situation, against the README's bar. Prints one Markdown row and writes it as JSON
//! when `json=PATH` is given.
//!
//! `cargo run --release -p patchflow-eval --example train_and_score -- situations=DIR
//! (train=DIR [samples=1600] [pseudo=100] [iters=300] [seed=7] [mirror=1] [jitter=25]
//! [min_speed=V] [preset=thesis] [zero_mean=0|1] [pls=K] [mlhgp=0|1] [save=MODEL.json] |
//! model=MODEL.json) [label=TEXT] [json=PATH] [scans=SITUATION]`

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use patchflow_dataset::Dataset;
use patchflow_eval::{Method, score_method, stages::evaluate_targets};
use patchflow_learn::{EstimatorParams, FeatureParams, GpKind, MotionEstimator, SampleSet};

type Failure = Box<dyn std::error::Error>;

fn main() -> Result<(), Failure> {
    let args: BTreeMap<String, String> = std::env::args()
        .skip(1)
        .filter_map(|a| a.split_once('=').map(|(k, v)| (k.to_owned(), v.to_owned())))
        .collect();
    let get = |k: &str| args.get(k).map(String::as_str);
    let situations = Dataset::open(Path::new(get("situations").ok_or("situations=DIR")?))?;
    let cpu = std::time::Instant::now();
    let estimator = match (get("model"), get("train")) {
        (Some(model), _) => MotionEstimator::load(Path::new(model))?,
        (None, Some(train)) => {
            // `preset=thesis` starts from the thesis' protocol; `zero_mean=0|1`, `pls=K` and
            // `mlhgp=0|1` switch the estimator's options (docs/estimator.md).
            let defaults = match get("preset") {
                Some("thesis") => EstimatorParams::thesis(),
                _ => EstimatorParams::default(),
            };
            let flag = |k: &str, default: bool| get(k).map_or(default, |v| v == "1");
            let params = EstimatorParams {
                zero_mean: flag("zero_mean", defaults.zero_mean),
                most_likely_noise: flag("mlhgp", defaults.most_likely_noise),
                projection_dims: get("pls").map_or(Ok(defaults.projection_dims), str::parse)?,
                gp: GpKind::SpgpHet,
                samples: get("samples").map_or(Ok(1600), str::parse)?,
                pseudo_inputs: get("pseudo").map_or(Ok(100), str::parse)?,
                max_iters: get("iters").map_or(Ok(300), str::parse)?,
                seed: get("seed").map_or(Ok(7), str::parse)?,
                mirror_images: flag("mirror", defaults.mirror_images),
                features: FeatureParams {
                    speed_jitter_deg: get("jitter")
                        .map_or(Ok(defaults.features.speed_jitter_deg), str::parse)?,
                    ..defaults.features.clone()
                },
                ..defaults
            };
            let dataset = Dataset::open(Path::new(train))?;
            // `min_speed=V` fits on the drawn samples of actors at V m/s or more only (a probe
            // of what the slow actors, mostly pedestrians, do to the GPs).
            let estimator = match get("min_speed") {
                None => MotionEstimator::train(&dataset, &params)?,
                Some(v) => {
                    let v: f64 = v.parse()?;
                    let mut set = SampleSet::collect(
                        &dataset,
                        &params.features,
                        params.feature,
                        params.samples,
                        params.seed,
                    )?;
                    set.samples.retain(|s| s.speed_mps >= v);
                    eprintln!("{} samples at {v} m/s or more", set.samples.len());
                    MotionEstimator::fit_samples(&set, &params)?.with_sequences(&dataset)
                }
            };
            if let Some(path) = get("save") {
                estimator.save(&PathBuf::from(path))?;
            }
            estimator
        }
        (None, None) => return Err("train=DIR or model=FILE".into()),
    };
    let trained_secs = cpu.elapsed().as_secs_f64();
    for gp in estimator.gps() {
        let report = gp.fit_report();
        let mut ls: Vec<f64> = gp.lengthscales().iter().copied().collect();
        ls.sort_by(f64::total_cmp);
        let h = gp
            .pseudo_noise()
            .map_or(0.0, |h| h.iter().sum::<f64>() / h.len().max(1) as f64);
        eprintln!(
            "{}: nlml {:.1}, {} iterations, noise variance {:.3e}, mean pseudo-noise {h:.3}, lengthscales min/median {:.2}/{:.2}",
            gp.target_name(),
            report.nlml,
            report.iterations,
            gp.noise_variance(),
            ls.first().copied().unwrap_or(f64::NAN),
            ls.get(ls.len() / 2).copied().unwrap_or(f64::NAN),
        );
    }
    let results = evaluate_targets(&situations, &[vec![estimator]])?;
    let mut cells = Vec::new();
    let mut json = Vec::new();
    let mut met = 0;
    for situation in results.into_iter().flatten() {
        let estimates = situation
            .methods
            .get(&Method::SpgpHetAll)
            .or_else(|| situation.methods.get(&Method::SpgpHetAllThesis))
            .ok_or("no SPGP-HET-ALL estimates")?;
        let m = score_method(&situation.truth, estimates)?;
        let (h, s) = (
            m.heading_rmse_deg.unwrap_or(f64::NAN),
            m.speed_rmse_mps.unwrap_or(f64::NAN),
        );
        // Mean signed speed error over scans with an estimate.
        let errors: Vec<f64> = situation
            .truth
            .iter()
            .zip(estimates)
            .filter_map(|(t, e)| e.as_ref().map(|e| e.speed_mps - t.speed_mps))
            .collect();
        let bias = errors.iter().sum::<f64>() / errors.len().max(1) as f64;
        if get("scans") == Some(situation.name.as_str()) {
            for (t, e) in situation.truth.iter().zip(estimates) {
                let est = e.as_ref().map_or("-".to_owned(), |e| {
                    format!(
                        "{:7.1} deg {:5.2} m/s",
                        e.heading_rad.to_degrees(),
                        e.speed_mps
                    )
                });
                eprintln!(
                    "scan {:3} range {:5.1} m points {:5}: truth {:7.1} deg {:5.2} m/s, estimate {est}",
                    t.scan,
                    t.range_m.unwrap_or(f64::NAN),
                    t.target_points.unwrap_or(0),
                    t.heading_rad.to_degrees(),
                    t.speed_mps
                );
            }
        }
        met += usize::from(h <= 25.0 && s <= 1.5);
        cells.push(format!("{h:.1} / {s:.2}"));
        json.push(format!(
            "{{\"situation\":\"{}\",\"heading_rmse_deg\":{h:.3},\"speed_rmse_mps\":{s:.3},\"speed_bias_mps\":{bias:.3}}}",
            situation.name
        ));
        eprintln!("{}: speed bias {bias:+.2} m/s", situation.name);
    }
    let label = get("label").unwrap_or("-");
    println!(
        "| {label} | {} | {met} | {trained_secs:.1} s |",
        cells.join(" | ")
    );
    if let Some(path) = get("json") {
        std::fs::write(
            path,
            format!(
                "{{\"label\":\"{label}\",\"met\":{met},\"situations\":[{}]}}\n",
                json.join(",")
            ),
        )?;
    }
    Ok(())
}
