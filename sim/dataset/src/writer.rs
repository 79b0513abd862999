//! Writes one sequence in the SPEC §4 layout. Every file is written atomically (temporary file,
//! then rename), and a sweep counts as written once its object file, written last, exists; so an
//! interrupted run leaves no half-written file and can be resumed sweep by sweep.

use std::path::{Path, PathBuf};

use crate::atomic_file::write_atomic;
use crate::limits::{MAX_TEXT_BYTES, read_limited};
use crate::manifest::{read_marker, write_json};
use crate::pose::format_kitti_pose;
use crate::sweep_integrity::{
    SWEEP_FILE_KINDS, read_sweep_files, sha256_hex, sweep_digests, sweep_path,
};
use crate::{
    DatasetError, FORMAT_NAME, FORMAT_VERSION, Pose, Result, SensorInfo, SequenceInfo,
    StaticObstacle, Sweep,
};

/// File of the ego's own pose estimate, beside `poses.txt`.
pub(crate) const ESTIMATED_POSES: &str = "poses_estimated.txt";

/// Sub-folders of a sequence, one file per sweep in each.
const SWEEP_FOLDERS: [&str; 5] = ["velodyne", "labels", "flow", "time", "objects"];

/// Static-world truth of a sequence (world-frame boxes), beside the data.
pub(crate) const STATIC_JSON: &str = "static.json";
/// Beam pattern of a sequence's sensor, beside the data.
pub(crate) const SENSOR_JSON: &str = "sensor.json";

/// Nominal KITTI odometry projections; `Tr` is the identity because `poses.txt` already holds
/// lidar poses (`world_from_sensor`), so KITTI tools computing `Tr⁻¹ · P · Tr` get them unchanged.
const CALIB_TXT: &str = "\
P0: 7.188560e+02 0.000000e+00 6.071928e+02 0.000000e+00 0.000000e+00 7.188560e+02 1.852157e+02 0.000000e+00 0.000000e+00 0.000000e+00 1.000000e+00 0.000000e+00
P1: 7.188560e+02 0.000000e+00 6.071928e+02 -3.861448e+02 0.000000e+00 7.188560e+02 1.852157e+02 0.000000e+00 0.000000e+00 0.000000e+00 1.000000e+00 0.000000e+00
P2: 7.188560e+02 0.000000e+00 6.071928e+02 4.538225e+01 0.000000e+00 7.188560e+02 1.852157e+02 -1.130887e-01 0.000000e+00 0.000000e+00 1.000000e+00 3.779761e-03
P3: 7.188560e+02 0.000000e+00 6.071928e+02 -3.372877e+02 0.000000e+00 7.188560e+02 1.852157e+02 2.369057e+00 0.000000e+00 0.000000e+00 1.000000e+00 4.915215e-03
Tr: 1.000000e+00 0.000000e+00 0.000000e+00 0.000000e+00 0.000000e+00 1.000000e+00 0.000000e+00 0.000000e+00 0.000000e+00 0.000000e+00 1.000000e+00 0.000000e+00
";

/// Writer for `DIR/sequences/<name>/`.
#[derive(Debug)]
pub struct SequenceWriter {
    dir: PathBuf,
}

impl SequenceWriter {
    /// Opens (creating if needed) the folder of sequence `name` under dataset `root`.
    /// Sweeps already written by an earlier, interrupted run are kept; see [`Self::has_sweep`].
    pub fn open(root: &Path, name: &str) -> Result<Self> {
        let dir = root.join("sequences").join(name);
        for folder in SWEEP_FOLDERS {
            let path = dir.join(folder);
            std::fs::create_dir_all(&path).map_err(|e| DatasetError::io(&path, e))?;
        }
        Ok(Self { dir })
    }

    /// True if sequence `name` under `root` has been finished (its marker exists and reads).
    pub fn is_complete(root: &Path, name: &str) -> bool {
        read_marker(&root.join("sequences").join(name).join("sequence.json")).is_ok()
    }

    /// The sequence folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// True if sweep `index` was fully written by this or an earlier run.
    pub fn has_sweep(&self, index: u32) -> bool {
        self.sweep_path("objects", index, "json").is_file()
    }

    /// True if sweep `index` was written and its files read back whole (sizes agree, values
    /// finite, labels agree with the object truth). A damaged sweep's files are removed so that
    /// it is written again; the error that condemned it is returned beside `false`.
    pub fn has_sound_sweep(&self, index: u32) -> Result<(bool, Option<DatasetError>)> {
        if !self.has_sweep(index) {
            return Ok((false, None));
        }
        match read_sweep_files(&self.dir, index) {
            Ok(_) => Ok((true, None)),
            Err(DatasetError::Io { path, source })
                if source.kind() != std::io::ErrorKind::NotFound =>
            {
                Err(DatasetError::Io { path, source })
            }
            Err(damage) => {
                // The object file goes first: without it the sweep counts as unwritten.
                for (folder, ext) in SWEEP_FILE_KINDS.iter().rev() {
                    let path = self.sweep_path(folder, index, ext);
                    if path.is_file() {
                        std::fs::remove_file(&path).map_err(|e| DatasetError::io(&path, e))?;
                    }
                }
                Ok((false, Some(damage)))
            }
        }
    }

    /// Writes the resolved scenario beside the data.
    pub fn write_scenario(&self, toml_text: &str) -> Result<()> {
        write_atomic(&self.dir.join("scenario.toml"), toml_text.as_bytes())
    }

