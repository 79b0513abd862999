//! What the moving/static classifier reads of one cluster: summaries of the difference map
//! (thesis Eq. 2.9, m_t − m_{t−1}) on the cluster's occupied cells and around its centroid, its
//! size and range; and the training label, whether most of its points truly move.
//!
//! A static object leaves the difference map near zero (both sweeps see the same cells occupied);
//! a moving one gains occupancy ahead of itself and loses it behind, on its own cells and in the
//! patch around it. Range and size tell the classifier how much to trust a weak difference (far
//! and small clusters are seen by few beams).

use patchflow_dataset::Sweep;

use crate::SweepFeatures;

/// Names of the inputs, in [`cluster_inputs`] order.
pub const MOVING_INPUT_NAMES: [&str; 6] = [
    "mean_difference",
    "mean_abs_difference",
    "patch_mean_abs_difference",
    "patch_max_abs_difference",
    "log_points",
    "log_range_m",
];

/// A point moves when its true speed exceeds this (Argoverse 2's dynamic threshold, m/s).
pub const MOVING_SPEED_MPS: f64 = 0.5;

/// The inputs of cluster `c` of `features` ([`MOVING_INPUT_NAMES`]).
pub fn cluster_inputs(features: &SweepFeatures, c: usize) -> [f64; 6] {
    let members = features.clusters().members(c);
    let samples = features.cell_samples(members);
    let difference = features.difference_map();
    let (mut sum, mut abs_sum) = (0.0, 0.0);
    for p in &samples.positions {
        let d = difference.at(p[0], p[1]);
        sum += d;
        abs_sum += d.abs();
    }
    let cells = samples.positions.len().max(1) as f64;
    let n = members.len().max(1) as f64;
    let centroid = members.iter().fold([0.0, 0.0], |acc, &i| {
        let p = &features.points()[i];
        [acc[0] + p.x_m / n, acc[1] + p.y_m / n]
    });
    let patch = features.patch_at(centroid, features.bearing_at(centroid));
    let patch_max = patch
        .difference()
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let sensor = features.sensor_xy();
    let range_m = (centroid[0] - sensor[0]).hypot(centroid[1] - sensor[1]);
    [
        sum / cells,
        abs_sum / cells,
        patch.mean_abs_difference(),
        patch_max,
        n.ln(),
        range_m.max(1.0).ln(),
    ]
}

/// Whether more than half the points of cluster `c` move faster than [`MOVING_SPEED_MPS`] in
/// `sweep` (the sweep `features` was cut from).
pub fn cluster_is_moving(features: &SweepFeatures, sweep: &Sweep, c: usize) -> bool {
    let members = features.clusters().members(c);
    let moving = members
        .iter()
        .filter(|&&i| {
            let v = sweep.flow_in_world_mps[features.points()[i].index];
            f64::from(v[0]).hypot(f64::from(v[1])) > MOVING_SPEED_MPS
        })
        .count();
    2 * moving > members.len()
}
