//! Moving or static, learned (issue 27): a per-cluster probability that an object hypothesis
//! moves, from summaries of its difference-map cells (thesis 2.1.2) and of the change both sweeps
//! observed over half a second, classified by GP probabilistic least squares (`patchflow-gp`'s
//! [`PlsClassifier`](patchflow_gp::PlsClassifier)) and saved as `moving.json` beside a motion
//! model.
//!
//! | file | what |
//! |---|---|
//! | `change_evidence.rs` | m_t − m_{t−5} where both sweeps observed the cell |
//! | `cluster_inputs.rs` | the classifier's inputs per cluster and the training label |
//! | `decision_threshold.rs` | the threshold that maximises the moving IoU on the training mix |
//! | `moving_belief.rs` | the per-scan probabilities smoothed along the clusters' own tracks |
//! | `moving_classifier.rs` | training the bag and the per-scan decision |
//! | `moving_draw.rs` | one GP of the bag, fitted to one seeded draw of clusters |
//! | `moving_file.rs` | the model file |

mod change_evidence;
mod cluster_inputs;
mod decision_threshold;
mod moving_belief;
mod moving_classifier;
mod moving_draw;
mod moving_file;

pub use change_evidence::{CHANGE_BASELINE_SCANS, ChangeEvidence};
pub use cluster_inputs::{
    MOVING_INPUT_NAMES, MOVING_INPUTS, MOVING_SPEED_MPS, cluster_inputs, cluster_is_moving,
};
pub use moving_belief::{BELIEF_MEMORY, MovingBelief};
pub use moving_classifier::{MovingClassifier, MovingParams, MovingRow};
pub use moving_file::{MOVING_FILE_NAME, MOVING_FORMAT, MOVING_VERSION};
