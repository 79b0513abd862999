//! An exclusive lock on a dataset folder (`.lock` inside it), held by the one process writing
//! there, so two `generate` runs never write the same sequence at once. The lock is the
//! operating system's advisory file lock, released when the holder exits, however it exits:
//! a crashed run leaves no stale lock behind.
//!
//! While it holds the lock, the holder owns the folder's temporary files: any `*.tmp` left there
//! belongs to a run that has ended, and [`FolderLock::acquire`] removes them.

use std::fs::{File, TryLockError};
use std::path::{Path, PathBuf};

use crate::{DatasetError, Result};

/// Name of the lock file inside a locked folder.
pub const LOCK_FILE: &str = ".lock";

/// A held lock on one folder; released on drop.
#[derive(Debug)]
pub struct FolderLock {
    dir: PathBuf,
    _file: File,
}

impl FolderLock {
    /// Locks `dir` (creating it), waiting for another holder to finish first (`on_wait` is called
    /// once if so), then removes stale temporary files in it and its sub-folders.
    pub fn acquire(dir: &Path, on_wait: &dyn Fn()) -> Result<Self> {
        std::fs::create_dir_all(dir).map_err(|e| DatasetError::io(dir, e))?;
        let path = dir.join(LOCK_FILE);
        let file = File::options()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path)
            .map_err(|e| DatasetError::io(&path, e))?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                on_wait();
                file.lock().map_err(|e| DatasetError::io(&path, e))?;
            }
            Err(TryLockError::Error(e)) => return Err(DatasetError::io(&path, e)),
        }
        let lock = Self {
            dir: dir.to_owned(),
            _file: file,
        };
        lock.remove_temporaries(&lock.dir, 2)?;
        Ok(lock)
    }

    /// The locked folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Removes everything in the folder but the lock file (to regenerate it from scratch).
    pub fn clear(&self) -> Result<()> {
        for entry in read_dir(&self.dir)? {
            let path = entry.path();
            if path.file_name().is_some_and(|n| n == LOCK_FILE) {
                continue;
            }
            let removed = if path.is_dir() {
                std::fs::remove_dir_all(&path)
            } else {
                std::fs::remove_file(&path)
            };
            removed.map_err(|e| DatasetError::io(&path, e))?;
        }
        Ok(())
    }

    /// Removes `*.tmp` files in `dir` and, `depth` levels down, its sub-folders.
    fn remove_temporaries(&self, dir: &Path, depth: usize) -> Result<()> {
        for entry in read_dir(dir)? {
            let path = entry.path();
            if path.is_dir() {
                if depth > 0 {
                    self.remove_temporaries(&path, depth - 1)?;
                }
            } else if path.extension().is_some_and(|e| e == "tmp") {
                std::fs::remove_file(&path).map_err(|e| DatasetError::io(&path, e))?;
            }
        }
        Ok(())
    }
}

fn read_dir(dir: &Path) -> Result<Vec<std::fs::DirEntry>> {
    std::fs::read_dir(dir)
        .and_then(|entries| entries.collect::<std::io::Result<Vec<_>>>())
        .map_err(|e| DatasetError::io(dir, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    #[test]
    fn a_second_holder_waits_until_the_first_releases() {
        let dir = tempfile::tempdir().unwrap();
        let first = FolderLock::acquire(dir.path(), &|| panic!("nobody holds it yet")).unwrap();
        let path = dir.path().to_owned();
        let waiter = std::thread::spawn(move || {
            let waited = Cell::new(false);
            let _second = FolderLock::acquire(&path, &|| waited.set(true)).unwrap();
            waited.get()
        });
        std::thread::sleep(std::time::Duration::from_millis(100));
        drop(first);
        assert!(waiter.join().unwrap(), "the second run did not wait");
    }

    #[test]
    fn stale_temporaries_are_removed_and_data_kept() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("velodyne")).unwrap();
        let stale = dir.path().join("velodyne/000001.bin.77-3.tmp");
        let kept = dir.path().join("velodyne/000000.bin");
        std::fs::write(&stale, b"half").unwrap();
        std::fs::write(&kept, b"whole").unwrap();
        let _lock = FolderLock::acquire(dir.path(), &|| {}).unwrap();
        assert!(!stale.exists() && kept.exists());
    }

    #[test]
    fn clearing_keeps_only_the_lock_file() {
        let dir = tempfile::tempdir().unwrap();
        let lock = FolderLock::acquire(dir.path(), &|| {}).unwrap();
        std::fs::create_dir_all(dir.path().join("labels")).unwrap();
        std::fs::write(dir.path().join("labels/000000.label"), b"x").unwrap();
        std::fs::write(dir.path().join("sequence.json"), b"{}").unwrap();
        lock.clear().unwrap();
        let names: Vec<_> = read_dir(dir.path())
            .unwrap()
            .iter()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(names, [LOCK_FILE]);
    }
}
