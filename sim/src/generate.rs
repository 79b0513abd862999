//! Dataset generation (`patchflow generate`): scenarios → sequences on disk, resumable, shardable.

use std::path::{Path, PathBuf};

use patchflow_dataset::{Manifest, SequenceWriter};

use crate::error::{Result, SimError};
use crate::scenario::{EMBEDDED_SCENARIOS, Realism, Scenario};
use crate::simulation::Simulation;

/// Where a scenario comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ScenarioSource {
    /// A TOML file on disk.
    File(PathBuf),
    /// An embedded scenario: name and text.
    Embedded(&'static str, &'static str),
}

impl ScenarioSource {
    /// Every embedded scenario.
    pub fn all_embedded() -> Vec<Self> {
        EMBEDDED_SCENARIOS
            .iter()
            .map(|&(name, text)| Self::Embedded(name, text))
            .collect()
    }

    /// Loads and validates it.
    pub fn load(&self) -> Result<Scenario> {
        self.load_at_rung(None)
    }

    /// Loads and validates it with its realism rung replaced by `rung`, if given.
    pub fn load_at_rung(&self, rung: Option<Realism>) -> Result<Scenario> {
        match self {
            Self::File(path) => Scenario::from_file_at_rung(path, rung),
            Self::Embedded(name, text) => {
                Scenario::from_toml_at_rung(text, &format!("<embedded {name}.toml>"), name, rung)
            }
        }
    }
}

/// Take every `count`-th unit of work starting at `index` (0-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This worker's index, `0..count`.
    pub index: usize,
    /// Number of workers.
    pub count: usize,
}

impl Shard {
    /// The whole job.
    pub const ALL: Self = Self { index: 0, count: 1 };

    /// Parses `I/N`.
    pub fn parse(text: &str) -> Result<Self> {
        let bad = || {
            SimError::Options(format!(
                "--shard {text:?}: expected I/N with 0 ≤ I < N, e.g. 0/4"
            ))
        };
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let (index, count) = (
            i.trim().parse::<usize>().map_err(|_| bad())?,
            n.trim().parse::<usize>().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// True if unit `i` (in sorted order) belongs to this shard.
    pub fn takes(&self, i: usize) -> bool {
        i % self.count == self.index
    }
}

/// Options of a generation run.
#[derive(Debug, Clone, PartialEq)]
pub struct GenerateOptions {
    /// Dataset folder.
    pub out: PathBuf,
    /// Seed of every random stream.
    pub seed: u64,
    /// Which part of the work to do.
    pub shard: Shard,
    /// Realism rung replacing every scenario's own (`generate --realism NAME`); `None` keeps theirs.
    pub realism: Option<Realism>,
}

/// What a running generation reports, for progress display.
#[derive(Debug, Clone, PartialEq)]
pub enum Progress {
    /// A sequence starts: its name and sweep count.
    SequenceStarted {
        /// Sequence name.
        name: String,
        /// Number of sweeps it has.
        sweeps: u32,
    },
    /// One sweep is on disk (written now or by an earlier run).
    SweepDone {
        /// Sequence name.
        name: String,
        /// Sweep index.
        index: u32,
        /// Points in it (0 if it was skipped as already written).
        points: usize,
    },
    /// A sequence is complete (or was already).
    SequenceDone {
        /// Sequence name.
        name: String,
        /// True if an earlier run had finished it.
        skipped: bool,
    },
}

/// Generates the dataset: validates every scenario first (errors name the file and line), sorts
/// them by name, takes this shard's share, skips finished sequences and finished sweeps of an
/// unfinished one, then rewrites `manifest.json` from the completion markers.
pub fn generate_dataset(
    sources: &[ScenarioSource],
    options: &GenerateOptions,
    progress: &dyn Fn(Progress),
) -> Result<Manifest> {
    let mut scenarios = sources
        .iter()
        .map(|s| s.load_at_rung(options.realism))
        .collect::<Result<Vec<_>>>()?;
    scenarios.sort_by(|a, b| a.name.cmp(&b.name));
    if let Some(w) = scenarios.windows(2).find(|w| w[0].name == w[1].name) {
        return Err(SimError::Options(format!(
            "two scenarios are both named {:?}; sequence names must be unique",
            w[0].name
        )));
    }
    std::fs::create_dir_all(&options.out).map_err(|source| SimError::Io {
        path: options.out.clone(),
        source,
    })?;
    for (i, scenario) in scenarios.iter().enumerate() {
        if options.shard.takes(i) {
            generate_sequence(scenario, &options.out, options.seed, progress)?;
        }
    }
    let manifest = Manifest::scan(&options.out)?;
    manifest.write(&options.out)?;
    Ok(manifest)
}

/// Generates (or completes) one sequence.
pub fn generate_sequence(
    scenario: &Scenario,
    root: &Path,
    seed: u64,
    progress: &dyn Fn(Progress),
) -> Result<()> {
    let name = scenario.name.clone();
    if SequenceWriter::is_complete(root, &name) {
        progress(Progress::SequenceDone {
            name,
            skipped: true,
        });
        return Ok(());
    }
    progress(Progress::SequenceStarted {
        name: name.clone(),
        sweeps: scenario.sweeps,
    });
    let writer = SequenceWriter::open(root, &name)?;
    let resolved = scenario.to_toml();
    writer.write_scenario(&format!(
        "# resolved scenario {name}, generated with seed {seed}\n{resolved}"
    ))?;
    let mut sim = Simulation::new(scenario, seed)?;
    for index in 0..scenario.sweeps {
        let mut points = 0;
        if !writer.has_sweep(index) {
            let sweep = sim.sweep(index);
            points = sweep.len();
            writer.write_sweep(&sweep)?;
        }
        progress(Progress::SweepDone {
            name: name.clone(),
            index,
            points,
        });
    }
    let poses: Vec<_> = (0..scenario.sweeps)
        .map(|i| sim.world_from_sensor(i))
        .collect();
    let estimated: Vec<_> = (0..scenario.sweeps)
        .map(|i| sim.estimated_world_from_sensor(i))
        .collect();
    writer.write_estimated_poses(&estimated)?;
    let stamps: Vec<f64> = (0..scenario.sweeps)
        .map(|i| sim.stamp_secs(i) - scenario.start_secs)
        .collect();
    let generator = concat!("patchflow-sim ", env!("CARGO_PKG_VERSION"));
    writer.finish(
        &name,
        seed,
        scenario.lidar.rate_hz,
        &poses,
        &stamps,
        generator,
    )?;
    progress(Progress::SequenceDone {
        name,
        skipped: false,
    });
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_parse_and_partition_the_work() {
        let shard = Shard::parse("1/3").unwrap();
        assert_eq!(
            (0..7).filter(|&i| shard.takes(i)).collect::<Vec<_>>(),
            vec![1, 4]
        );
        assert!(Shard::parse("3/3").is_err());
        assert!(Shard::parse("x").is_err());
        assert!(Shard::parse("0/0").is_err());
    }
}
