//! The occupancy run over a dataset: which sequences are scored (every planar scanner's sequence
//! and every 3-D lidar's at 1 Hz or slower, read through the height slice, but training runs; see
//! `sequence_kind.rs`), which methods are compared, and the report they make.

use std::collections::BTreeMap;
use std::sync::Arc;

use patchflow_dataset::Dataset;
use patchflow_occupancy::{
    AheadScores, DgpomMethod, GpomMethod, MapMethod, MotionMap, OccupancyGridMethod,
    OccupancyParams, OccupancySequence, SampleParams, SequenceScores, Thinning, evaluate_sequence,
};

use super::dgpom::dgpom_method;
use super::sequence_kind::{SequenceKind, load_sequence};
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
    /// DGPOM's motion map of each scenario with a training run, by scenario name (Figure 5).
    pub motion_maps: BTreeMap<String, Arc<MotionMap>>,
    /// DGPOM's predictions ahead of the last scan, by scenario name (Figure 10).
    pub ahead: BTreeMap<String, AheadScores>,
    /// How each scored scenario was observed, by scenario name.
    pub kinds: BTreeMap<String, SequenceKind>,
    /// CPU seconds of each map (its thread's: a map runs alone on one), by scenario and method,
    /// in query order, where the system reports them (wall seconds are in the scores; on a
    /// shared machine they grow with the load, CPU seconds hardly).
    pub cpu_seconds: BTreeMap<String, BTreeMap<String, Vec<f64>>>,
}

/// The sequences of `dataset` to score: those [`SequenceKind::of`] maps (a planar scanner's, a
/// 3-D lidar's at 1 Hz or slower), except training runs (names ending in `_train`, kept for
/// methods that learn beforehand). A sequence without `sensor.json` (a dataset of an older
/// build) is an error naming the file; none to score is an error too.
pub fn occupancy_sequences(dataset: &Dataset) -> Result<Vec<String>, EvalError> {
    let mut names = Vec::new();
    for info in dataset.sequences() {
        let sensor = dataset.sequence(&info.name)?.sensor()?;
        if SequenceKind::of(&sensor).is_some() && !info.name.ends_with("_train") {
            names.push(info.name.clone());
        }
    }
    if names.is_empty() {
        return Err(EvalError::BadResult {
            situation: dataset.root().display().to_string(),
            reason: "no sequence of a planar scanner or of a 3-D lidar at 1 Hz to map (generate e.g. dgpom_tjunction)".into(),
        });
    }
    Ok(names)
}

/// The methods compared: DGPOM (if a motion map was learned for the scenario), GPOM in ℜ^D and
/// ℜ^{D+1} (the DGPOM paper's Table 1) and the grid baseline; `samples` says how the GPs draw
/// their training samples (the seed of the free-space samples, the thinning of dense scans:
/// [`SequenceKind::sample_params`]).
pub fn occupancy_methods(
    samples: &SampleParams,
    motion_map: Option<Arc<MotionMap>>,
) -> Vec<Box<dyn MapMethod>> {
    occupancy_methods_with(samples, motion_map.map(|map| dgpom_method(samples, map)))
}

/// [`occupancy_methods`] with a given DGPOM method (whose clones share its fits).
pub fn occupancy_methods_with(
    samples: &SampleParams,
    dgpom: Option<DgpomMethod>,
) -> Vec<Box<dyn MapMethod>> {
    let mut methods: Vec<Box<dyn MapMethod>> = Vec::new();
    if let Some(method) = dgpom {
        methods.push(Box::new(method));
    }
    methods.push(Box::new(GpomMethod::space(samples.clone())));
    methods.push(Box::new(GpomMethod::space_time(samples.clone())));
    methods.push(Box::new(OccupancyGridMethod::default()));
    methods
}

