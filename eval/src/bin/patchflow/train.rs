//! `patchflow train`: train the motion estimator (two heading GPs and a speed GP) on a dataset.

use std::path::PathBuf;

use anyhow::Context;
use patchflow_dataset::Dataset;
use patchflow_eval::progress::progress_bar;
use patchflow_learn::{EstimatorParams, FeatureParams, MotionEstimator};

use crate::choices::{FeatureChoice, GpChoice, PresetChoice};
use crate::output_guard::{Input, OutputKind, check_output};

/// Arguments of `patchflow train`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Dataset folder.
    #[arg(long)]
    pub data: PathBuf,
    /// Model file to write.
    #[arg(long)]
    pub out: PathBuf,
    /// GP kind: `spgp`, `spgp-het` or `full`.
    #[arg(long, value_enum, default_value_t = GpChoice::SpgpHet)]
    pub gp: GpChoice,
    /// Feature kind: `patch` or `gabor`.
    #[arg(long, value_enum, default_value_t = FeatureChoice::Patch)]
    pub feature: FeatureChoice,
    /// Map prior for unobserved cells.
    #[arg(long, default_value_t = 0.5)]
    pub prior: f64,
    /// Training samples per GP.
    #[arg(long, default_value_t = 1600)]
    pub samples: usize,
    /// Pseudo-inputs per sparse GP.
    #[arg(long, default_value_t = 100)]
    pub pseudo: usize,
    /// Seed of sampling and initialisation.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// `default` or `thesis`: the thesis' protocol exactly (no mirror images, speed patches
    /// aligned to the exact true heading, GPs with a zero mean function; the list of the
    /// default's deviations is `EstimatorParams`' doc and docs/estimator.md).
    #[arg(long, value_enum, default_value_t = PresetChoice::Default)]
    pub preset: PresetChoice,
    /// Same as `--preset thesis` (kept for older scripts).
    #[arg(long, hide = true)]
    pub thesis_training: bool,
    /// Thesis Ch. 6: project the patches to this many PLS directions with k-means
    /// pseudo-inputs (0: the raw patch values, free pseudo-inputs). Default: the preset's.
    #[arg(long)]
    pub projection_dims: Option<usize>,
    /// Thesis Ch. 6: Kersting et al.'s most-likely heteroscedastic noise GP (`true`/`false`).
    /// Default: the preset's.
    #[arg(long)]
    pub most_likely_noise: Option<bool>,
    /// GPs with a zero prior mean (`true`/`false`). Default: the preset's.
    #[arg(long)]
    pub zero_mean: Option<bool>,
}

/// Runs `patchflow train`.
pub fn run(args: Args) -> anyhow::Result<()> {
    check_output(
        &args.out,
        OutputKind::File,
        &[Input::new("--data", &args.data)],
    )?;
    let base = if args.thesis_training {
        EstimatorParams::thesis()
    } else {
        EstimatorParams::from(args.preset)
    };
    let base = EstimatorParams {
        projection_dims: args.projection_dims.unwrap_or(base.projection_dims),
        most_likely_noise: args.most_likely_noise.unwrap_or(base.most_likely_noise),
        zero_mean: args.zero_mean.unwrap_or(base.zero_mean),
        ..base
    };
    let params = EstimatorParams {
        gp: args.gp.into(),
        feature: args.feature.into(),
        features: FeatureParams {
            prior: args.prior,
            ..base.features.clone()
        },
        samples: args.samples,
        pseudo_inputs: args.pseudo,
        seed: args.seed,
        ..base
    };
    let dataset = Dataset::open(&args.data)?;
    let estimator = train_with_bar(&dataset, &params)?;
    estimator.save(&args.out)?;
    println!("wrote {}", args.out.display());
    // The moving/static classifier on the same maps, beside the model (issue 27).
    let moving = patchflow_learn::MovingClassifier::train(
        &dataset,
        estimator.feature_params(),
        &patchflow_learn::MovingParams {
            seed: params.seed,
            ..patchflow_learn::MovingParams::default()
        },
    )
    .with_context(|| {
        format!(
            "training the moving classifier on {}",
            dataset.root().display()
        )
    })?;
    let moving_path = args.out.with_file_name(patchflow_learn::MOVING_FILE_NAME);
    moving.save(&moving_path)?;
    println!("wrote {}", moving_path.display());
    print_summary(&estimator);
    Ok(())
}

/// Trains with a progress bar over the sample collection.
pub fn train_with_bar(
    dataset: &Dataset,
    params: &EstimatorParams,
) -> anyhow::Result<MotionEstimator> {
    let bar = progress_bar(0, &format!("samples ({})", params.gp));
    let estimator = MotionEstimator::train_with_progress(dataset, params, &|done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
        if done == total {
            bar.set_message(format!("fitting 3 {} GPs", params.gp));
        }
    })
    .with_context(|| format!("training on {}", dataset.root().display()))?;
    bar.finish_and_clear();
    Ok(estimator)
}

/// One line per GP and a JSON summary as the last line.
pub fn print_summary(estimator: &MotionEstimator) {
    let names = ["sin_rel", "cos_rel", "speed"];
    for (name, gp) in names.iter().zip(estimator.gps()) {
        let r = gp.fit_report();
        println!(
            "{name:>8}: {} n={} d={} m={} evals={} nlml={:.3} {:.1}s ({})",
            gp.kind(),
            r.n,
            r.d,
            r.m,
            r.evals,
            r.nlml,
            r.seconds,
            r.stop
        );
    }
    let t = estimator.training();
    let summary = serde_json::json!({
        "gp": estimator.gp_kind().name(),
        "samples": t.samples,
        "pool": t.pool_size,
        "pseudo": crate::evaluate::pseudo_inputs_used(estimator),
        "pseudo_requested": t.pseudo_inputs,
        "seed": t.seed,
        "seconds": t.seconds,
    });
    println!("{summary}");
}
