//! The datasets a run deletes once used: `bench` and `study` generate their data under `OUT/data`
//! and remove each dataset as soon as no later stage reads it, so the disk holds one at a time.

use std::path::Path;

use crate::error::EvalError;

/// Deletes a dataset folder the run no longer needs (nothing if it is gone already).
pub(crate) fn remove_data(dir: &Path) -> Result<(), EvalError> {
    match std::fs::remove_dir_all(dir) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(EvalError::io(dir, e)),
        _ => Ok(()),
    }
}

/// Deletes a folder if it is empty.
pub(crate) fn remove_empty_dir(dir: &Path) -> Result<(), EvalError> {
    let empty = match std::fs::read_dir(dir) {
        Ok(mut entries) => entries.next().is_none(),
        Err(_) => false,
    };
    if empty {
        std::fs::remove_dir(dir).map_err(|e| EvalError::io(dir, e))?;
    }
    Ok(())
}
