//! KITTI odometry's numeric sequence names beside a dataset's own: KITTI-style loaders (e.g.
//! `kiss_icp_pipeline --dataloader kitti --sequence N`) look for `sequences/NN/velodyne/*.bin`,
//! `sequences/NN/calib.txt` and `poses/NN.txt` under one folder. `DIR/kitti/` is that folder:
//! `kitti/sequences/NN` links to `DIR/sequences/<name>` (nothing is copied), `kitti/poses/NN.txt`
//! is a copy of its true `poses.txt`, and `kitti/names.txt` lists `NN <name>` per line. Numbers
//! follow the manifest's order (sorted by name), so the same dataset gets the same numbers.

use std::path::{Path, PathBuf};

use patchflow_dataset::Manifest;

use crate::error::{Result, SimError};

/// Writes `dir/kitti/` for every finished sequence of the dataset at `dir` (replacing an older
/// one); returns `(number, name)` per sequence. An error names the file concerned.
///
/// ```no_run
/// let names = patchflow_sim::write_kitti_names(std::path::Path::new("data")).unwrap();
/// assert!(names.iter().all(|(number, _)| number.len() >= 2));
/// ```
pub fn write_kitti_names(dir: &Path) -> Result<Vec<(String, String)>> {
    let manifest = Manifest::scan(dir)?;
    let kitti = dir.join("kitti");
    for sub in [kitti.join("sequences"), kitti.join("poses")] {
        if sub.exists() {
            std::fs::remove_dir_all(&sub).map_err(io(&sub))?;
        }
        std::fs::create_dir_all(&sub).map_err(io(&sub))?;
    }
    let names: Vec<(String, String)> = manifest
        .sequences
        .iter()
        .enumerate()
        .map(|(k, s)| (format!("{k:02}"), s.name.clone()))
        .collect();
    for (number, name) in &names {
        let poses = dir.join("sequences").join(name).join("poses.txt");
        let copy = kitti.join("poses").join(format!("{number}.txt"));
        std::fs::copy(&poses, &copy).map_err(io(&poses))?;
        let link = kitti.join("sequences").join(number);
        link_dir(&Path::new("../../sequences").join(name), &link).map_err(io(&link))?;
    }
    let list: String = names.iter().map(|(n, s)| format!("{n} {s}\n")).collect();
    let list_file = kitti.join("names.txt");
    std::fs::write(&list_file, list).map_err(io(&list_file))?;
    Ok(names)
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> SimError + '_ {
    move |source| SimError::Io {
        path: PathBuf::from(path),
        source,
    }
}

#[cfg(unix)]
fn link_dir(target: &Path, link: &Path) -> std::io::Result<()> {
    std::os::unix::fs::symlink(target, link)
}

#[cfg(not(unix))]
fn link_dir(_target: &Path, _link: &Path) -> std::io::Result<()> {
    Err(std::io::Error::new(
        std::io::ErrorKind::Unsupported,
        "numeric KITTI names link folders, which needs a Unix file system",
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{GenerateOptions, ScenarioSource, Shard, generate_dataset};

    #[test]
    fn every_sequence_gets_a_number_a_folder_link_and_a_pose_file() {
        let dir = tempfile::tempdir().unwrap();
        let tiny = include_str!("../../scenarios/tiny.toml");
        let text = tiny.replace("sweeps = 3", "sweeps = 1");
        let sources: Vec<ScenarioSource> = ["b_scene", "a_scene"]
            .iter()
            .map(|name| {
                let path = dir.path().join(format!("{name}.toml"));
                std::fs::write(&path, &text).unwrap();
                ScenarioSource::File(path)
            })
            .collect();
        let out = dir.path().join("data");
        let options = GenerateOptions {
            realism: None,
            out: out.clone(),
            seed: 1,
            shard: Shard::ALL,
            overwrite: false,
        };
        generate_dataset(&sources, &options, &|_| {}).unwrap();
        let names = write_kitti_names(&out).unwrap();
        assert_eq!(
            names,
            [
                ("00".into(), "a_scene".into()),
                ("01".into(), "b_scene".into())
            ]
        );
        let kitti = out.join("kitti");
        let velodyne = kitti.join("sequences/01/velodyne/000000.bin");
        assert!(velodyne.is_file(), "{} missing", velodyne.display());
        assert!(kitti.join("sequences/00/calib.txt").is_file());
        assert_eq!(
            std::fs::read_to_string(kitti.join("poses/01.txt")).unwrap(),
            std::fs::read_to_string(out.join("sequences/b_scene/poses.txt")).unwrap()
        );
        // Run again: replaced, not refused or doubled.
        assert_eq!(write_kitti_names(&out).unwrap().len(), 2);
        assert_eq!(
            std::fs::read_to_string(kitti.join("names.txt")).unwrap(),
            "00 a_scene\n01 b_scene\n"
        );
    }
}
