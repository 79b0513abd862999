//! Point-to-point ICP between a cluster at t−1 and at t in the ground plane (thesis 3.2.1, Besl &
//! McKay 1992): nearest neighbours from a k-d tree, the closed-form SVD fit of [`fit_rigid_svd`],
//! outlier gating, and a convergence test on the change of the transform.
//!
//! Gating: a correspondence is kept when its distance is at most the current gate. The gate starts
//! at `initial_gate_m` (wide, since the centroid initialisation can be off by the partial-view
//! centroid shift of a metre or more) and then shrinks after every iteration to
//! `gate_sigma_factor` × a robust residual scale σ = 1.4826 · median residual, never growing and
//! never below `min_gate_m` (in the spirit of KISS-ICP's 3σ gate, reference/baselines.md §1.1; the
//! median keeps the points seen in only one of the scans from inflating the gate).
//! Correspondences run from each source point to its nearest target point (Besl & McKay, as the
//! thesis); `symmetric` adds the pairs from each target point to its nearest source point, which
//! helps when the target scan shows more of the object than the source.
//!
//! Convergence: stop when one iteration changes the transform by less than
//! `convergence_translation_m` and `convergence_rotation_rad` and the gate has stopped
//! shrinking, or after `max_iterations`.
//!
//! Known limit: on evenly spaced samples (a grid), point-to-point ICP can stop at a fixed point a
//! few centimetres from the truth (see the test documenting it); real scans, with irregular
//! sampling, rarely show it.
//!
//! Motion: the object's velocity is the displacement of the source centroid under the found
//! transform, `(T·c − c)/Δt`, not `t/Δt`, which would be wrong whenever R ≠ I away from the origin.

use kiddo::{ImmutableKdTree, SquaredEuclidean};
use nalgebra::{Isometry2, Point2, Rotation2, Translation2, UnitComplex, Vector2};
use rayon::prelude::*;

use crate::methods::baselines::rigid_fit::fit_rigid_svd;
use crate::methods::observation::centroid_of;

/// ICP knobs; the defaults suit car-sized clusters at 10 Hz.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IcpParams {
    /// Most iterations.
    pub max_iterations: usize,
    /// Stop when an iteration moves the translation by less than this, metres.
    pub convergence_translation_m: f64,
    /// ... and the rotation by less than this, radians.
    pub convergence_rotation_rad: f64,
    /// Correspondence gate of the first iteration, metres.
    pub initial_gate_m: f64,
    /// Smallest gate, metres (a few times the range noise, so a perfect match does not collapse it).
    pub min_gate_m: f64,
    /// The gate shrinks to this many robust residual scales (1.4826 · median residual).
    pub gate_sigma_factor: f64,
    /// Fewer points than this in either cluster: no rotation is fitted, only the centroid translation.
    pub min_points: usize,
    /// Also pair every target point with its nearest source point (both directions, one fit).
    pub symmetric: bool,
}

impl Default for IcpParams {
    fn default() -> Self {
        Self {
            max_iterations: 50,
            convergence_translation_m: 1e-5,
            convergence_rotation_rad: 1e-6,
            initial_gate_m: 2.0,
            min_gate_m: 0.25,
            gate_sigma_factor: 3.0,
            min_points: 3,
            symmetric: false,
        }
    }
}

/// The result of one ICP run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IcpAlignment {
    /// Maps a point of the source cluster (t−1) onto the target cluster (t), world frame.
    pub target_from_source: Isometry2<f64>,
    /// Iterations run.
    pub iterations: usize,
    /// Whether the convergence test was met (false when stopped by the cap or lost correspondences).
    pub converged: bool,
    /// Correspondences inside the final gate.
    pub inlier_count: usize,
    /// RMS residual of those, metres.
    pub inlier_rms_m: f64,
    /// True when only the centroid translation could be used (too few points or correspondences).
    pub degenerate: bool,
}

