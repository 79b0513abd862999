//! Reads a dataset written by [`crate::SequenceWriter`], checking every file against the format.

use std::path::{Path, PathBuf};

use crate::manifest::read_marker;
use crate::pose::parse_kitti_pose;
use crate::record_files::read_lines;
use crate::sweep_integrity::{SweepFiles, check_sweep_digests, read_sweep_files, sweep_path};
use crate::writer::ESTIMATED_POSES;
use crate::{DatasetError, MAX_SWEEPS, Manifest, Pose, Result, SequenceInfo, Sweep};

/// An opened dataset folder.
#[derive(Debug, Clone)]
pub struct Dataset {
    root: PathBuf,
    manifest: Manifest,
}

impl Dataset {
    /// Opens the dataset at `root`. The finished sequences are found from their markers, so a
    /// folder filled by several shards opens whole; a `manifest.json` of another format version,
    /// or one listing a sequence whose marker is gone, is an error (never a silently smaller
    /// dataset).
    pub fn open(root: &Path) -> Result<Self> {
        if !root.is_dir() {
            return Err(DatasetError::Missing {
                path: root.to_owned(),
                what: "dataset folder".into(),
            });
        }
        let listed = match root.join("manifest.json").is_file() {
            true => Some(Manifest::read(root)?),
            false => None,
        };
        let manifest = Manifest::scan(root)?;
        if let Some(listed) = listed {
            check_listed(root, &listed, &manifest)?;
        }
        if manifest.sequences.is_empty() {
            return Err(DatasetError::Missing {
                path: root.join("sequences"),
                what: "finished sequence".into(),
            });
        }
        Ok(Self {
            root: root.to_owned(),
            manifest,
        })
    }

    /// The same dataset with only the sequences whose names `keep` accepts (e.g. the thesis
    /// preset's nine training tracks of a folder that holds more); an error naming the folder if
    /// none is left.
    pub fn restricted_to(&self, keep: &dyn Fn(&str) -> bool) -> Result<Self> {
        let mut manifest = self.manifest.clone();
        manifest.sequences.retain(|s| keep(&s.name));
        if manifest.sequences.is_empty() {
            return Err(DatasetError::Missing {
                path: self.root.join("sequences"),
                what: "sequence of the requested ones".into(),
            });
        }
        Ok(Self {
            root: self.root.clone(),
            manifest,
        })
    }

    /// The dataset folder.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The finished sequences, sorted by name.
    pub fn sequences(&self) -> &[SequenceInfo] {
        &self.manifest.sequences
    }

    /// Opens one sequence by name.
    pub fn sequence(&self, name: &str) -> Result<SequenceReader> {
        SequenceReader::open(&self.root.join("sequences").join(name))
    }
}

/// Every sequence `manifest.json` lists must still have its marker, with the same sweeps and points.
fn check_listed(root: &Path, listed: &Manifest, found: &Manifest) -> Result<()> {
    for entry in &listed.sequences {
        let marker = root
            .join("sequences")
            .join(&entry.name)
            .join("sequence.json");
        let Some(info) = found.sequences.iter().find(|s| s.name == entry.name) else {
            return Err(DatasetError::Missing {
                path: marker,
                what: format!(
                    "completion marker of sequence {:?}, which manifest.json lists (an unfinished or deleted sequence: run generate again to finish it)",
                    entry.name
                ),
            });
        };
        if (info.sweeps, info.points) != (entry.sweeps, entry.points) {
            let reason = format!(
                "says {} sweeps and {} points, manifest.json {} and {}",
                info.sweeps, info.points, entry.sweeps, entry.points
            );
            return Err(DatasetError::corrupt(marker, reason));
        }
    }
    Ok(())
}

/// One sequence of a dataset: poses and stamps up front, sweeps read on demand.
#[derive(Debug, Clone)]
pub struct SequenceReader {
    dir: PathBuf,
    info: SequenceInfo,
    poses: Vec<Pose>,
    /// The ego's own estimates (`poses_estimated.txt`), if the sequence has them.
    estimated_poses: Option<Vec<Pose>>,
    stamps_secs: Vec<f64>,
}

