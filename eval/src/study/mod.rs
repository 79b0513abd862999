//! Studies (issue #10): one factor of the world or the sensor varied, everything else fixed and
//! seeded, every method scored at each point (the whole-scene flow too, with `ZERO-FLOW`); sharded
//! like `generate` and merged into `study.json`, `study.md` and plots. The realism study also runs inside `bench`.

mod bench_realism;
mod discussion;
mod findings;
mod flow_scores;
mod markdown;
mod measures;
mod merge;
mod plan;
mod plan_stamp;
mod plot;
mod point_result;
mod run;
mod scenario_setting;
mod sensor_setting;
mod study_report;

pub use bench_realism::{realism_in_bench, realism_sections};
pub use discussion::discussion_section;
pub use flow_scores::FlowScores;
pub use markdown::{study_markdown, study_section};
pub use merge::{StudyFiles, merge_study, write_study};
pub use plan::{CELL_SIZES_M, StudyFactor, StudyPlan, StudyPoint};
pub use plan_stamp::PlanStamp;
pub use point_result::{POINT_BINS, PointResult, Scores};
pub use run::run_study;
pub use sensor_setting::SensorSetting;
pub use study_report::{PointFile, StudyReport, point_file};
