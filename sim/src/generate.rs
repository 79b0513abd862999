//! Dataset generation (`patchflow generate`): scenarios → sequences on disk, resumable, shardable.

use std::path::{Path, PathBuf};

use patchflow_dataset::{
    FolderLock, Manifest, SequenceReader, SequenceWriter, Sweep, remove_written_files,
};

use crate::disk_space::{bytes_under, check_disk_space, free_bytes};
use crate::error::{Result, SimError};
use crate::memory_budget::{check_memory, memory_budget};
use crate::output_folder::{check_manifest_is_ours, check_sequence_folder};
use crate::provenance::{Provenance, provenance};
use crate::scenario::{Realism, Scenario, WorkEstimate};
use crate::scenario_source::ScenarioSource;
use crate::sequence_queue::{generate_each, sequences_at_once};
pub use crate::shard::Shard;
use crate::simulation::Simulation;

/// Program and version recorded in every marker; a sequence written by another is not resumed.
const GENERATOR: &str = concat!("patchflow-sim ", env!("CARGO_PKG_VERSION"));

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
    /// Delete and regenerate the sequences this run covers, instead of refusing to touch those
    /// another request (another seed, scenario text or version) wrote.
    pub overwrite: bool,
}

/// What a running generation reports, for progress display.
#[derive(Debug, Clone, PartialEq)]
pub enum Progress {
    /// Another run is writing this sequence; this one waits for it to finish.
    Waiting {
        /// Sequence name.
        name: String,
    },
    /// Before any work: what a sequence of this shard implies (reported for every one, finished
    /// or not, once every check passed).
    Estimate {
        /// Sequence name.
        name: String,
        /// Rays, actors, world and bytes on disk.
        estimate: WorkEstimate,
    },
    /// The sequence's world (ground, streets, pieces, actors' bodies) is being built: with a
    /// large world or many actors this takes seconds to minutes before the first sweep.
    WorldBuilding {
        /// Sequence name.
        name: String,
        /// True when the estimate says it may take more than a few seconds.
        long: bool,
    },
    /// The world is built.
    WorldBuilt {
        /// Sequence name.
        name: String,
        /// Wall time it took, seconds.
        secs: f64,
    },
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
    /// A sweep an earlier run left is damaged: its files were removed and it is written again.
    SweepDamaged {
        /// Sequence name.
        name: String,
        /// Sweep index.
        index: u32,
        /// What is wrong, naming the file.
        reason: String,
    },
    /// A sequence is complete (or was already).
    SequenceDone {
        /// Sequence name.
        name: String,
        /// True if an earlier run had finished it.
        skipped: bool,
    },
}

/// Generates the dataset: validates every scenario first (errors name the file and line), checks
/// that a sweep fits in the machine's memory and that what this shard would write fits on the
/// disk (reporting each sequence's [`WorkEstimate`]), sorts them by name, takes this shard's share,
/// skips finished sequences and finished sweeps of an unfinished one (of the same request;
/// another request's sequence is an error unless `overwrite`), then rewrites `manifest.json`
/// from the completion markers.
pub fn generate_dataset(
    sources: &[ScenarioSource],
    options: &GenerateOptions,
    progress: &(dyn Fn(Progress) + Sync),
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
    for scenario in &scenarios {
        check_memory(scenario)?;
    }
    check_manifest_is_ours(&options.out, options.overwrite)?;
    for scenario in &scenarios {
        check_sequence_folder(&options.out, &scenario.name)?;
    }
    // The work up front: what this shard's sequences would still write must fit on the disk.
    let ours: Vec<(&Scenario, WorkEstimate)> = scenarios
        .iter()
        .enumerate()
        .filter(|(i, _)| options.shard.takes(*i))
        .map(|(_, s)| (s, WorkEstimate::of(s)))
        .collect();
    let to_write: u64 = ours
        .iter()
        .map(|(s, e)| {
            let written = bytes_under(&options.out.join("sequences").join(&s.name));
            e.disk_bytes.saturating_sub(written)
        })
        .fold(0, u64::saturating_add);
    check_disk_space(&options.out, to_write, free_bytes(&options.out))?;
    for (scenario, estimate) in &ours {
        progress(Progress::Estimate {
            name: scenario.name.clone(),
            estimate: *estimate,
        });
    }
    std::fs::create_dir_all(&options.out).map_err(|source| SimError::Io {
        path: options.out.clone(),
        source,
    })?;
    // Two sequences at once where memory allows (`sequence_queue.rs`): the same files.
    let ours: Vec<&Scenario> = ours.into_iter().map(|(s, _)| s).collect();
    let at_once = sequences_at_once(&ours, memory_budget());
    generate_each(&ours, at_once, &|scenario| {
        generate_sequence(
            scenario,
            &options.out,
            options.seed,
            options.overwrite,
            progress,
        )
    })?;
    // Shards finishing at once rewrite the manifest one at a time.
    let _lock = FolderLock::acquire(&options.out, &|| {})?;
    let manifest = Manifest::scan(&options.out)?;
    manifest.write(&options.out)?;
    Ok(manifest)
}

