//! DGPOM in the occupancy run (DGPOM paper, Sections 2.3 and 3): the motion map learned from a
//! scenario's training run (`<name>_train`) and the DGPOM method on it, with what the report says
//! about them (the predictions ahead of the last scan are in `ahead.rs`).

use std::sync::Arc;

use patchflow_occupancy::{
    AheadParams, DgpomMethod, DgpomParams, MotionMap, MotionMapParams, OccupancySequence,
    SampleParams,
};

use crate::error::EvalError;

/// Learns DGPOM's motion map from a training run (Section 2.3: motion clusters of consecutive
/// scans, Υ from 500 of their cells, ε from clusters held out).
pub fn learn_motion_map(training: &OccupancySequence) -> Result<Arc<MotionMap>, EvalError> {
    Ok(Arc::new(MotionMap::learn(
        training,
        &MotionMapParams::default(),
    )?))
}

/// The DGPOM method of the run on `motion_map`; `samples` says how training samples are drawn
/// (the seed of the free-space samples, the thinning of dense scans).
pub fn dgpom_method(samples: &SampleParams, motion_map: Arc<MotionMap>) -> DgpomMethod {
    let params = DgpomParams {
        samples: samples.clone(),
        ..DgpomParams::default()
    };
    DgpomMethod::new(params, motion_map)
}

/// What the report says about DGPOM and where it differs from the paper.
pub fn dgpom_notes(ahead: &AheadParams) -> Vec<String> {
    let method = DgpomParams::default();
    let map = MotionMapParams::default();
    vec![
        format!(
            "DGPOM (paper, Sections 2.2-2.3): the motion map is learned from the scenario's training run (`<name>_train`): per-scan occupancy maps on {} m cells, Diff and Same maps of consecutive scans (a cell counts as changed only if the other scan has no return within one cell, so range noise across a cell boundary is not motion), Same clusters as objects, Diff clusters next to an object as motion clusters (direction from the Diff cluster's centroid to the object's or back, magnitude its width along that line over the scan interval), Same clusters with no Diff cluster next to them as stationary, but (addition) only in the cells the training run never saw change at any pair: a place where objects came and went that looks the same across one pair is a car's side face sliding along itself at grazing incidence, or a queue, not a still object. Addition: a car that moves farther than its visible length between scans leaves no Same cells; its vacated and arrived clusters are paired within {} m/s, best borne out by the scans before and after first (nearest among equals), and get the displacement of their centroids; clusters of one cell are paired too when the scanner's beams are farther apart than a cell at the end of its reach (such a scanner sees a far car as one return a scan), while for a denser scanner each cluster of a pair needs at least {} cells (a one-cell change there is an edge flickering). Υ(x) is two full GPs (SE-ARD, one per component) on up to {} cells of {:.0} % of the scan pairs, half from moving and half from stationary clusters (stationary cells outnumber moving ones about ten to one; a plain draw left the lanes a few cells among hundreds of zeros and slowed the far lane's cars to a third of their speed); ε(x) a third GP on how far Υ misses the velocities of up to {} cells of the held-out pairs (one pair in {}, whole, so ε measures Υ on pairs it never saw); the fields are sampled on a {} m lattice and read bilinearly.",
            map.clusters.cell_m,
            map.clusters.max_speed_mps,
            map.clusters.min_cells,
            map.velocity_points,
            100.0 * (1.0 - map.held_out_fraction),
            map.error_points,
            (1.0 / map.held_out_fraction).round(),
            map.raster_m
        ),
        format!(
            "DGPOM kernel (eqs. 2-6, patchflow-gp `MotionAdapted`): every training point is carried along Υ from its scan's time to the query time (eq. 4, classical Runge-Kutta with a fixed {} s step), then SE-ARD in space between the carried points times the sum of two non-stationary Matérn 3/2 terms in time with l_t(x) = a·ε(x)^(−1/b) (eq. 5-6; the l(x) = l(x') limit is taken analytically). ℓx, ℓy, a, b, the signal and noise variances are learned per map by maximising the marginal likelihood (analytic gradients, checked against central differences in tests), with {} (at most {} L-BFGS iterations); classification by the same probabilistic least squares as GPOM. The paper does not say how it solved its GPs.",
            method.step_secs,
            method.solver.describe(),
            method.max_iters
        ),
        format!(
            "Predicting ahead (cf. the paper's Figure 10): DGPOM is fit once to the scan at a start time and the {} before it, then predicts at the times of the next {} scans with no newer scan; the AUC against the exact occupancy then (the paper approximated its truth by a map of the scan at the query time and scored only where that map was confident), over the area the scanner observes at the start time, averaged over start times {:?} (± 1 standard deviation). The paper's Figure 10 is on its recorded busy intersection; ours is on the simulated scenario named.",
            ahead.scans_per_map.saturating_sub(1),
            ahead.horizon_scans,
            ahead.start_scans
        ),
    ]
}
