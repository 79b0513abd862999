//! `patchflow features`: importance-sampled patch or Gabor features with motion targets, as a CSV.

use std::path::PathBuf;

use crate::choices::{AlignChoice, FeatureChoice, PresetChoice};
use crate::output_guard::{Input, OutputKind, check_output};
use anyhow::Context;
use patchflow_dataset::Dataset;
use patchflow_learn::{Alignment, EstimatorParams, FeatureKind, FeatureParams, SampleSet};

/// Arguments of `patchflow features`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Dataset folder.
    #[arg(long)]
    pub data: PathBuf,
    /// CSV file to write.
    #[arg(long)]
    pub out: PathBuf,
    /// Feature kind: `patch` (242 map values) or `gabor` (16 filter responses).
    #[arg(long, value_enum, default_value_t = FeatureChoice::Patch)]
    pub feature: FeatureChoice,
    /// Map prior for unobserved cells.
    #[arg(long, default_value_t = 0.5)]
    pub prior: f64,
    /// Number of samples drawn by importance sampling.
    #[arg(long, default_value_t = 1600)]
    pub samples: usize,
    /// Seed of the sampling.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Patch alignment: `bearing` (heading features) or `heading` (speed features, along the
    /// true heading plus the preset's training alignment error: 25° for `default`, none for
    /// `thesis`).
    #[arg(long, value_enum, default_value_t = AlignChoice::Bearing)]
    pub align: AlignChoice,
    /// Whose features: `default` (what `train` trains on: the 0.5-0.85 m slice, patches on
    /// 0.20 m maps) or `thesis` (`train --preset thesis`: the 0.5-1.0 m slice, 0.10 m maps).
    #[arg(long, value_enum, default_value_t = PresetChoice::Default)]
    pub preset: PresetChoice,
}

/// Runs `patchflow features`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let kind: FeatureKind = args.feature.into();
    let align: Alignment = args.align.into();
    check_output(
        &args.out,
        OutputKind::File,
        &[Input::new("--data", &args.data)],
    )?;
    // The features the preset's `train` draws, with the prior asked for.
    let preset = EstimatorParams::from(args.preset);
    let params = FeatureParams {
        prior: args.prior,
        ..preset.features
    };
    let dataset = Dataset::open(&args.data)?;
    let bar = indicatif::ProgressBar::new(0).with_message("sweep pairs");
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} {msg} ({elapsed})")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let progress = |done: usize, total: usize| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    };
    let set = SampleSet::collect_with_progress(
        &dataset,
        &params,
        kind,
        args.samples,
        args.seed,
        &progress,
    )
    .with_context(|| format!("collecting samples from {}", args.data.display()))?;
    bar.finish_and_clear();
    set.write_csv(&args.out, align)?;
    println!(
        "wrote {} samples (pool {}) to {}",
        set.samples.len(),
        set.pool_size,
        args.out.display()
    );
    Ok(())
}
