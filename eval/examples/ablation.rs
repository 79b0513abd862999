//! The estimator's ablation (docs/estimator.md): every variant of the training options trained on
//! the same sample draws for each training seed, and all scored in one pass over the situations'
//! maps (`evaluate_targets`, as `bench` scores its further seeds): SPGP-HET-ALL heading RMSE (°)
//! and speed RMSE (m/s) per situation, mean ± std over the seeds, as a Markdown table; every
//! figure also as JSON with `json=PATH`.
//!
//! `cargo run --release -p patchflow-eval --example ablation -- situations=DIR[,DIR...] train=DIR
//! [seeds=7,8,9] [samples=1200] [pseudo=60] [iters=150] [variants=default,thesis,...]
//! [json=PATH]`
//!
//! DIRs are `bench --quick --keep-data`'s `data/situations` and `data/train`; the default sizes are
//! `bench --quick`'s. Variants: `default`, `thesis` (its own draws, no speed jitter), `zero-mean`,
//! `no-mirror` and `mirror` (without or with each sample's mirror image), `side` (no mirror
//! images, the draw balanced by side of the line of sight), `mirror-only` (each sample's mirror
//! image instead of the sample), `pls<K>` (e.g. `pls20`),
//! `mlhgp`, joined with `+` (`pls20+mlhgp`), and `x<F>` to train on F times the samples
//! (`pls20+x3`; each sample count is its own importance draw, as `bench` draws it: a set's
//! samples are in dataset order, so the first N of a larger draw would hold only the first
//! tracks' samples); `top<CM>` and `bot<CM>` move the height slice's top and
//! bottom edge to CM centimetres above the ground (`top85`), `cell<CM>` sets the cell of the maps
//! the patches sample to CM centimetres (`cell10`: the thesis' 1.1 m patches on the maps
//! themselves; `cell20`, the default: 2.2 m patches on maps of their own) and `maps<CM>` the
//! cell of the maps themselves (the clusters' cells), each its own draw; `jitter<DEG>` sets the
//! training speed patches' heading error (`FeatureParams::speed_jitter_deg`; `jitter0` aligns them
//! to the true heading, the default is 25°).

use std::collections::BTreeMap;
use std::path::Path;

use patchflow_dataset::Dataset;
use patchflow_eval::{Method, score_method, stages::evaluate_targets};
use patchflow_learn::{EstimatorParams, FeatureKind, FeatureParams, MotionEstimator, SampleSet};
use rayon::prelude::*;

type Failure = Box<dyn std::error::Error>;

/// A variant's parameters (sizes from the command line), its sample factor, whether it is the
/// thesis preset and what is done to its draw.
type Variant = (EstimatorParams, usize, bool, DrawUse);

/// What a variant trains on of its draw.
#[derive(Clone, Copy, PartialEq)]
enum DrawUse {
    /// The samples as drawn.
    AsDrawn,
    /// Half of a draw of twice the samples, balanced by side (`SampleSet::balanced_by_side`).
    BalancedBySide,
    /// The mirror image of every sample instead of the sample.
    MirrorImagesOnly,
}