/// Largest time stamp magnitude in `times.txt`, seconds (about 32 years).
const MAX_STAMP_SECS: f64 = 1e9;

impl SequenceReader {
    /// Opens a sequence folder (`DIR/sequences/<name>`), checking the marker against the
    /// folder: one pose and one stamp per sweep, every sweep's files present, and the points
    /// the marker counts.
    pub fn open(dir: &Path) -> Result<Self> {
        let marker = dir.join("sequence.json");
        let info = read_marker(&marker)?;
        if info.sweeps as usize > MAX_SWEEPS {
            let reason = format!(
                "{} sweeps; a sequence holds at most {MAX_SWEEPS}",
                info.sweeps
            );
            return Err(DatasetError::corrupt(&marker, reason));
        }
        let poses_path = dir.join("poses.txt");
        let poses = read_poses(&poses_path)?;
        let times_path = dir.join("times.txt");
        let stamps_secs = read_lines(&times_path)?
            .iter()
            .enumerate()
            .map(|(i, line)| match line.trim().parse::<f64>() {
                Ok(t) if t.abs() <= MAX_STAMP_SECS => Ok(t),
                _ => Err(DatasetError::corrupt(
                    &times_path,
                    format!(
                        "line {}: not a finite number within ±{MAX_STAMP_SECS:e} s",
                        i + 1
                    ),
                )),
            })
            .collect::<Result<Vec<_>>>()?;
        if let Some(i) = stamps_secs.windows(2).position(|w| w[1] <= w[0]) {
            let reason = format!(
                "line {}: time {} s does not follow line {}'s {} s (sweeps are in time order)",
                i + 2,
                stamps_secs[i + 1],
                i + 1,
                stamps_secs[i]
            );
            return Err(DatasetError::corrupt(&times_path, reason));
        }
        for (path, count) in [(&poses_path, poses.len()), (&times_path, stamps_secs.len())] {
            if count != info.sweeps as usize {
                let reason = format!("{count} lines, but the sequence has {} sweeps", info.sweeps);
                return Err(DatasetError::corrupt(path, reason));
            }
        }
        let estimated_poses = read_estimated_poses(dir, info.sweeps as usize)?;
        let reader = Self {
            dir: dir.to_owned(),
            info,
            poses,
            estimated_poses,
            stamps_secs,
        };
        reader.check_point_total(&marker)?;
        Ok(reader)
    }

    /// The marker's point count must be the sum over the sweeps' `velodyne` files.
    fn check_point_total(&self, marker: &Path) -> Result<()> {
        let mut points = 0u64;
        for i in 0..self.len() as u32 {
            let velodyne = sweep_path(&self.dir, "velodyne", i, "bin");
            let bytes = std::fs::metadata(&velodyne)
                .map_err(|e| DatasetError::io(&velodyne, e))?
                .len();
            points += bytes / 16;
        }
        if points != self.info.points {
            let reason = format!(
                "counts {} points, but the velodyne files hold {points}",
                self.info.points
            );
            return Err(DatasetError::corrupt(marker, reason));
        }
        Ok(())
    }

    /// Checks every sweep's files: against the SHA-256 digests the marker records (markers of
    /// older builds record none; then each sweep is read with every check of [`Self::read_sweep`]).
    /// The first damaged file is a [`DatasetError::Corrupt`] naming it.
    pub fn verify_files(&self) -> Result<()> {
        for i in 0..self.len() as u32 {
            match self.info.sweep_sha256.get(i as usize) {
                Some(recorded) => check_sweep_digests(&self.dir, i, recorded)?,
                None => {
                    read_sweep_files(&self.dir, i)?;
                }
            }
        }
        Ok(())
    }

    /// What the marker says about this sequence.
    pub fn info(&self) -> &SequenceInfo {
        &self.info
    }

