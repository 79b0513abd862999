//! The occupancy run over a dataset: which sequences are scored (every planar scanner's sequence
//! but training runs), which methods are compared, and the report they make.

use patchflow_dataset::{Dataset, SensorKind};
use patchflow_occupancy::{
    GpomMethod, MapMethod, OccupancyGridMethod, OccupancyParams, OccupancySequence, SampleParams,
    SequenceScores, evaluate_sequence,
};

use crate::error::EvalError;

/// Scores of every method on every scored sequence, with what produced them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct OccupancyReport {
    /// One entry per scored sequence, sorted by name.
    pub scenarios: Vec<SequenceScores>,
    /// The evaluation protocol.
    pub params: OccupancyParams,
    /// Seed of the training samples' free-space draws.
    pub seed: u64,
    /// Notes for the Markdown report.
    pub notes: Vec<String>,
}

/// The sequences of `dataset` to score: those of a planar scanner, except training runs (names
/// ending in `_train`, kept for methods that learn beforehand). A sequence without `sensor.json`
/// (a dataset of an older build) is an error naming the file; none to score is an error too.
pub fn occupancy_sequences(dataset: &Dataset) -> Result<Vec<String>, EvalError> {
    let mut names = Vec::new();
    for info in dataset.sequences() {
        let sensor = dataset.sequence(&info.name)?.sensor()?;
        if sensor.kind == SensorKind::Planar && !info.name.ends_with("_train") {
            names.push(info.name.clone());
        }
    }
    if names.is_empty() {
        return Err(EvalError::BadResult {
            situation: dataset.root().display().to_string(),
            reason: "no sequence of a planar scanner to map (generate e.g. dgpom_tjunction)".into(),
        });
    }
    Ok(names)
}

/// The methods compared: GPOM in ℜ^D and ℜ^{D+1} (the DGPOM paper's Table 1) and the grid
/// baseline; `seed` places the free-space samples along the beams.
pub fn occupancy_methods(seed: u64) -> Vec<Box<dyn MapMethod>> {
    let samples = SampleParams {
        seed,
        ..SampleParams::default()
    };
    vec![
        Box::new(GpomMethod::space(samples.clone())),
        Box::new(GpomMethod::space_time(samples)),
        Box::new(OccupancyGridMethod::default()),
    ]
}

/// Scores `methods` on every sequence [`occupancy_sequences`] picks; `on_map(sequence, method,
/// query_scan)` is called after every map.
pub fn evaluate_occupancy(
    dataset: &Dataset,
    methods: &[&dyn MapMethod],
    params: &OccupancyParams,
    seed: u64,
    on_map: &(dyn Fn(&str, &str, usize) + Sync),
) -> Result<OccupancyReport, EvalError> {
    let mut report = OccupancyReport {
        params: params.clone(),
        seed,
        ..OccupancyReport::default()
    };
    for name in occupancy_sequences(dataset)? {
        let sequence = OccupancySequence::load(&dataset.sequence(&name)?)?;
        let scores = evaluate_sequence(&sequence, methods, params, &|method, t| {
            on_map(&name, method, t)
        })?;
        report.scenarios.push(scores);
    }
    Ok(report)
}
