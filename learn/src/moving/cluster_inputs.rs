//! What the moving/static classifier reads of one cluster: summaries of the difference map
//! (thesis Eq. 2.9, m_t − m_{t−1}) on the cluster's occupied cells and around its centroid, its
//! size and range; and the training label, whether most of its points truly move.
//!
//! A static object leaves the difference map near zero (both sweeps see the same cells occupied);
//! a moving one gains occupancy ahead of itself and loses it behind, on its own cells and in the
//! box around it. Range and size tell the classifier how much to trust a weak difference (far
//! and small clusters are seen by few beams). Over one sweep a slow mover barely changes the map
//! and a parked car coming into view changes it a lot, so four more inputs read the change both
//! sweeps observed over half a second ([`ChangeEvidence`]).

use patchflow_dataset::Sweep;

use super::change_evidence::ChangeEvidence;
use crate::SweepFeatures;

/// How many inputs the classifier reads per cluster.
pub const MOVING_INPUTS: usize = 10;

/// Names of the inputs, in [`cluster_inputs`] order.
pub const MOVING_INPUT_NAMES: [&str; MOVING_INPUTS] = [
    "gained_share",
    "mean_abs_difference",
    "lost_share",
    "box_mean_abs_difference",
    "log_points",
    "log_range_m",
    "observed_mean_abs_change",
    "observed_gained_own_share",
    "observed_gained_share",
    "observed_lost_share",
];

/// The cluster's bounding box is widened by this on every side to see the cells a moving object
/// left or entered (15 m/s over a 0.1 s sweep), metres.
const BOX_MARGIN_M: f64 = 1.5;
/// A cell gained or lost occupancy when the difference map exceeds this in magnitude.
const CHANGE: f64 = 0.3;

/// A point moves when its true speed exceeds this (Argoverse 2's dynamic threshold, m/s).
pub const MOVING_SPEED_MPS: f64 = 0.5;

/// The inputs of cluster `c` of `features` ([`MOVING_INPUT_NAMES`]): on the cluster's occupied
/// cells the mean |difference|; over its bounding box widened by 1.5 m, the cells that gained
/// and lost occupancy (|difference| > 0.3) per occupied cell of the cluster and the mean
/// |difference|; the log of its points and of its range; then from the observed change of
/// `change`, on the cluster's cells its mean magnitude and the share gained, over the widened box
/// the cells gained and lost per cluster cell. The thesis' 1.1 m patches see only part of a car,
/// whose long side barely changes as it drives along it; the widened box sees the cells it
/// entered and left.
pub fn cluster_inputs(
    features: &SweepFeatures,
    change: &ChangeEvidence,
    c: usize,
) -> [f64; MOVING_INPUTS] {
    let members = features.clusters().members(c);
    let samples = features.cell_samples(members);
    let difference = features.difference_map();
    let abs_sum: f64 = samples
        .positions
        .iter()
        .map(|p| difference.at(p[0], p[1]).abs())
        .sum();
    let cells = samples.positions.len().max(1) as f64;
    let (mut observed_abs, mut observed_gained_own) = (0.0, 0.0);
    for p in &samples.positions {
        let d = change.observed_change(p[0], p[1]);
        observed_abs += d.abs();
        observed_gained_own += f64::from(u8::from(d > CHANGE));
    }
    let n = members.len().max(1) as f64;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    let mut centroid = [0.0, 0.0];
    for &i in members {
        let p = &features.points()[i];
        lo = [lo[0].min(p.x_m), lo[1].min(p.y_m)];
        hi = [hi[0].max(p.x_m), hi[1].max(p.y_m)];
        centroid = [centroid[0] + p.x_m / n, centroid[1] + p.y_m / n];
    }
    let (mut gained, mut lost, mut box_abs, mut box_cells) = (0.0, 0.0, 0.0, 0.0f64);
    let (mut observed_gained, mut observed_lost) = (0.0, 0.0);
    if members.is_empty() {
        lo = [0.0, 0.0];
        hi = [0.0, 0.0];
    }
    let step = features.params().cell_m;
    let mut x = lo[0] - BOX_MARGIN_M;
    while x <= hi[0] + BOX_MARGIN_M {
        let mut y = lo[1] - BOX_MARGIN_M;
        while y <= hi[1] + BOX_MARGIN_M {
            let d = difference.at(x, y);
            gained += f64::from(u8::from(d > CHANGE));
            lost += f64::from(u8::from(d < -CHANGE));
            box_abs += d.abs();
            box_cells += 1.0;
            let observed = change.observed_change(x, y);
            observed_gained += f64::from(u8::from(observed > CHANGE));
            observed_lost += f64::from(u8::from(observed < -CHANGE));
            y += step;
        }
        x += step;
    }
    let sensor = features.sensor_xy();
    let range_m = (centroid[0] - sensor[0]).hypot(centroid[1] - sensor[1]);
    [
        (gained / cells).ln_1p(),
        abs_sum / cells,
        (lost / cells).ln_1p(),
        box_abs / box_cells.max(1.0),
        n.ln(),
        range_m.max(1.0).ln(),
        observed_abs / cells,
        observed_gained_own / cells,
        (observed_gained / cells).ln_1p(),
        (observed_lost / cells).ln_1p(),
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
