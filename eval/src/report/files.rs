//! Atomic file writes: write a sibling temporary file, then rename, so no half-written report survives.

use std::path::Path;

use crate::error::EvalError;

/// Writes `bytes` to `path` through a temporary sibling and a rename.
pub(crate) fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), EvalError> {
    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let tmp = path.with_file_name(format!(".{file_name}.tmp"));
    std::fs::write(&tmp, bytes).map_err(|e| EvalError::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| EvalError::io(path, e))
}

/// Creates a folder and its parents.
pub(crate) fn create_dir(path: &Path) -> Result<(), EvalError> {
    std::fs::create_dir_all(path).map_err(|e| EvalError::io(path, e))
}

/// A number with `decimals` decimals, or `–` when absent or not finite (for Markdown tables).
pub(crate) fn fmt_opt(value: Option<f64>, decimals: usize) -> String {
    match value {
        Some(v) if v.is_finite() => format!("{v:.decimals$}"),
        _ => "–".to_owned(),
    }
}
