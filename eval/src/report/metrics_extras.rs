//! Entries that a caller adds to a written `metrics.json` beside the SPEC §7 shape: what produced
//! the numbers (`seeds`, `models`, `versions`) and the spread over training seeds.

use std::path::Path;

use crate::error::EvalError;
use crate::report::files::write_atomic;
use crate::report::json::metrics_text;

/// Adds (or replaces) top-level `entries` in the `metrics.json` at `path`; the file stays sorted
/// by key and pretty-printed like the writer's.
pub fn add_to_metrics(
    path: &Path,
    entries: serde_json::Map<String, serde_json::Value>,
) -> Result<(), EvalError> {
    let bytes = std::fs::read(path).map_err(|e| EvalError::io(path, e))?;
    let json_error = |source| EvalError::Json {
        path: path.to_owned(),
        source,
    };
    let mut value: serde_json::Value = serde_json::from_slice(&bytes).map_err(json_error)?;
    let Some(object) = value.as_object_mut() else {
        return Err(EvalError::BadResult {
            situation: path.display().to_string(),
            reason: "metrics.json does not hold a JSON object".into(),
        });
    };
    object.extend(entries);
    write_atomic(path, metrics_text(&value)?.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn added_entries_sit_beside_the_existing_ones_in_key_order() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("metrics.json");
        std::fs::write(&path, "{\"situations\": {}, \"version\": \"0.1.0\"}\n").unwrap();
        let mut entries = serde_json::Map::new();
        entries.insert("seeds".into(), serde_json::json!([7, 8, 9]));
        add_to_metrics(&path, entries).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let value: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(value["seeds"], serde_json::json!([7, 8, 9]));
        assert_eq!(value["version"], "0.1.0");
        assert!(
            text.find("\"seeds\"") < text.find("\"situations\""),
            "{text}"
        );
    }
}
