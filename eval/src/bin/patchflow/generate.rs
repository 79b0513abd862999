//! `patchflow generate`: simulate scenario files and write a dataset (SPEC §4).

use std::path::PathBuf;

use patchflow_eval::stages::generate_with_progress;
use patchflow_sim::{GenerateOptions, ScenarioSource, Shard};

/// Arguments of `patchflow generate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scenario files, or names of embedded scenarios (e.g. `dgpom_tjunction`); with none, every
    /// embedded scenario of the motion benchmark (situations and training tracks) is run.
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
    /// Delete and regenerate the sequences this run covers (without it, a sequence written by
    /// another seed, scenario text or version is refused, never mixed in).
    #[arg(long)]
    pub overwrite: bool,
}

/// Runs `patchflow generate`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let sources = if args.scenarios.is_empty() {
        ScenarioSource::all_embedded()
    } else {
        args.scenarios
            .iter()
            .map(|path| ScenarioSource::from_argument(path))
            .collect::<Result<Vec<_>, _>>()?
    };
    let shard = match &args.shard {
        Some(text) => Shard::parse(text)?,
        None => Shard::ALL,
    };
    let options = GenerateOptions {
        out: args.out.clone(),
        seed: args.seed,
        shard,
        overwrite: args.overwrite,
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
