//! Reads a dataset written by [`crate::SequenceWriter`], checking every file against the format.

use std::path::{Path, PathBuf};

use crate::manifest::read_marker;
use crate::pose::parse_kitti_pose;
use crate::writer::{ESTIMATED_POSES, sweep_path};
use crate::{DatasetError, Manifest, ObjectTruth, PointLabel, Pose, Result, SequenceInfo, Sweep};

/// An opened dataset folder.
#[derive(Debug, Clone)]
pub struct Dataset {
    root: PathBuf,
    manifest: Manifest,
}

impl Dataset {
    /// Opens the dataset at `root`. The finished sequences are found from their markers, so a
    /// folder filled by several shards opens whole; a `manifest.json` of another format version is
    /// an error.
    pub fn open(root: &Path) -> Result<Self> {
        if !root.is_dir() {
            return Err(DatasetError::Missing {
                path: root.to_owned(),
                what: "dataset folder".into(),
            });
        }
        if root.join("manifest.json").is_file() {
            Manifest::read(root)?;
        }
        let manifest = Manifest::scan(root)?;
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

impl SequenceReader {
    /// Opens a sequence folder (`DIR/sequences/<name>`).
    pub fn open(dir: &Path) -> Result<Self> {
        let info = read_marker(&dir.join("sequence.json"))?;
        let poses_path = dir.join("poses.txt");
        let poses = read_lines(&poses_path)?
            .iter()
            .enumerate()
            .map(|(i, line)| {
                parse_kitti_pose(line).ok_or_else(|| {
                    DatasetError::corrupt(&poses_path, format!("line {}: not a 3 x 4 pose", i + 1))
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let times_path = dir.join("times.txt");
        let stamps_secs = read_lines(&times_path)?
            .iter()
            .enumerate()
            .map(|(i, line)| {
                line.trim().parse::<f64>().map_err(|_| {
                    DatasetError::corrupt(&times_path, format!("line {}: not a number", i + 1))
                })
            })
            .collect::<Result<Vec<_>>>()?;
        for (path, count) in [(&poses_path, poses.len()), (&times_path, stamps_secs.len())] {
            if count != info.sweeps as usize {
                let reason = format!("{count} lines, but the sequence has {} sweeps", info.sweeps);
                return Err(DatasetError::corrupt(path, reason));
            }
        }
        let estimated_poses = read_estimated_poses(dir, info.sweeps as usize)?;
        Ok(Self {
            dir: dir.to_owned(),
            info,
            poses,
            estimated_poses,
            stamps_secs,
        })
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

    /// Reads sweep `index` and checks that its files agree on the point count.
    pub fn read_sweep(&self, index: usize) -> Result<Sweep> {
        if index >= self.len() {
            let what = format!("sweep {index} (the sequence has {})", self.len());
            return Err(DatasetError::Missing {
                path: self.dir.clone(),
                what,
            });
        }
        let i = index as u32;
        let velodyne = read_f32s(&sweep_path(&self.dir, "velodyne", i, "bin"), 4)?;
        let n = velodyne.len() / 4;
        let labels_path = sweep_path(&self.dir, "labels", i, "label");
        let labels: Vec<PointLabel> = read_words(&labels_path, 1, n)?
            .into_iter()
            .map(PointLabel)
            .collect();
        let flow = read_f32s_n(&sweep_path(&self.dir, "flow", i, "bin"), 3, n)?;
        let time = read_f32s_n(&sweep_path(&self.dir, "time", i, "bin"), 1, n)?;
        let ring_path = sweep_path(&self.dir, "ring", i, "bin");
        let rings = if ring_path.is_file() {
            read_rings(&ring_path, n)?
        } else {
            Vec::new()
        };
        let objects_path = sweep_path(&self.dir, "objects", i, "json");
        let text = std::fs::read_to_string(&objects_path)
            .map_err(|e| DatasetError::io(&objects_path, e))?;
        let objects: Vec<ObjectTruth> = serde_json::from_str(&text)
            .map_err(|e| DatasetError::corrupt(&objects_path, e.to_string()))?;
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

/// The estimated poses of a sequence folder, `None` if it has no `poses_estimated.txt`.
fn read_estimated_poses(dir: &Path, sweeps: usize) -> Result<Option<Vec<Pose>>> {
    let path = dir.join(ESTIMATED_POSES);
    if !path.is_file() {
        return Ok(None);
    }
    let poses = read_lines(&path)?
        .iter()
        .enumerate()
        .map(|(i, line)| {
            parse_kitti_pose(line).ok_or_else(|| {
                DatasetError::corrupt(&path, format!("line {}: not a 3 x 4 pose", i + 1))
            })
        })
        .collect::<Result<Vec<_>>>()?;
    if poses.len() != sweeps {
        let reason = format!(
            "{} lines, but the sequence has {sweeps} sweeps",
            poses.len()
        );
        return Err(DatasetError::corrupt(&path, reason));
    }
    Ok(Some(poses))
}

/// A ring file: one little-endian uint16 per point, exactly `n`.
fn read_rings(path: &Path, n: usize) -> Result<Vec<u16>> {
    let bytes = std::fs::read(path).map_err(|e| DatasetError::io(path, e))?;
    if bytes.len() != 2 * n {
        let reason = format!("{} bytes for {n} points (2 bytes each)", bytes.len());
        return Err(DatasetError::corrupt(path, reason));
    }
    Ok(bytes
        .chunks_exact(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect())
}

fn read_lines(path: &Path) -> Result<Vec<String>> {
    let text = std::fs::read_to_string(path).map_err(|e| DatasetError::io(path, e))?;
    Ok(text
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(str::to_owned)
        .collect())
}

/// Reads little-endian 32-bit words; the file must hold whole records of `per_record` words.
fn read_words_any(path: &Path, per_record: usize) -> Result<Vec<u32>> {
    let bytes = std::fs::read(path).map_err(|e| DatasetError::io(path, e))?;
    let record = 4 * per_record;
    if bytes.len() % record != 0 {
        let reason = format!(
            "{} bytes is not a whole number of {record}-byte records",
            bytes.len()
        );
        return Err(DatasetError::corrupt(path, reason));
    }
    Ok(bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect())
}

/// Like [`read_words_any`], and the file must hold exactly `n` records.
fn read_words(path: &Path, per_record: usize, n: usize) -> Result<Vec<u32>> {
    let words = read_words_any(path, per_record)?;
    if words.len() != per_record * n {
        let reason = format!("{} records for {n} points", words.len() / per_record);
        return Err(DatasetError::corrupt(path, reason));
    }
    Ok(words)
}

fn read_f32s(path: &Path, per_record: usize) -> Result<Vec<f32>> {
    Ok(read_words_any(path, per_record)?
        .into_iter()
        .map(f32::from_bits)
        .collect())
}

fn read_f32s_n(path: &Path, per_record: usize, n: usize) -> Result<Vec<f32>> {
    Ok(read_words(path, per_record, n)?
        .into_iter()
        .map(f32::from_bits)
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ActorClass, SemanticClass, SequenceWriter};
    use nalgebra::Vector3;

    fn sample_sweep(index: u32) -> Sweep {
        let pose = Pose::new(
            Vector3::new(index as f64, 2.0, 1.73),
            Vector3::new(0.0, 0.0, 0.3),
        );
        Sweep {
            index,
            stamp_secs: index as f64 * 0.1,
            world_from_sensor: pose,
            points_in_sensor: vec![[1.0, 2.0, -1.5], [10.5, -3.25, 0.5]],
            intensities: vec![0.25, 0.75],
            labels: vec![
                PointLabel::new(SemanticClass::Road, 0),
                PointLabel::new(SemanticClass::MovingCar, 3),
            ],
            flow_in_world_mps: vec![[0.0, 0.0, 0.0], [5.0, -1.0, 0.0]],
            time_in_sweep_secs: vec![0.0125, 0.0875],
            rings: vec![63, 2],
            estimated_world_from_sensor: None,
            objects: vec![ObjectTruth {
                id: 3,
                name: "target".into(),
                class: ActorClass::Car,
                target: true,
                moving: true,
                centre_m: [12.0, 0.0, 0.75],
                size_m: [4.5, 1.8, 1.5],
                yaw_rad: -0.2,
                velocity_mps: [5.0, -1.0, 0.0],
                speed_mps: 26f64.sqrt(),
                heading_rad: (-1f64).atan2(5.0),
                yaw_rate_radps: 0.0,
                point_count: 1,
            }],
        }
    }

    fn write_sequence(root: &Path, sweeps: &[Sweep]) {
        let writer = SequenceWriter::open(root, "seq").unwrap();
        for sweep in sweeps {
            writer.write_sweep(sweep).unwrap();
        }
        let poses: Vec<Pose> = sweeps.iter().map(|s| s.world_from_sensor).collect();
        let stamps: Vec<f64> = sweeps.iter().map(|s| s.stamp_secs).collect();
        writer
            .finish("demo", 7, 10.0, &poses, &stamps, "test")
            .unwrap();
    }

    #[test]
    fn a_written_sequence_reads_back_identically() {
        let dir = tempfile::tempdir().unwrap();
        let sweeps = [sample_sweep(0), sample_sweep(1)];
        write_sequence(dir.path(), &sweeps);
        let dataset = Dataset::open(dir.path()).unwrap();
        assert_eq!(dataset.sequences().len(), 1);
        assert_eq!(dataset.sequences()[0].points, 4);
        let seq = dataset.sequence("seq").unwrap();
        for (i, expected) in sweeps.iter().enumerate() {
            let got = seq.read_sweep(i).unwrap();
            assert_eq!(got.points_in_sensor, expected.points_in_sensor);
            assert_eq!(got.labels, expected.labels);
            assert_eq!(got.flow_in_world_mps, expected.flow_in_world_mps);
            assert_eq!(got.time_in_sweep_secs, expected.time_in_sweep_secs);
            assert_eq!(got.rings, expected.rings);
            assert_eq!(got.objects, expected.objects);
            assert!(
                (got.world_from_sensor.translation.vector
                    - expected.world_from_sensor.translation.vector)
                    .norm()
                    < 1e-9
            );
        }
    }

    #[test]
    fn without_an_estimate_file_the_estimated_poses_are_the_truth() {
        let dir = tempfile::tempdir().unwrap();
        write_sequence(dir.path(), &[sample_sweep(0), sample_sweep(1)]);
        let seq = Dataset::open(dir.path()).unwrap().sequence("seq").unwrap();
        assert_eq!(seq.estimated_poses(), seq.poses());
        let sweep = seq.read_sweep(1).unwrap();
        assert_eq!(sweep.estimated_world_from_sensor, None);
        assert_eq!(sweep.estimated_pose(), sweep.world_from_sensor);
    }

    #[test]
    fn an_estimate_file_is_read_beside_the_truth() {
        let dir = tempfile::tempdir().unwrap();
        let sweeps = [sample_sweep(0), sample_sweep(1)];
        let writer = SequenceWriter::open(dir.path(), "seq").unwrap();
        for sweep in &sweeps {
            writer.write_sweep(sweep).unwrap();
        }
        let truth: Vec<Pose> = sweeps.iter().map(|s| s.world_from_sensor).collect();
        let estimate: Vec<Pose> = truth
            .iter()
            .map(|p| {
                Pose::new(
                    p.translation.vector + Vector3::new(0.3, -0.2, 0.0),
                    Vector3::new(0.0, 0.0, 0.31),
                )
            })
            .collect();
        writer.write_estimated_poses(&estimate).unwrap();
        let stamps: Vec<f64> = sweeps.iter().map(|s| s.stamp_secs).collect();
        writer
            .finish("demo", 7, 10.0, &truth, &stamps, "test")
            .unwrap();
        let seq = Dataset::open(dir.path()).unwrap().sequence("seq").unwrap();
        let sweep = seq.read_sweep(1).unwrap();
        let got = sweep.estimated_pose().translation.vector;
        assert!((got - estimate[1].translation.vector).norm() < 1e-9);
        assert!(
            (sweep.world_from_sensor.translation.vector - truth[1].translation.vector).norm()
                < 1e-9
        );
    }

    #[test]
    fn a_ring_file_of_the_wrong_length_is_an_error_naming_it() {
        let dir = tempfile::tempdir().unwrap();
        write_sequence(dir.path(), &[sample_sweep(0)]);
        let ring = dir.path().join("sequences/seq/ring/000000.bin");
        std::fs::write(&ring, [0u8; 3]).unwrap();
        let err = Dataset::open(dir.path())
            .unwrap()
            .sequence("seq")
            .unwrap()
            .read_sweep(0)
            .unwrap_err();
        assert!(err.to_string().contains("ring/000000.bin"), "{err}");
    }

    #[test]
    fn a_truncated_label_file_is_an_error_naming_it() {
        let dir = tempfile::tempdir().unwrap();
        write_sequence(dir.path(), &[sample_sweep(0)]);
        let labels = dir.path().join("sequences/seq/labels/000000.label");
        std::fs::write(&labels, [0u8; 4]).unwrap();
        let err = Dataset::open(dir.path())
            .unwrap()
            .sequence("seq")
            .unwrap()
            .read_sweep(0)
            .unwrap_err();
        assert!(err.to_string().contains("000000.label"), "{err}");
    }

    #[test]
    fn a_marker_of_another_version_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        write_sequence(dir.path(), &[sample_sweep(0)]);
        let marker = dir.path().join("sequences/seq/sequence.json");
        let text = std::fs::read_to_string(&marker)
            .unwrap()
            .replace("\"version\": 1", "\"version\": 99");
        std::fs::write(&marker, text).unwrap();
        let err = Dataset::open(dir.path()).unwrap_err();
        assert!(
            matches!(err, DatasetError::Version { found: 99, .. }),
            "{err}"
        );
    }

    #[test]
    fn an_unfinished_sequence_is_not_listed() {
        let dir = tempfile::tempdir().unwrap();
        write_sequence(dir.path(), &[sample_sweep(0)]);
        let writer = SequenceWriter::open(dir.path(), "half").unwrap();
        writer.write_sweep(&sample_sweep(0)).unwrap();
        let dataset = Dataset::open(dir.path()).unwrap();
        let names: Vec<_> = dataset
            .sequences()
            .iter()
            .map(|s| s.name.as_str())
            .collect();
        assert_eq!(names, ["seq"]);
        assert!(writer.has_sweep(0) && !writer.has_sweep(1));
    }
}
