//! Report files: written atomically (the dataset crate's one atomic write), folders, numbers in tables.

use std::path::Path;

use crate::error::EvalError;

/// Writes `bytes` to `path` atomically, through the workspace's one atomic write
/// ([`patchflow_dataset::write_atomic`]).
pub(crate) fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), EvalError> {
    Ok(patchflow_dataset::write_atomic(path, bytes)?)
}

/// Writes `value` to `path` as pretty JSON with a final line break, atomically.
pub(crate) fn write_json_atomic(
    path: &Path,
    value: &impl serde::Serialize,
) -> Result<(), EvalError> {
    let mut bytes = serde_json::to_vec_pretty(value).map_err(|source| EvalError::Json {
        path: path.to_owned(),
        source,
    })?;
    bytes.push(b'\n');
    write_atomic(path, &bytes)
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