fn variant(name: &str, base: &EstimatorParams) -> Result<Variant, Failure> {
    let mut p = base.clone();
    let (mut factor, mut thesis, mut draw) = (1, false, DrawUse::AsDrawn);
    for part in name.split('+') {
        match part {
            "default" => {}
            "thesis" => {
                thesis = true;
                p = EstimatorParams {
                    samples: p.samples,
                    pseudo_inputs: p.pseudo_inputs,
                    max_iters: p.max_iters,
                    ..EstimatorParams::thesis()
                };
            }
            "zero-mean" => p.zero_mean = true,
            "centred" => p.zero_mean = false,
            "mlhgp" => p.most_likely_noise = true,
            "no-mlhgp" => p.most_likely_noise = false,
            "mirror" => p.mirror_images = true,
            "no-mirror" => p.mirror_images = false,
            "side" => {
                draw = DrawUse::BalancedBySide;
                p.mirror_images = false;
            }
            "mirror-only" => {
                draw = DrawUse::MirrorImagesOnly;
                p.mirror_images = false;
            }
            other if other.starts_with("top") => {
                p.features.slice_max_m = other[3..].parse::<f64>()? / 100.0;
            }
            other if other.starts_with("bot") => {
                p.features.slice_min_m = other[3..].parse::<f64>()? / 100.0;
            }
            other if other.starts_with("cell") => {
                p.features.patch_cell_m = other[4..].parse::<f64>()? / 100.0;
            }
            other if other.starts_with("maps") => {
                p.features.cell_m = other[4..].parse::<f64>()? / 100.0;
            }
            other if other.starts_with("pls") => p.projection_dims = other[3..].parse()?,
            other if other.starts_with("jitter") => {
                p.features.speed_jitter_deg = other[6..].parse()?;
            }
            other if other.starts_with('x') => factor = other[1..].parse()?,
            other if other.starts_with('m') => p.pseudo_inputs = other[1..].parse()?,
            other => return Err(format!("unknown variant part '{other}'").into()),
        }
    }
    p.samples *= factor;
    Ok((p, factor, thesis, draw))
}