    /// The sequence folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Number of sweeps.
    pub fn len(&self) -> usize {
        self.poses.len()
    }

    /// True if the sequence has no sweeps.
    pub fn is_empty(&self) -> bool {
        self.poses.is_empty()
    }

    /// `world_from_sensor` of every sweep: the truth (`poses.txt`), for truth labels and metrics.
    pub fn poses(&self) -> &[Pose] {
        &self.poses
    }

    /// The ego's own estimate of `world_from_sensor` for every sweep (`poses_estimated.txt`), for
    /// perception and estimators (what a real car knows); the truth for datasets written before
    /// the estimate existed.
    pub fn estimated_poses(&self) -> &[Pose] {
        self.estimated_poses.as_deref().unwrap_or(&self.poses)
    }

    /// Reference time of every sweep, seconds since the sequence started.
    pub fn stamps_secs(&self) -> &[f64] {
        &self.stamps_secs
    }

    /// The resolved scenario the sequence was generated from.
    pub fn scenario_toml(&self) -> Result<String> {
        let path = self.dir.join("scenario.toml");
        std::fs::read_to_string(&path).map_err(|e| DatasetError::io(&path, e))
    }

    /// Reads sweep `index` and checks it: its files agree on the point count, every value is
    /// finite, and the labels agree with the object truth. Errors name the file.
    pub fn read_sweep(&self, index: usize) -> Result<Sweep> {
        if index >= self.len() {
            let what = format!(
                "sweep {index} (the sequence has {}: 0 to {})",
                self.len(),
                self.len().saturating_sub(1)
            );
            return Err(DatasetError::Missing {
                path: self.dir.clone(),
                what,
            });
        }
        let i = index as u32;
        let SweepFiles {
            velodyne,
            labels,
            flow,
            time,
            rings,
            objects,
        } = read_sweep_files(&self.dir, i)?;
        Ok(Sweep {
            index: i,
            stamp_secs: self.stamps_secs[index],
            world_from_sensor: self.poses[index],
            estimated_world_from_sensor: self.estimated_poses.as_ref().map(|e| e[index]),
            points_in_sensor: velodyne
                .chunks_exact(4)
                .map(|c| [c[0], c[1], c[2]])
                .collect(),
            intensities: velodyne.chunks_exact(4).map(|c| c[3]).collect(),
            labels,
            flow_in_world_mps: flow.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
            time_in_sweep_secs: time,
            rings,
            objects,
        })
    }
}

/// A KITTI pose file, one finite 3 × 4 pose per line (size bounded before reading).
fn read_poses(path: &Path) -> Result<Vec<Pose>> {
    read_lines(path)?
        .iter()
        .enumerate()
        .map(|(i, line)| {
            parse_kitti_pose(line).ok_or_else(|| {
                DatasetError::corrupt(path, format!(
                        "line {}: not a 3 x 4 pose (12 finite numbers, a rotation, a translation within ±{} m)",
                        i + 1,
                        crate::MAX_COORDINATE_M
                    ))
            })
        })
        .collect()
}

/// The estimated poses of a sequence folder, `None` if it has no `poses_estimated.txt`; one line
/// per sweep, like `poses.txt`.
fn read_estimated_poses(dir: &Path, sweeps: usize) -> Result<Option<Vec<Pose>>> {
    let path = dir.join(ESTIMATED_POSES);
    if !path.is_file() {
        return Ok(None);
    }
    let poses = read_poses(&path)?;
    if poses.len() != sweeps {
        let reason = format!(
            "{} lines, but the sequence has {sweeps} sweeps",
            poses.len()
        );
        return Err(DatasetError::corrupt(&path, reason));
    }
    Ok(Some(poses))
}

#[cfg(test)]
#[path = "reader_tests.rs"]
pub(crate) mod tests;

#[cfg(test)]
#[path = "reader_estimate_tests.rs"]
mod estimate_tests;
