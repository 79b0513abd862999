//! What a benchmark run records beside the scores: its entries in `metrics.json` (seeds, model
//! files, spread) and the model files' names.

use patchflow_learn::GpKind;

use crate::bench::seed_spread::SeedSpread;
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

/// The model file of one GP kind and seed, relative to the output folder.
pub(crate) fn model_file(plan: &BenchPlan, gp: GpKind, seed: u64) -> String {
    if seed == plan.seed {
        format!("models/{gp}.json")
    } else {
        format!("models/{gp}-seed{seed}.json")
    }
}