fn main() -> Result<(), Failure> {
    let args: BTreeMap<String, String> = std::env::args()
        .skip(1)
        .filter_map(|a| a.split_once('=').map(|(k, v)| (k.to_owned(), v.to_owned())))
        .collect();
    let get = |k: &str| args.get(k).map(String::as_str);
    let situation_dirs: Vec<&str> = get("situations")
        .ok_or("situations=DIR[,DIR...]")?
        .split(',')
        .collect();
    let train = Dataset::open(Path::new(get("train").ok_or("train=DIR")?))?;
    let seeds: Vec<u64> = get("seeds")
        .unwrap_or("7,8,9")
        .split(',')
        .map(str::parse)
        .collect::<Result<_, _>>()?;
    let base = EstimatorParams {
        samples: get("samples").map_or(Ok(1200), str::parse)?,
        pseudo_inputs: get("pseudo").map_or(Ok(60), str::parse)?,
        max_iters: get("iters").map_or(Ok(150), str::parse)?,
        ..EstimatorParams::default()
    };
    let names: Vec<String> = get("variants")
        .unwrap_or("no-mlhgp,default,thesis")
        .split(',')
        .map(str::to_owned)
        .collect();
    let variants: Vec<Variant> = names
        .iter()
        .map(|n| variant(n, &base))
        .collect::<Result<_, _>>()?;
    // One pass over the training maps per sample count and feature setting, every seed at once.
    let draws: Vec<(f64, u64)> = seeds.iter().map(|&s| (0.5, s)).collect();
    let clock = std::time::Instant::now();
    let mut keys: Vec<(FeatureParams, usize)> = Vec::new();
    // A side-balanced variant keeps half of twice its samples (SampleSet::balanced_by_side).
    let draw_size = |p: &EstimatorParams, draw: DrawUse| {
        p.samples
            * if draw == DrawUse::BalancedBySide {
                2
            } else {
                1
            }
    };
    for (p, _, _, draw) in &variants {
        let key = (p.features.clone(), draw_size(p, *draw));
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    let mut drawn: Vec<Vec<SampleSet>> = Vec::with_capacity(keys.len());
    for (features, samples) in &keys {
        drawn.push(SampleSet::collect_draws(
            &train,
            features,
            &draws,
            FeatureKind::Patch,
            *samples,
            &|_, _| {},
        )?);
    }
    eprintln!("samples drawn in {:.1} s", clock.elapsed().as_secs_f64());
    let jobs: Vec<(usize, usize)> = (0..variants.len())
        .flat_map(|v| (0..seeds.len()).map(move |s| (v, s)))
        .collect();
    let clock = std::time::Instant::now();
    let models = jobs
        .par_iter()
        .map(|&(v, s)| {
            let (params, _, _, draw) = &variants[v];
            let key = (params.features.clone(), draw_size(params, *draw));
            let set = keys
                .iter()
                .position(|k| *k == key)
                .and_then(|k| drawn[k].get(s))
                .ok_or_else(|| "no sample set drawn for a variant".to_owned())?;
            let params = EstimatorParams {
                seed: seeds[s],
                ..params.clone()
            };
            let fit = |set: &SampleSet| MotionEstimator::fit_samples(set, &params);
            match draw {
                DrawUse::AsDrawn => fit(set),
                DrawUse::BalancedBySide => {
                    let balanced = set.balanced_by_side(params.samples, seeds[s]);
                    eprintln!("{}, seed {}: exact {}", names[v], seeds[s], balanced.exact);
                    fit(&balanced.set)
                }
                DrawUse::MirrorImagesOnly => fit(&set.mirror_images()),
            }
            .map_err(|e| e.to_string())
        })
        .collect::<Result<Vec<_>, String>>()?;
    eprintln!(
        "{} models fitted in {:.1} s",
        models.len(),
        clock.elapsed().as_secs_f64()
    );
    let runs: Vec<Vec<MotionEstimator>> = models.into_iter().map(|m| vec![m]).collect();
    let mut json = Vec::new();
    for dir in &situation_dirs {
        let situations = Dataset::open(Path::new(dir))?;
        println!("\nsituations: {dir}\n");
        let clock = std::time::Instant::now();
        let results = evaluate_targets(&situations, &runs)?;
        eprintln!("scored in {:.1} s", clock.elapsed().as_secs_f64());
        // figures[variant][situation] = per-seed (heading, speed)
        let mut figures: Vec<BTreeMap<String, Vec<(f64, f64)>>> =
            vec![BTreeMap::new(); variants.len()];
        for (&(v, _), run) in jobs.iter().zip(&results) {
            for situation in run {
                let estimates = [Method::SpgpHetAll, Method::SpgpHetAllThesis]
                    .iter()
                    .find_map(|m| situation.methods.get(m))
                    .ok_or("no SPGP-HET-ALL estimates")?;
                let m = score_method(&situation.truth, estimates)?;
                figures[v].entry(situation.name.clone()).or_default().push((
                    m.heading_rmse_deg.unwrap_or(f64::NAN),
                    m.speed_rmse_mps.unwrap_or(f64::NAN),
                ));
            }
        }
        let stats = |xs: &[f64]| {
            let mean = xs.iter().sum::<f64>() / xs.len() as f64;
            let var =
                xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (xs.len().max(2) - 1) as f64;
            (mean, var.sqrt())
        };
        let situation_names: Vec<String> = figures
            .first()
            .map_or(Vec::new(), |f| f.keys().cloned().collect());
        println!("| variant | {} | within bar |", situation_names.join(" | "));
        println!("|---|{}---|", "---|".repeat(situation_names.len()));
        for (name, per) in names.iter().zip(&figures) {
            let mut cells = Vec::new();
            let mut met = 0;
            for s in &situation_names {
                let values = &per[s];
                let (h, hs) = stats(&values.iter().map(|v| v.0).collect::<Vec<_>>());
                let (v, vs) = stats(&values.iter().map(|v| v.1).collect::<Vec<_>>());
                if h <= 25.0 && v <= 1.5 {
                    met += 1;
                }
                cells.push(format!("{h:.1} ± {hs:.1} / {v:.2} ± {vs:.2}"));
                json.push(
                    serde_json::json!({"variant": name, "situations": dir, "situation": s, "seeds": seeds,
                    "heading_rmse_deg": values.iter().map(|v| v.0).collect::<Vec<_>>(),
                    "speed_rmse_mps": values.iter().map(|v| v.1).collect::<Vec<_>>()}),
                );
            }
            println!("| {name} | {} | {met} |", cells.join(" | "));
        }
    }
    if let Some(path) = get("json") {
        std::fs::write(path, serde_json::to_string_pretty(&json)?)?;
    }
    Ok(())
}
