//! `patchflow generate`: simulate scenario files and write a dataset (SPEC §4).

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Mutex;

use anyhow::Context;
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use patchflow_dataset::Manifest;
use patchflow_sim::{GenerateOptions, Progress, Realism, ScenarioSource, Shard, generate_dataset};

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
    /// Realism rung for every scenario (`ideal`, `urban`, `harsh`), replacing the one each file
    /// names (default: the file's own, `urban` if it names none); knobs a file sets alone still apply.
    #[arg(long, value_parser = parse_realism)]
    pub realism: Option<Realism>,
    /// Delete and regenerate the sequences this run covers (without it, a sequence written by
    /// another seed, scenario text or version is refused, never mixed in).
    #[arg(long)]
    pub overwrite: bool,
}

fn parse_realism(name: &str) -> Result<Realism, String> {
    Realism::parse(name).ok_or_else(|| {
        format!("unknown realism rung {name:?}: expected one of ideal, urban, harsh")
    })
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
        realism: args.realism,
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

/// Generates with one progress bar per sequence; `bench` uses it too.
pub fn generate_with_progress(
    sources: &[ScenarioSource],
    options: &GenerateOptions,
) -> anyhow::Result<Manifest> {
    let bars = MultiProgress::new();
    let style = ProgressStyle::with_template(
        "{prefix:>12} [{bar:40}] {pos}/{len} sweeps {elapsed} (eta {eta}) {msg}",
    )
    .unwrap_or_else(|_| ProgressStyle::default_bar())
    .progress_chars("=> ");
    let open: Mutex<HashMap<String, ProgressBar>> = Mutex::new(HashMap::new());
    let on_progress = |event: Progress| {
        let Ok(mut open) = open.lock() else { return };
        match event {
            Progress::Waiting { name } => {
                let _ = bars.println(format!(
                    "{name:>12} is being written by another run; waiting for it"
                ));
            }
            Progress::SequenceStarted { name, sweeps } => {
                let bar = bars.add(
                    ProgressBar::new(u64::from(sweeps))
                        .with_style(style.clone())
                        .with_prefix(name.clone()),
                );
                open.insert(name, bar);
            }
            Progress::SweepDone { name, points, .. } => {
                if let Some(bar) = open.get(&name) {
                    bar.inc(1);
                    if points > 0 {
                        bar.set_message(format!("{points} points"));
                    }
                }
            }
            Progress::SequenceDone { name, skipped } => match open.remove(&name) {
                Some(bar) => bar.finish_with_message("done"),
                None if skipped => {
                    let _ = bars.println(format!("{name:>12} already complete, skipped"));
                }
                None => {}
            },
        }
    };
    generate_dataset(sources, options, &on_progress)
        .with_context(|| format!("generating into {}", options.out.display()))
}