impl IcpAlignment {
    /// Velocity of the object: displacement of the source centroid under the transform over `dt_secs`.
    pub fn velocity_of(&self, source_centroid_xy: [f64; 2], dt_secs: f64) -> [f64; 2] {
        let c = Point2::new(source_centroid_xy[0], source_centroid_xy[1]);
        let moved = self.target_from_source.transform_point(&c);
        [(moved.x - c.x) / dt_secs, (moved.y - c.y) / dt_secs]
    }
}

/// Aligns `source` (the cluster at t−1) to `target` (the cluster at t), starting from the centroid
/// alignment. `None` when either set is empty; a pure centroid translation (flagged `degenerate`)
/// when either has fewer than `min_points` points.
///
/// ```
/// use patchflow_eval::{align_icp, IcpParams};
/// let source = [[0.0, 0.0], [4.0, 0.0], [4.0, 1.8], [0.0, 1.8], [2.0, 0.0], [4.0, 0.9]];
/// let target: Vec<[f64; 2]> = source.iter().map(|p| [p[0] + 1.0, p[1] + 0.5]).collect();
/// let alignment = align_icp(&source, &target, &IcpParams::default()).unwrap();
/// let v = alignment.velocity_of([2.0, 0.75], 0.1);
/// assert!((v[0] - 10.0).abs() < 1e-6 && (v[1] - 5.0).abs() < 1e-6);
/// ```
pub fn align_icp(
    source: &[[f64; 2]],
    target: &[[f64; 2]],
    params: &IcpParams,
) -> Option<IcpAlignment> {
    // Non-finite points carry no geometry (and would break the k-d tree); drop them.
    let finite = |p: &&[f64; 2]| p[0].is_finite() && p[1].is_finite();
    if !source.iter().all(|p| finite(&p)) || !target.iter().all(|p| finite(&p)) {
        let source: Vec<[f64; 2]> = source.iter().filter(finite).copied().collect();
        let target: Vec<[f64; 2]> = target.iter().filter(finite).copied().collect();
        return align_icp(&source, &target, params);
    }
    let source_centroid = centroid_of(source)?;
    let target_centroid = centroid_of(target)?;
    // Initialisation by centroid alignment.
    let centroid_shift = Isometry2::translation(
        target_centroid[0] - source_centroid[0],
        target_centroid[1] - source_centroid[1],
    );
    align_icp_from(source, target, centroid_shift, params)
}

/// [`align_icp`] started from `initial` instead of the centroid alignment (`GP-ICP`: the GP's
/// motion estimate over the interval). `None` when either set is empty; `initial` itself
/// (flagged `degenerate`) when either has fewer than `min_points` points.
pub fn align_icp_from(
    source: &[[f64; 2]],
    target: &[[f64; 2]],
    initial: Isometry2<f64>,
    params: &IcpParams,
) -> Option<IcpAlignment> {
    let finite = |p: &&[f64; 2]| p[0].is_finite() && p[1].is_finite();
    if !source.iter().all(|p| finite(&p)) || !target.iter().all(|p| finite(&p)) {
        let source: Vec<[f64; 2]> = source.iter().filter(finite).copied().collect();
        let target: Vec<[f64; 2]> = target.iter().filter(finite).copied().collect();
        return align_icp_from(&source, &target, initial, params);
    }
    if source.is_empty() || target.is_empty() {
        return None;
    }
    let translation_only = IcpAlignment {
        target_from_source: initial,
        iterations: 0,
        converged: false,
        inlier_count: 0,
        inlier_rms_m: f64::NAN,
        degenerate: true,
    };
    if source.len() < params.min_points || target.len() < params.min_points {
        return Some(translation_only);
    }
    let (Ok(target_tree), Ok(source_tree)) = (
        ImmutableKdTree::<f64, 2>::new_from_slice(target),
        ImmutableKdTree::<f64, 2>::new_from_slice(source),
    ) else {
        return Some(translation_only);
    };

    let mut current = initial;
    let mut gate_m = params.initial_gate_m;
    let mut result = translation_only;
    for iteration in 1..=params.max_iterations {
        // 1. Associate each source point with its nearest target point, inside the gate.
        let (mut paired_source, mut paired_target) =
            correspondences(source, target, &target_tree, &current, gate_m);
        if params.symmetric {
            // Target → source pairs, found by pulling the target back into the source frame.
            let (back_target, back_source) =
                correspondences(target, source, &source_tree, &current.inverse(), gate_m);
            paired_source.extend(back_source);
            paired_target.extend(back_target);
        }
        if paired_source.len() < params.min_points {
            break;
        }
        // 2. Closed-form transform minimising eq. 3.38 over the pairs.
        let Some((rotation, translation)) = fit_rigid_svd(&paired_source, &paired_target) else {
            break;
        };
        let fitted = Isometry2::from_parts(
            Translation2::from(translation),
            UnitComplex::from_rotation_matrix(&Rotation2::from_matrix_unchecked(rotation)),
        );
        // 3. Apply it and measure the residual; shrink the gate.
        let (rms_m, median_m) = residual_stats(&paired_source, &paired_target, &fitted);
        let step = fitted * current.inverse();
        current = fitted;
        result = IcpAlignment {
            target_from_source: current,
            iterations: iteration,
            converged: false,
            inlier_count: paired_source.len(),
            inlier_rms_m: rms_m,
            degenerate: false,
        };
        let previous_gate_m = gate_m;
        gate_m = (params.gate_sigma_factor * 1.4826 * median_m)
            .clamp(params.min_gate_m, gate_m.max(params.min_gate_m));
        // 4. Converged when the transform and the gate stopped changing.
        if gate_m >= previous_gate_m
            && step.translation.vector.norm() < params.convergence_translation_m
            && step.rotation.angle().abs() < params.convergence_rotation_rad
        {
            result.converged = true;
            break;
        }
    }
    Some(result)
}

