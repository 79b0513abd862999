//! One training sample (thesis 3.1.1): a sliced point on a moving actor, its heading and speed
//! targets, and the features of its heading- and speed-aligned patches.

/// One training sample: a sliced point on a moving actor at sweep `scan ≥ 1`.
#[derive(Debug, Clone, PartialEq)]
pub struct TrainingSample {
    /// Sequence name.
    pub sequence: String,
    /// Sweep index within the sequence.
    pub scan: u32,
    /// Index of the point among the sweep's points.
    pub point: usize,
    /// Actor id (instance id of the point's label).
    pub actor: u16,
    /// Importance weight: mean absolute difference value of the heading patch (thesis Eq. 3.1).
    pub weight: f64,
    /// Bearing of sensor → point, world frame.
    pub bearing_rad: f64,
    /// sin(heading − bearing): the first heading target (thesis 3.1.1).
    pub sin_rel: f64,
    /// cos(heading − bearing): the second heading target.
    pub cos_rel: f64,
    /// The actor's true heading, world frame.
    pub heading_rad: f64,
    /// The actor's true speed: the speed target.
    pub speed_mps: f64,
    /// Features of the patch aligned to the bearing (input of the heading GPs).
    pub heading_features: Vec<f64>,
    /// Features of the patch aligned to the true heading (input of the speed GP).
    pub speed_features: Vec<f64>,
}
