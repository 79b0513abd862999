//! `patchflow generate`: simulate scenario files and write a dataset (SPEC §4).

use std::path::PathBuf;

use crate::choices::RealismChoice;
use crate::output_guard::{Input, OutputKind, check_output};
use patchflow_eval::stages::generate_with_progress;
use patchflow_sim::{GenerateOptions, Realism, ScenarioSource, Shard, write_kitti_names};

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
    /// Realism rung for every scenario (`ideal`, `urban`, `harsh`), replacing the one each file
    /// names (default: the file's own, `urban` if it names none); knobs a file sets alone still apply.
    #[arg(long, value_enum)]
    pub realism: Option<RealismChoice>,
    /// Delete and regenerate the sequences this run covers (without it, a sequence written by
    /// another seed, scenario text or version is refused, never mixed in).
    #[arg(long)]
    pub overwrite: bool,
    /// Also write `OUT/kitti/`: KITTI odometry's numeric sequence names (`sequences/NN` linked
    /// to the sequence folders, `poses/NN.txt`, `names.txt`) for loaders that take a sequence
    /// number, e.g. `kiss_icp_pipeline --dataloader kitti --sequence 3 OUT/kitti`.
    #[arg(long)]
    pub kitti_names: bool,
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
    let files: Vec<&std::path::PathBuf> = args.scenarios.iter().filter(|p| p.exists()).collect();
    let inputs: Vec<Input<'_>> = files.iter().map(|p| Input::new("scenario", p)).collect();
    check_output(&args.out, OutputKind::Folder, &[])?;
    // What generate writes inside --out; a scenario kept beside them is never touched.
    for (written, kind) in [
        ("sequences", OutputKind::Folder),
        ("manifest.json", OutputKind::File),
        ("kitti", OutputKind::Folder),
    ] {
        check_output(&args.out.join(written), kind, &inputs)?;
    }
    let shard = match &args.shard {
        Some(text) => Shard::parse(text)?,
        None => Shard::ALL,
    };
    let options = GenerateOptions {
        out: args.out.clone(),
        seed: args.seed,
        shard,
        realism: args.realism.map(Realism::from),
        overwrite: args.overwrite,
    };
    let manifest = generate_with_progress(&sources, &options)?;
    if args.kitti_names {
        let names = write_kitti_names(&args.out)?;
        println!(
            "{}: {} sequences numbered 00-{:02} for KITTI loaders (names.txt)",
            args.out.join("kitti").display(),
            names.len(),
            names.len().saturating_sub(1)
        );
    }
    let points: u64 = manifest.sequences.iter().map(|s| s.points).sum();
    println!(
        "{}: {} sequences, {} points (manifest.json rewritten)",
        args.out.display(),
        manifest.sequences.len(),
        points
    );
    Ok(())
}