/// Generates (or completes) one sequence, holding its folder's lock: a finished sequence of the
/// same request is skipped, an unfinished one resumed; one of another request is an error naming
/// the difference, or with `overwrite` deleted and generated anew. A request is the resolved
/// scenario text plus the geometry of every mesh file it names (an edited mesh is another request).
pub fn generate_sequence(
    scenario: &Scenario,
    root: &Path,
    seed: u64,
    overwrite: bool,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<()> {
    let name = scenario.name.clone();
    check_sequence_folder(root, &name)?;
    let dir = root.join("sequences").join(&name);
    let on_wait = || progress(Progress::Waiting { name: name.clone() });
    let lock = FolderLock::acquire(&dir, &on_wait)?;
    let text = format!(
        "# resolved scenario {name}, generated with seed {seed}\n{}{}",
        scenario.to_toml(),
        mesh_digests(scenario)
    );
    match (provenance(&dir, &text, seed, GENERATOR), overwrite) {
        (Provenance::Foreign(reason), _) => {
            return Err(SimError::Options(format!(
                "{}: refusing to touch sequence {name:?}: {reason}; move those files away or write to another folder",
                dir.display()
            )));
        }
        (_, true) => {
            // Only what a generate run wrote goes; a user's own files stay.
            remove_written_files(&dir)?;
        }
        (Provenance::Same { finished: true }, false) => {
            verify_finished(&dir, &name)?;
            progress(Progress::SequenceDone {
                name,
                skipped: true,
            });
            return Ok(());
        }
        (Provenance::Fresh | Provenance::Same { finished: false }, false) => {}
        (Provenance::Different(reason), false) => {
            return Err(SimError::Options(format!(
                "{}: refusing to mix this run into sequence {name:?}: {reason}; pass --overwrite to regenerate it, or write to another folder",
                dir.display()
            )));
        }
    }
    progress(Progress::SequenceStarted {
        name: name.clone(),
        sweeps: scenario.sweeps,
    });
    let writer = SequenceWriter::open(root, &name)?;
    writer.write_scenario(&text)?;
    progress(Progress::WorldBuilding {
        name: name.clone(),
        long: WorkEstimate::of(scenario).world_build_is_long(),
    });
    let building = std::time::Instant::now();
    let mut sim = Simulation::new(scenario, seed)?;
    progress(Progress::WorldBuilt {
        name: name.clone(),
        secs: building.elapsed().as_secs_f64(),
    });
    writer.write_static_obstacles(&sim.scene().static_obstacles())?;
    writer.write_sensor(&crate::lidar::sensor_info(&scenario.lidar))?;
    // Sweep k is written on a thread of its own while sweep k + 1 is cast: the files go out in
    // the same order with the same bytes, and the cast no longer waits for the disk.
    std::thread::scope(|scope| -> Result<()> {
        let (to_writer, sweeps) = std::sync::mpsc::sync_channel::<Sweep>(1);
        let writing = scope.spawn(|| -> Result<()> {
            for sweep in sweeps {
                writer.write_sweep(&sweep)?;
            }
            Ok(())
        });
        for index in 0..scenario.sweeps {
            let mut points = 0;
            let (sound, damage) = writer.has_sound_sweep(index)?;
            if let Some(damage) = damage {
                progress(Progress::SweepDamaged {
                    name: name.clone(),
                    index,
                    reason: damage.to_string(),
                });
            }
            if !sound {
                let sweep = sim.sweep(index);
                if sweep.is_empty() {
                    return Err(SimError::Options(format!(
                        "{}: sweep {index} has no points: the lidar hit nothing (is the ego off the ground, or the sensor inside a structure?)",
                        dir.display()
                    )));
                }
                points = sweep.len();
                if to_writer.send(sweep).is_err() {
                    break; // the writer stopped on an error, which its join returns
                }
            }
            progress(Progress::SweepDone {
                name: name.clone(),
                index,
                points,
            });
        }
        drop(to_writer);
        writing.join().map_err(|_| {
            SimError::Options(format!("{}: the sweep writer panicked", dir.display()))
        })?
    })?;
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
    writer.finish(
        &name,
        seed,
        scenario.lidar.rate_hz,
        &poses,
        &stamps,
        GENERATOR,
    )?;
    drop(lock);
    progress(Progress::SequenceDone {
        name,
        skipped: false,
    });
    Ok(())
}

/// Checks a sequence an earlier run finished before calling it complete: every sweep file
/// against the digests its marker records (or read whole, for markers without them).
fn verify_finished(dir: &Path, name: &str) -> Result<()> {
    SequenceReader::open(dir)
        .and_then(|reader| reader.verify_files())
        .map_err(|damage| {
            SimError::Options(format!(
                "sequence {name:?} is marked complete but its data is damaged: {damage}; pass --overwrite to regenerate it"
            ))
        })
}

/// One comment line per actor with a mesh: its file and the SHA-256 of its geometry, so that the
/// sequence's recorded request changes when the file's contents do.
fn mesh_digests(scenario: &Scenario) -> String {
    std::iter::once(&scenario.ego)
        .chain(&scenario.actors)
        .filter_map(|a| Some((a.mesh.as_ref()?, a.mesh_data.as_ref()?)))
        .map(|(file, mesh)| {
            format!(
                "# mesh {file}: geometry sha256 {}\n",
                mesh.geometry_sha256()
            )
        })
        .collect()
}
