//! The files a benchmark run writes or deletes beside the report writer's: the run's entries in
//! `metrics.json` (seeds, model files, spread), sections added to `report.md`, the model files'
//! names.

use std::path::Path;

use patchflow_learn::GpKind;

use crate::bench::seed_spread::SeedSpread;
use crate::error::EvalError;
use crate::pipeline::plan::BenchPlan;

/// What `metrics.json` records of the run beside the scores: the training seeds, the model
/// files (relative to the output folder, seed by seed) and the spread over the seeds.
pub(crate) fn run_entries(
    plan: &BenchPlan,
    spread: &SeedSpread,
) -> serde_json::Map<String, serde_json::Value> {
    let seeds = plan.training_seeds();
    let models: Vec<String> = seeds
        .iter()
        .flat_map(|&seed| plan.gps.iter().map(move |&gp| model_file(plan, gp, seed)))
        .collect();
    let mut entries = serde_json::Map::new();
    entries.insert("seeds".into(), serde_json::json!(seeds));
    entries.insert("model_files".into(), serde_json::json!(models));
    entries.insert("quick".into(), serde_json::json!(plan.quick));
    entries.insert("seed_spread".into(), spread.json());
    entries
}

/// Inserts `section` into the Markdown file at `path` before its second `## ` heading (right
/// after the summary), or at its end.
pub(crate) fn insert_after_summary(path: &Path, section: &str) -> Result<(), EvalError> {
    let content = std::fs::read_to_string(path).map_err(|e| EvalError::io(path, e))?;
    let at = content
        .match_indices("\n## ")
        .nth(1)
        .map_or(content.len(), |(i, _)| i + 1);
    let text = format!("{}{section}\n{}", &content[..at], &content[at..]);
    std::fs::write(path, text).map_err(|e| EvalError::io(path, e))
}

/// Appends `text` to the file at `path`, after a blank line.
pub(crate) fn append(path: &Path, text: &str) -> Result<(), EvalError> {
    let mut content = std::fs::read_to_string(path).map_err(|e| EvalError::io(path, e))?;
    content.push('\n');
    content.push_str(text);
    std::fs::write(path, content).map_err(|e| EvalError::io(path, e))
}

/// The model file of one GP kind and seed, relative to the output folder.
pub(crate) fn model_file(plan: &BenchPlan, gp: GpKind, seed: u64) -> String {
    if seed == plan.seed {
        format!("models/{gp}.json")
    } else {
        format!("models/{gp}-seed{seed}.json")
    }
}
