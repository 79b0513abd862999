//! Size limits of the dataset format, checked before a file is read or a sweep is written, so a
//! corrupt or hostile file cannot make a reader allocate without bound.

use std::io::Read;
use std::path::Path;

use crate::{DatasetError, Result, check_input_file};

/// Most points one sweep may hold (the simulator's rays per turn are bounded by the same number):
/// 4,000,000 points are 64 MB of `velodyne` data, 35 times an HDL-64E sweep.
pub const MAX_POINTS_PER_SWEEP: usize = 4_000_000;

/// Most sweeps one sequence may hold.
pub const MAX_SWEEPS: usize = 100_000;

/// Largest JSON file (objects, markers, manifest) a reader accepts: 64 MiB, far above 65,535
/// objects of about 400 bytes each.
pub(crate) const MAX_JSON_BYTES: u64 = 64 << 20;

/// Largest per-sweep file (a `velodyne` file of [`MAX_POINTS_PER_SWEEP`] points, 16 bytes each).
pub(crate) const MAX_SWEEP_FILE_BYTES: u64 = 16 * MAX_POINTS_PER_SWEEP as u64;

/// Largest text file (`poses.txt`, `times.txt`, `scenario.toml`) a reader accepts: 64 MiB, far
/// above [`MAX_SWEEPS`] pose lines of about 200 bytes.
pub(crate) const MAX_TEXT_BYTES: u64 = 64 << 20;

/// Reads a whole file, refusing one larger than `max_bytes` before allocating for it.
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("big.bin");
/// std::fs::write(&path, [0u8; 100]).unwrap();
/// assert!(patchflow_dataset::read_limited(&path, 50).is_err());
/// assert_eq!(patchflow_dataset::read_limited(&path, 100).unwrap().len(), 100);
/// ```
pub fn read_limited(path: &Path, max_bytes: u64) -> Result<Vec<u8>> {
    let too_big = |len: u64| DatasetError::TooLarge {
        path: path.to_owned(),
        len,
        limit: max_bytes,
    };
    // Checked before opening: opening a FIFO for reading blocks until a writer comes.
    let len = check_input_file(path)?;
    if len > max_bytes {
        return Err(too_big(len));
    }
    let file = std::fs::File::open(path).map_err(|e| DatasetError::io(path, e))?;
    let len = file
        .metadata()
        .map_err(|e| DatasetError::io(path, e))?
        .len();
    if len > max_bytes {
        return Err(too_big(len));
    }
    // The length can change under us (or be wrong for special files): read at most one byte more.
    let mut bytes = Vec::with_capacity(len as usize);
    file.take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| DatasetError::io(path, e))?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_big(bytes.len() as u64));
    }
    Ok(bytes)
}

/// Like [`read_limited`], as UTF-8 text.
pub(crate) fn read_text_limited(path: &Path, max_bytes: u64) -> Result<String> {
    String::from_utf8(read_limited(path, max_bytes)?)
        .map_err(|_| DatasetError::corrupt(path, "not UTF-8 text"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_over_the_limit_is_refused_naming_it() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("objects.json");
        std::fs::write(&path, vec![b' '; 2000]).unwrap();
        let err = read_limited(&path, 1000).unwrap_err().to_string();
        assert!(
            err.contains("objects.json") && err.contains("too large (2000 bytes, limit 1000)"),
            "{err}"
        );
    }

    #[test]
    fn binary_bytes_are_not_text() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("times.txt");
        std::fs::write(&path, [0xff, 0xfe, 0x00]).unwrap();
        assert!(read_text_limited(&path, 100).is_err());
    }
}
