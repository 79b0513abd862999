//! `patchflow train`: train the motion estimator (two heading GPs and a speed GP) on a dataset.

use std::path::PathBuf;

use anyhow::Context;
use patchflow_dataset::Dataset;
use patchflow_eval::progress::progress_bar;
use patchflow_learn::{EstimatorParams, FeatureParams, MotionEstimator};

use crate::common::{parse_feature, parse_gp};

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
    #[arg(long, default_value = "spgp-het")]
    pub gp: String,
    /// Feature kind: `patch` or `gabor`.
    #[arg(long, default_value = "patch")]
    pub feature: String,
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
    /// Train on the thesis' training set exactly: no mirror images, speed patches aligned to the
    /// exact true heading (see ARCHITECTURE.md for why the default differs).
    #[arg(long)]
    pub thesis_training: bool,
}

/// Runs `patchflow train`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let base = match args.thesis_training {
        true => EstimatorParams::thesis(),
        false => EstimatorParams::default(),
    };
    let params = EstimatorParams {
        gp: parse_gp(&args.gp)?,
        feature: parse_feature(&args.feature)?,
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
        "pseudo": t.pseudo_inputs,
        "seed": t.seed,
        "seconds": t.seconds,
    });
    println!("{summary}");
}
