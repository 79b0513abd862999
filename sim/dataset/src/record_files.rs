//! The plain files of a sequence: text lines (`poses.txt`, `poses_estimated.txt`, `times.txt`),
//! binary records of little-endian 32-bit words (`velodyne`, `labels`, `flow`, `time`) and of
//! 16-bit words (`ring`), each read with its size checked first and its values checked after.

use std::path::Path;

use crate::limits::{MAX_TEXT_BYTES, read_limited, read_text_limited};
use crate::{DatasetError, MAX_POINTS_PER_SWEEP, Result};

pub(crate) fn read_lines(path: &Path) -> Result<Vec<String>> {
    let text = read_text_limited(path, MAX_TEXT_BYTES)?;
    Ok(text
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(str::to_owned)
        .collect())
}

/// Reads little-endian 32-bit words; the file must hold whole records of `per_record` words,
/// exactly `n` records if given, and at most [`MAX_POINTS_PER_SWEEP`]. The size is checked
/// before anything is read.
pub(crate) fn read_words(path: &Path, per_record: usize, n: Option<usize>) -> Result<Vec<u32>> {
    let record = 4 * per_record as u64;
    let max_records = n.unwrap_or(MAX_POINTS_PER_SWEEP) as u64;
    let bytes = read_limited(path, record * max_records).map_err(|e| match (e, n) {
        (DatasetError::TooLarge { .. }, Some(n)) => {
            DatasetError::corrupt(path, format!("more than {n} records for {n} points"))
        }
        (DatasetError::TooLarge { .. }, None) => DatasetError::corrupt(
            path,
            format!("more than {MAX_POINTS_PER_SWEEP} points, the most a sweep holds"),
        ),
        (other, _) => other,
    })?;
    let len = bytes.len() as u64;
    if !len.is_multiple_of(record) {
        let reason = format!("{len} bytes is not a whole number of {record}-byte records");
        return Err(DatasetError::corrupt(path, reason));
    }
    if let Some(n) = n
        && len / record != n as u64
    {
        let reason = format!("{} records for {n} points", len / record);
        return Err(DatasetError::corrupt(path, reason));
    }
    Ok(bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect())
}

/// Like [`read_words`], as finite `f32` values of magnitude at most `limit` (what the file holds
/// in physical sense, e.g. no 1e38 m/s flow), named with their `unit` in the error.
pub(crate) fn read_f32s(
    path: &Path,
    per_record: usize,
    n: Option<usize>,
    (limit, unit): (f64, &str),
) -> Result<Vec<f32>> {
    let values: Vec<f32> = read_words(path, per_record, n)?
        .into_iter()
        .map(f32::from_bits)
        .collect();
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        let reason = format!(
            "point {} holds {}, not a finite number",
            k / per_record,
            values[k]
        );
        return Err(DatasetError::corrupt(path, reason));
    }
    if let Some(k) = values.iter().position(|v| f64::from(v.abs()) > limit) {
        let reason = format!(
            "point {} holds {:e}, beyond the ±{limit} {unit} this file may hold",
            k / per_record,
            values[k]
        );
        return Err(DatasetError::corrupt(path, reason));
    }
    Ok(values)
}

/// Reads a file of exactly `n` little-endian `u16` values (`ring/NNNNNN.bin`); the size is
/// checked before anything is read.
pub(crate) fn read_u16s(path: &Path, n: usize) -> Result<Vec<u16>> {
    let expected = 2 * n as u64;
    let bytes = read_limited(path, expected).map_err(|e| match e {
        DatasetError::TooLarge { .. } => DatasetError::corrupt(
            path,
            format!("more than {expected} bytes for {n} points (2 bytes each)"),
        ),
        other => other,
    })?;
    if bytes.len() as u64 != expected {
        let reason = format!("{} bytes for {n} points (2 bytes each)", bytes.len());
        return Err(DatasetError::corrupt(path, reason));
    }
    Ok(bytes
        .chunks_exact(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect())
}