/// What the report says about how the maps were made and where that differs from the paper, for
/// the methods of [`occupancy_methods`] and the protocol `params`.
pub fn occupancy_notes(params: &OccupancyParams) -> Vec<String> {
    let gpom = GpomMethod::space(SampleParams::default());
    let samples = &gpom.samples;
    vec![
        format!(
            "Training samples per scan (paper, Section 2): each return occupied; free samples along every beam, one per {} m stretch at a seeded place, stopping {} m short of the return; beams without a return are free out to maximum range. Each map pools the scan at the query time and the {} before it.",
            samples.free_spacing_m,
            samples.stop_short_m,
            params.scans_per_map.saturating_sub(1)
        ),
        format!(
            "GPOM: GP classification by probabilistic least squares (patchflow-gp; GPML §6.5): SE-ARD regression on ±1 labels, then Φ((αμ + β)/√(1 + α²σ²)) with α, β maximising the leave-one-out probability. Hyperparameters are learned for every map (at most {} L-BFGS iterations of the marginal likelihood on the exact GP's path, as DGPOM's, {} on SPGP's). GP solver: {} (the path each map took is `solver_by_query_time` in `occupancy.json`); the paper does not say how it solved its GPs. GPOM-RD1 adds the time as a third input with its own (ARD) length-scale. The variance drawn is the latent predictive variance σ².",
            gpom.exact_max_iters.min(gpom.max_iters),
            gpom.max_iters,
            gpom.solver.describe()
        ),
        format!(
            "Truth and scoring: exact occupancy at the scanner's height from the dataset's static obstacles (`static.json`) and actor boxes, at each query point of a {} m lattice over the area the scanner observes: within range, inside its field of view, and in front of static structure (a building's interior, which no scan can reach, is left out; what cars hide is kept). The grid baseline (`GRID`) uses 0.5 m cells, hits / (hits + misses), 0.5 where no beam passed.",
            params.query_spacing_m
        ),
        "Reading the maps: pooling the scans of moving cars, GPOM-RD finds its best marginal likelihood with a long length-scale along the lanes and a very short one across them (see the fit column above; the exact GP chooses the same on the T-junction), so the cars become stripes along their lanes while the building's face stays sharp: the paper's 'inability to reconstruct the vehicles' of GPOM ℜ^D. GPOM-RD1 weighs the older scans by its learned temporal length-scale and keeps the cars as blobs where they were last seen; both see only the faces the scanner hit, not the cars' whole boxes, and fall back towards their prior where cars are hidden.".to_owned(),
        "Timing: one map is fit and prediction over the query points, in wall-clock and CPU seconds; the maps run side by side, one per core, each alone on its thread (so the maps' wall seconds add up to about the stage's wall time times the cores, and on a loaded machine a map's wall seconds grow with the load while its CPU seconds hardly do); a Criterion bench (`cargo bench -p patchflow-eval --bench occupancy`) times one map of each method at t = 5.".to_owned(),
    ]
}

/// What the report says about the 3-D lidar's sequences read through the height slice: how a
/// sweep becomes observations and what it took to map them (issue 12, item 4).
pub fn height_slice_note() -> String {
    let thinning = Thinning::default();
    format!(
        "3-D lidar through the height slice (scenarios whose sensor is a spinning lidar at 1 Hz or slower; a planar scanner's are read as they are): each sweep is cut to the thesis' slice, 0.5-1.0 m above the ground estimated from the sweep itself (patchflow-learn's `HeightSlice`, the slice the motion features use), and every beam's part inside the slice becomes a beam in the plane, from where it enters the slice to where it leaves it or returns: a return in the slice is an occupied sample, its sliced stretch is sampled for free space as a planar beam is; a beam's stretch above or below the slice is left out (a ray from the sensor would cross cars it passed over). Truth is taken 0.75 m up. Scaling: an HDL-64E sweep gives about 110,000 returns, about 90,000 beams crossing the slice and about 100,000 samples on the busy intersection, so each scan's GP samples are thinned on a square lattice in the plane (per cell and class the sample nearest the cell centre; the cell starts at {} m and grows by √2 until the scan fits {} samples, about the planar scanner's per-scan count here), so a 3-D map's GP is as large as a planar one's (the same SPGP with fixed pseudo-inputs) and the query lattice is the same 0.5 m; the grid counts every sliced beam. `training points` are after thinning, `drawn` before.",
        thinning.start_cell_m, thinning.budget_per_scan
    )
}

/// Builds the methods for one scenario from the sequence, how it was observed and its training
/// run (`<name>_train` in the same dataset, if there is one): methods that learn beforehand
/// (DGPOM's motion map) learn from the training run.
pub type MethodsFor<'a> = dyn Fn(
        &OccupancySequence,
        SequenceKind,
        Option<&OccupancySequence>,
    ) -> Result<Vec<Box<dyn MapMethod>>, EvalError>
    + 'a;

/// Scores the methods `methods_for` builds on every sequence [`occupancy_sequences`] picks;
/// `on_map(sequence, method, query_scan)` is called after every map.
pub fn evaluate_occupancy(
    dataset: &Dataset,
    methods_for: &MethodsFor<'_>,
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
        let (sequence, kind) = load_sequence(dataset, &name)?;
        let training_name = format!("{name}_train");
        let training = match dataset.sequences().iter().any(|s| s.name == training_name) {
            true => Some(load_sequence(dataset, &training_name)?.0),
            false => None,
        };
        report.kinds.insert(name.clone(), kind);
        let methods = methods_for(&sequence, kind, training.as_ref())?;
        let methods: Vec<&dyn MapMethod> = methods.iter().map(|m| m.as_ref()).collect();
        let scores = evaluate_sequence(&sequence, &methods, params, &|method, t| {
            on_map(&name, method, t)
        })?;
        // Each map's CPU seconds, where the system reports them for every map of the method.
        let cpu: BTreeMap<String, Vec<f64>> = scores
            .methods
            .iter()
            .filter_map(|(id, m)| {
                let secs: Option<Vec<f64>> = m.cpu_seconds_per_map.iter().copied().collect();
                Some((id.name().to_owned(), secs?))
            })
            .collect();
        if !cpu.is_empty() {
            report.cpu_seconds.insert(name.clone(), cpu);
        }
        report.scenarios.push(scores);
    }
    Ok(report)
}