/// Pairs (original source point, nearest target point) whose distance under `transform` is within the gate.
fn correspondences(
    source: &[[f64; 2]],
    target: &[[f64; 2]],
    tree: &ImmutableKdTree<f64, 2>,
    transform: &Isometry2<f64>,
    gate_m: f64,
) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
    let gate_sq = gate_m * gate_m;
    let pair = |p: &[f64; 2]| {
        let moved = transform.transform_point(&Point2::new(p[0], p[1]));
        let nearest = tree
            .query(&[moved.x, moved.y])
            .nearest_one::<SquaredEuclidean<f64>>()
            .execute();
        (nearest.distance <= gate_sq)
            .then(|| target.get(nearest.item as usize).map(|q| (*p, *q)))
            .flatten()
    };
    if source.len() < PARALLEL_MIN_POINTS {
        return source.iter().filter_map(pair).unzip();
    }
    // Large clusters: the lookups in blocks over both cores, gathered in order (the same pairs).
    let blocks: Vec<Vec<([f64; 2], [f64; 2])>> = source
        .par_chunks(PARALLEL_BLOCK_POINTS)
        .map(|block| block.iter().filter_map(pair).collect())
        .collect();
    blocks.into_iter().flatten().unzip()
}

/// Clusters with at least this many points look up their nearest neighbours in parallel blocks.
const PARALLEL_MIN_POINTS: usize = 512;
/// Points per parallel block of nearest-neighbour lookups.
const PARALLEL_BLOCK_POINTS: usize = 256;

/// RMS and median of the pair residuals under `transform`, metres.
fn residual_stats(
    source: &[[f64; 2]],
    target: &[[f64; 2]],
    transform: &Isometry2<f64>,
) -> (f64, f64) {
    let mut residuals: Vec<f64> = source
        .iter()
        .zip(target)
        .map(|(p, q)| {
            let moved = transform.transform_point(&Point2::new(p[0], p[1]));
            (moved.coords - Vector2::new(q[0], q[1])).norm()
        })
        .collect();
    if residuals.is_empty() {
        return (0.0, 0.0);
    }
    let rms = (residuals.iter().map(|r| r * r).sum::<f64>() / residuals.len() as f64).sqrt();
    residuals.sort_by(f64::total_cmp);
    (rms, residuals[residuals.len() / 2])
}

#[cfg(test)]
#[path = "icp_tests.rs"]
mod tests;
