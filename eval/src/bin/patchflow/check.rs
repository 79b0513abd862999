//! `patchflow check`: trained models read on targets of one's own scenarios over several world
//! draws, each reading held to the bar (heading RMSE under 25°, speed RMSE under 1.5 m/s).

use std::path::PathBuf;

use anyhow::Context;
use patchflow_eval::{CheckModel, CheckPlan, parse_worlds, run_checks};
use patchflow_learn::MotionEstimator;
use patchflow_sim::{Realism, ScenarioSource};

use crate::choices::RealismChoice;
use crate::output_guard::{Input, OutputKind, check_output};

/// Arguments of `patchflow check`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scenario files (or embedded scenarios' names), each marking one actor `target = true`.
    #[arg(required = true)]
    pub scenarios: Vec<PathBuf>,
    /// Trained model file (from `patchflow train` or `bench`'s `models/`); repeat to read several,
    /// e.g. the three training seeds' `spgp-het.json`, `spgp-het-seed8.json`, `spgp-het-seed9.json`.
    #[arg(long, required = true)]
    pub model: Vec<PathBuf>,
    /// Report folder to write: `checks.md`, `checks.json`, `checks.csv` (and each world's data
    /// under `data/` while it is read).
    #[arg(long)]
    pub out: PathBuf,
    /// World seeds, each check simulated once per seed: a range `7-14`, a list `7,9,12` or `7`.
    #[arg(long, default_value = "7-14")]
    pub worlds: String,
    /// Realism rung for every check (default: each file's own, `urban` if it names none).
    #[arg(long, value_enum)]
    pub realism: Option<RealismChoice>,
    /// Keep each world's dataset under `OUT/data/world-W` (about 6 GB per world for the shipped
    /// checks; without it one world is on disk at a time).
    #[arg(long)]
    pub keep_data: bool,
}

/// Runs `patchflow check`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let mut inputs: Vec<Input<'_>> = args
        .model
        .iter()
        .map(|m| Input::new("--model", m))
        .collect();
    inputs.extend(
        args.scenarios
            .iter()
            .filter(|p| p.exists())
            .map(|p| Input::new("scenario", p)),
    );
    check_output(&args.out, OutputKind::Folder, &inputs)?;
    let scenarios = args
        .scenarios
        .iter()
        .map(|path| ScenarioSource::from_argument(path))
        .collect::<Result<Vec<_>, _>>()?;
    let plan = CheckPlan {
        scenarios,
        worlds: parse_worlds(&args.worlds)?,
        realism: args.realism.map(Realism::from),
        keep_data: args.keep_data,
    };
    // The scenarios first: a check that cannot run is named before any model is loaded.
    plan.check_names()?;
    let models = args
        .model
        .iter()
        .map(|path| {
            let estimator = MotionEstimator::load(path)
                .with_context(|| format!("loading model {}", path.display()))?;
            Ok(CheckModel {
                name: path.display().to_string(),
                estimator,
            })
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let report = run_checks(&plan, &models, &args.out)?;
    let files = report.write(&args.out)?;
    for tally in &report.methods {
        println!(
            "{}: {} of {} readings within the bar",
            tally.method, tally.within, tally.readings
        );
    }
    println!("wrote {}", files.markdown.display());
    Ok(())
}
