//! The benchmark driver behind `patchflow bench` (SPEC §7): generate the training tracks and the
//! situations, draw training samples, train SPGP and SPGP-HET, cross-validate (thesis 4.3),
//! evaluate every method on every sequence (thesis 4.4 and the whole scene), map the DGPOM paper's
//! T-junction (its Table 1 and Figure 6), write the report.

mod bar_check;
mod notes;
mod plan;
mod run;
pub(crate) mod run_files;
mod seed_spread;
mod short_tracks;
mod stages;
mod target_runs;

pub(crate) use plan::source_name;
pub use plan::{
    BENCH_SEED, BenchPlan, DENSE_TRAFFIC_TOML, QUICK_REALISM_SITUATIONS, QUICK_SWEEP_SHARE,
};
pub use run::{BenchOutcome, run_bench};
pub use seed_spread::{MethodSpread, SeedFigure, SeedSpread};
pub(crate) use short_tracks::shortened_tracks;
pub(crate) use stages::collect_feature_draws_with_bar;
pub use stages::{
    collect_draws_with_bar, collect_samples_with_bar, cross_validate_with_bar, evaluate_with_bar,
    generate_with_progress, occupancy_with_bar,
};
pub use target_runs::evaluate_targets;
pub(crate) use target_runs::evaluate_targets_with_baselines;
