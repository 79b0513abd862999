//! `patchflow show`: a PNG of one sweep's reflection and difference maps with clusters and true boxes.

use std::path::PathBuf;

use anyhow::Context;
use patchflow_dataset::Dataset;
use patchflow_learn::{FeatureParams, SweepFeatures, write_png};

/// Arguments of `patchflow show`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Dataset folder.
    #[arg(long)]
    pub data: PathBuf,
    /// Sequence name (default: the first one).
    #[arg(long)]
    pub sequence: Option<String>,
    /// Sweep index (must be at least 1: the difference needs the previous sweep).
    #[arg(long, default_value_t = 1)]
    pub scan: usize,
    /// PNG file to write.
    #[arg(long)]
    pub out: PathBuf,
}

/// Runs `patchflow show`.
pub fn run(args: Args) -> anyhow::Result<()> {
    if args.scan == 0 {
        anyhow::bail!("--scan must be at least 1: the difference map needs the previous sweep");
    }
    let dataset = Dataset::open(&args.data)?;
    let name = match &args.sequence {
        Some(name) => name.clone(),
        None => dataset
            .sequences()
            .first()
            .map(|s| s.name.clone())
            .with_context(|| format!("{}: no sequence", args.data.display()))?,
    };
    let sequence = dataset.sequence(&name)?;
    if args.scan >= sequence.len() {
        anyhow::bail!(
            "--scan {}: sequence {name} of {} has {} sweeps (0 to {})",
            args.scan,
            args.data.display(),
            sequence.len(),
            sequence.len().saturating_sub(1)
        );
    }
    let prev = sequence.read_sweep(args.scan - 1)?;
    let curr = sequence.read_sweep(args.scan)?;
    let features = SweepFeatures::compute(&prev, &curr, &FeatureParams::default())
        .with_context(|| format!("{}: sweep {}", sequence.dir().display(), args.scan))?;
    write_png(&features, &curr, &args.out)?;
    println!(
        "wrote {} ({} sliced points, {} clusters)",
        args.out.display(),
        features.len(),
        features.clusters().len()
    );
    Ok(())
}
