//! `patchflow study NAME`: one factor varied (realism rung, lidar rate, channels, patch-map cell
//! size, or cell and rate together), everything else fixed and seeded, by the library's study
//! driver ([`patchflow_eval::run_study`]); `--shard I/N` runs every N-th point, `--merge` joins
//! the shards' points into `study.json`.

use std::path::PathBuf;

use patchflow_eval::{BenchPlan, Method, StudyFactor, StudyPlan, merge_study, run_study};
use patchflow_sim::Shard;

use crate::choices::StudyChoice;
use crate::output_guard::{OutputKind, check_output};

/// The methods each finished point prints: the default GP and the two oracle baselines.
const READOUT_METHODS: [Method; 3] = [Method::SpgpHetAll, Method::Kf, Method::Icp];

/// Arguments of `patchflow study`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The study: `realism` (the five situations at each rung, trained on `urban`), `rate`
    /// (5, 10, 20 Hz), `channels` (16, 32, 64, 128), `cell` (patch-map cells of 0.05, 0.10,
    /// 0.20 m; patches of 11 × 11 cells) or `cell-rate` (0.10 m at 10 Hz beside 0.05 m at 20 Hz,
    /// 0.20 m at 10 Hz beside 0.10 m at 20 Hz).
    #[arg(value_enum)]
    pub name: StudyChoice,
    /// Output folder (default `results/study-NAME`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Take every N-th point (in sorted order) starting at I (0-based), as `I/N`; merge afterwards.
    #[arg(long)]
    pub shard: Option<String>,
    /// Seed of generation, sampling and training (default: the benchmark's).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Join the points the shards wrote into `study.json`, `study.md` and plots (runs nothing).
    #[arg(long)]
    pub merge: bool,
    /// The smaller plan of `bench --quick` (SPGP-HET only, the last third of each training
    /// track's sweeps, fewer samples, pseudo-inputs and iterations) at every point.
    #[arg(long)]
    pub quick: bool,
}

/// Runs `patchflow study`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let factor = StudyFactor::from(args.name);
    let bench = if args.quick {
        BenchPlan::quick()
    } else {
        BenchPlan::full()
    };
    let mut plan = StudyPlan::from_bench(factor, &bench);
    if let Some(seed) = args.seed {
        plan.seed = seed;
    }
    let out = args
        .out
        .unwrap_or_else(|| PathBuf::from(format!("results/study-{}", factor.name())));
    check_output(&out, OutputKind::Folder, &[])?;
    let files = if args.merge {
        Some(merge_study(&plan, &out)?)
    } else {
        let shard = match &args.shard {
            Some(text) => Shard::parse(text)?,
            None => Shard::ALL,
        };
        run_study(&plan, &out, shard, &|point| {
            let line: Vec<String> = READOUT_METHODS
                .iter()
                .filter_map(|m| {
                    let s = point.pooled.get(m.name())?;
                    Some(format!(
                        "{m} {}° / {} m/s",
                        s.heading_rmse_deg.map_or("-".into(), |v| format!("{v:.1}")),
                        s.speed_rmse_mps.map_or("-".into(), |v| format!("{v:.2}"))
                    ))
                })
                .collect();
            println!("{:>10}: {}", point.label, line.join(", "));
        })?
    };
    match files {
        Some(files) => println!("study: {}", files.study_md.display()),
        None => println!(
            "points written to {}; run `patchflow study {} --merge --out {}` after every shard",
            out.join("points").display(),
            factor.name(),
            out.display()
        ),
    }
    Ok(())
}
