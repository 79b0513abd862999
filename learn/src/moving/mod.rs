//! Moving or static, learned (issue 27): a per-cluster probability that an object hypothesis
//! moves, from a few summaries of its difference-map cells (thesis 2.1.2), classified by GP
//! probabilistic least squares (`patchflow-gp`'s [`PlsClassifier`](patchflow_gp::PlsClassifier))
//! and saved as `moving.json` beside a motion model.
//!
//! | file | what |
//! |---|---|
//! | `cluster_inputs.rs` | the classifier's inputs per cluster and the training label |
//! | `moving_classifier.rs` | training, the per-scan decision, the model file |

mod cluster_inputs;
mod moving_classifier;

pub use cluster_inputs::{MOVING_INPUT_NAMES, MOVING_SPEED_MPS, cluster_inputs, cluster_is_moving};
pub use moving_classifier::{
    MOVING_FILE_NAME, MOVING_FORMAT, MOVING_VERSION, MovingClassifier, MovingParams,
};
