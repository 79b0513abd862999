//! `patchflow generate`: simulate scenario files and write a dataset (SPEC §4).

use std::path::PathBuf;

use patchflow_eval::generate_with_progress;
use patchflow_sim::{GenerateOptions, ScenarioSource, Shard};

/// Arguments of `patchflow generate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scenario files; with none, every embedded scenario is run.
    pub scenarios: Vec<PathBuf>,
    /// Dataset folder to write (created; an interrupted run is resumed).
    #[arg(long)]
    pub out: PathBuf,
    /// Seed of every random stream.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Take every N-th unit of work starting at I (0-based), as `I/N`.
    #[arg(long)]
    pub shard: Option<String>,
}

/// Runs `patchflow generate`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let sources = if args.scenarios.is_empty() {
        ScenarioSource::all_embedded()
    } else {
        args.scenarios
            .iter()
            .cloned()
            .map(ScenarioSource::File)
            .collect()
    };
    let shard = match &args.shard {
        Some(text) => Shard::parse(text)?,
        None => Shard::ALL,
    };
    let options = GenerateOptions {
        out: args.out.clone(),
        seed: args.seed,
        shard,
    };
    let manifest = generate_with_progress(&sources, &options)?;
    let points: u64 = manifest.sequences.iter().map(|s| s.points).sum();
    println!(
        "{}: {} sequences, {} points (manifest.json rewritten)",
        args.out.display(),
        manifest.sequences.len(),
        points
    );
    Ok(())
}
