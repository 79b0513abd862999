//! Which files in a sequence folder the writer made, so that regenerating a sequence
//! (`generate --overwrite`) removes exactly those and never a file a user put there.

use std::path::Path;

use crate::writer::{ESTIMATED_POSES, SENSOR_JSON, STATIC_JSON};
use crate::{DatasetError, LOCK_FILE, Result};

/// Files the writer puts at the top of a sequence folder.
const TOP_FILES: [&str; 8] = [
    "scenario.toml",
    "sequence.json",
    STATIC_JSON,
    SENSOR_JSON,
    "poses.txt",
    ESTIMATED_POSES,
    "times.txt",
    "calib.txt",
];

/// Per-sweep folders and the extension of their `NNNNNN.ext` files.
const SWEEP_FILES: [(&str, &str); 6] = [
    ("velodyne", "bin"),
    ("labels", "label"),
    ("flow", "bin"),
    ("time", "bin"),
    ("objects", "json"),
    ("ring", "bin"),
];

/// Removes from sequence folder `dir` the files the writer makes (its top-level files and the
/// `NNNNNN.ext` files of its sweep folders, then those folders if empty), leaving every other
/// file; returns the paths it left. A symbolic link is never followed: one in place of a file
/// or folder of the layout is an error naming it, so nothing outside `dir` is removed.
pub fn remove_written_files(dir: &Path) -> Result<Vec<std::path::PathBuf>> {
    let mut kept = Vec::new();
    for name in TOP_FILES {
        remove_if_file(&dir.join(name))?;
    }
    for (folder, ext) in SWEEP_FILES {
        let sub = dir.join(folder);
        match std::fs::symlink_metadata(&sub) {
            Err(_) => continue,
            Ok(meta) if meta.file_type().is_symlink() || !meta.is_dir() => {
                return Err(refused_link(&sub));
            }
            Ok(_) => {}
        }
        let entries = std::fs::read_dir(&sub).map_err(|e| DatasetError::io(&sub, e))?;
        let mut left = false;
        for entry in entries {
            let entry = entry.map_err(|e| DatasetError::io(&sub, e))?;
            let path = entry.path();
            if is_sweep_file(&entry.file_name().to_string_lossy(), ext) {
                remove_if_file(&path)?;
            } else {
                kept.push(path);
                left = true;
            }
        }
        if !left {
            std::fs::remove_dir(&sub).map_err(|e| DatasetError::io(&sub, e))?;
        }
    }
    let entries = std::fs::read_dir(dir).map_err(|e| DatasetError::io(dir, e))?;
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let known = name == LOCK_FILE
            || TOP_FILES.contains(&name.as_str())
            || SWEEP_FILES.iter().any(|(f, _)| *f == name);
        if !known {
            kept.push(entry.path());
        }
    }
    kept.sort();
    Ok(kept)
}

/// `NNNNNN.ext`: six digits and the folder's extension.
fn is_sweep_file(name: &str, ext: &str) -> bool {
    name.split_once('.').is_some_and(|(stem, e)| {
        e == ext && stem.len() == 6 && stem.bytes().all(|b| b.is_ascii_digit())
    })
}

/// Removes `path` if it is a regular file; a symbolic link or folder there is an error.
fn remove_if_file(path: &Path) -> Result<()> {
    match std::fs::symlink_metadata(path) {
        Err(_) => Ok(()),
        Ok(meta) if meta.is_file() => {
            std::fs::remove_file(path).map_err(|e| DatasetError::io(path, e))
        }
        Ok(_) => Err(refused_link(path)),
    }
}

fn refused_link(path: &Path) -> DatasetError {
    DatasetError::Invalid {
        path: path.to_owned(),
        reason: "a symbolic link or another kind of file stands where the dataset writer puts its own; refusing to remove it or anything it leads to".to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_writers_files_are_removed_and_the_rest_is_listed() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::create_dir_all(d.join("velodyne")).unwrap();
        std::fs::create_dir_all(d.join("labels")).unwrap();
        std::fs::write(d.join("velodyne/000000.bin"), b"x").unwrap();
        std::fs::write(d.join("velodyne/notes.txt"), b"mine").unwrap();
        std::fs::write(d.join("labels/000000.label"), b"x").unwrap();
        std::fs::write(d.join("sequence.json"), b"{}").unwrap();
        std::fs::write(d.join("thesis.pdf"), b"mine").unwrap();
        let kept = remove_written_files(d).unwrap();
        assert_eq!(
            kept,
            vec![d.join("thesis.pdf"), d.join("velodyne/notes.txt")]
        );
        assert!(!d.join("labels").exists() && !d.join("sequence.json").exists());
        assert!(!d.join("velodyne/000000.bin").exists());
    }

    #[test]
    fn a_symlinked_sweep_folder_is_refused_and_its_target_untouched() {
        let dir = tempfile::tempdir().unwrap();
        let elsewhere = tempfile::tempdir().unwrap();
        std::fs::write(elsewhere.path().join("000000.bin"), b"precious").unwrap();
        std::os::unix::fs::symlink(elsewhere.path(), dir.path().join("velodyne")).unwrap();
        let err = remove_written_files(dir.path()).unwrap_err();
        assert!(err.to_string().contains("symbolic link"), "{err}");
        assert!(elsewhere.path().join("000000.bin").exists());
    }
}
