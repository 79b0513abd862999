//! Occupancy maps in the evaluation (SPEC §5b, §7 `patchflow occupancy`): the methods compared,
//! the run over a dataset's planar sequences, the DGPOM paper's Table 1 for comparison, and the
//! report files `occupancy.json`, `occupancy.md` and `plots/occupancy_*.png`.

mod ahead;
mod dgpom;
mod fit_tables;
mod json;
mod markdown;
mod paper_table;
mod plot;
mod plot_dgpom;
mod run;
mod sequence_kind;
mod slice_scan;
mod writer;

pub use ahead::{predict_ahead, predict_ahead_with};
pub use dgpom::{dgpom_method, dgpom_notes, learn_motion_map};
pub use markdown::occupancy_section;
pub use run::{
    OccupancyReport, evaluate_occupancy, height_slice_note, occupancy_methods,
    occupancy_methods_with, occupancy_notes, occupancy_sequences,
};
pub use sequence_kind::{SequenceKind, load_sequence};
pub use slice_scan::height_slice_scan;
pub use writer::write_occupancy_report;