    /// Writes `static.json`: every static obstacle of the scene as a world-frame box.
    pub fn write_static_obstacles(&self, obstacles: &[StaticObstacle]) -> Result<()> {
        write_json(&self.dir.join(STATIC_JSON), &obstacles)
    }

    /// Writes `sensor.json`: the beam pattern of the sequence's sensor.
    pub fn write_sensor(&self, sensor: &SensorInfo) -> Result<()> {
        write_json(&self.dir.join(SENSOR_JSON), sensor)
    }

    /// Writes one sweep's five files; the object file goes last and marks the sweep as done.
    pub fn write_sweep(&self, sweep: &Sweep) -> Result<()> {
        let objects_path = self.sweep_path("objects", sweep.index, "json");
        sweep
            .check_lengths()
            .and_then(|()| sweep.check_values())
            .map_err(|reason| DatasetError::Invalid {
                path: objects_path.clone(),
                reason,
            })?;
        let n = sweep.len();
        let mut velodyne = Vec::with_capacity(16 * n);
        for (p, i) in sweep.points_in_sensor.iter().zip(&sweep.intensities) {
            for v in [p[0], p[1], p[2], *i] {
                velodyne.extend_from_slice(&v.to_le_bytes());
            }
        }
        let labels: Vec<u8> = sweep
            .labels
            .iter()
            .flat_map(|l| l.0.to_le_bytes())
            .collect();
        let flow: Vec<u8> = sweep
            .flow_in_world_mps
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let time: Vec<u8> = sweep
            .time_in_sweep_secs
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        write_atomic(&self.sweep_path("velodyne", sweep.index, "bin"), &velodyne)?;
        write_atomic(&self.sweep_path("labels", sweep.index, "label"), &labels)?;
        write_atomic(&self.sweep_path("flow", sweep.index, "bin"), &flow)?;
        write_atomic(&self.sweep_path("time", sweep.index, "bin"), &time)?;
        if !sweep.rings.is_empty() {
            let rings: Vec<u8> = sweep.rings.iter().flat_map(|r| r.to_le_bytes()).collect();
            let dir = self.dir.join("ring");
            std::fs::create_dir_all(&dir).map_err(|e| DatasetError::io(&dir, e))?;
            write_atomic(&self.sweep_path("ring", sweep.index, "bin"), &rings)?;
        }
        write_json(&objects_path, &sweep.objects)
    }

    /// Writes the ego's own pose estimate of every sweep, `poses_estimated.txt` (KITTI layout, as
    /// `poses.txt`); call before [`Self::finish`].
    pub fn write_estimated_poses(&self, poses: &[Pose]) -> Result<()> {
        let text: String = poses.iter().map(|p| format_kitti_pose(p) + "\n").collect();
        write_atomic(&self.dir.join(ESTIMATED_POSES), text.as_bytes())
    }

    /// Writes `poses.txt`, `times.txt`, `calib.txt`, then the `sequence.json` marker, which
    /// records the SHA-256 of `scenario.toml` (written before, see [`Self::write_scenario`]).
    /// `poses[i]` and `stamps_secs[i]` belong to sweep `i`; every sweep must have been written.
    pub fn finish(
        self,
        scenario: &str,
        seed: u64,
        rate_hz: f64,
        poses: &[Pose],
        stamps_secs: &[f64],
        generator: &str,
    ) -> Result<SequenceInfo> {
        let marker = self.dir.join("sequence.json");
        if poses.len() != stamps_secs.len() {
            let reason = format!(
                "{} poses for {} time stamps",
                poses.len(),
                stamps_secs.len()
            );
            return Err(DatasetError::Invalid {
                path: marker,
                reason,
            });
        }
        let mut points = 0u64;
        let mut sweep_sha256 = Vec::with_capacity(poses.len());
        for index in 0..poses.len() as u32 {
            if !self.has_sweep(index) {
                return Err(DatasetError::Invalid {
                    path: marker,
                    reason: format!("sweep {index} was never written"),
                });
            }
            let velodyne = self.sweep_path("velodyne", index, "bin");
            let bytes = std::fs::metadata(&velodyne)
                .map_err(|e| DatasetError::io(&velodyne, e))?
                .len();
            points += bytes / 16;
            sweep_sha256.push(sweep_digests(&self.dir, index)?);
        }
        let poses_txt: String = poses.iter().map(|p| format_kitti_pose(p) + "\n").collect();
        let times_txt: String = stamps_secs.iter().map(|t| format!("{t:.6e}\n")).collect();
        write_atomic(&self.dir.join("poses.txt"), poses_txt.as_bytes())?;
        write_atomic(&self.dir.join("times.txt"), times_txt.as_bytes())?;
        write_atomic(&self.dir.join("calib.txt"), CALIB_TXT.as_bytes())?;
        // A sequence written by a library user without a scenario records no hash.
        let scenario_path = self.dir.join("scenario.toml");
        let scenario_sha256 = match scenario_path.is_file() {
            true => sha256_hex(&read_limited(&scenario_path, MAX_TEXT_BYTES)?),
            false => String::new(),
        };
        let name = self
            .dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let info = SequenceInfo {
            format: FORMAT_NAME.to_owned(),
            version: FORMAT_VERSION,
            name,
            scenario: scenario.to_owned(),
            scenario_sha256,
            seed,
            sweeps: poses.len() as u32,
            points,
            rate_hz,
            generator: generator.to_owned(),
            sweep_sha256,
        };
        write_json(&marker, &info)?;
        Ok(info)
    }

    pub(crate) fn sweep_path(&self, folder: &str, index: u32, ext: &str) -> PathBuf {
        sweep_path(&self.dir, folder, index, ext)
    }
}
