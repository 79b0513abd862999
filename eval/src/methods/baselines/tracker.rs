//! Multi-target tracker over all clusters, for the `KF-AUTO` baseline: one constant-velocity Kalman
//! filter per track on the cluster centroid, nearest-neighbour association with a χ² gate.
//! `GP-KF` runs the same tracker with the clusters' outlines
//! ([`MultiTargetTracker::step_anchored`]): while one end of a moving object is hidden, its track
//! measures the visible end instead of the centroid (`reference_point`), and while the whole
//! object shows, the centre of a box aligned with the track's heading (`box_reference`); `KF-AUTO`
//! stays the thesis' centroid filter.
//!
//! Each scan:
//! 1. predict every track to the scan's time stamp;
//! 2. gate: a (track, cluster) pair is a candidate when the squared Mahalanobis distance of the
//!    centroid innovation `yᵀS⁻¹y` (the anchored point's or the box's centre, for a track that
//!    has one) is at most `gate_chi2` (9.21 = χ²₂ at 99 %);
//! 3. associate greedily, one-to-one: confirmed tracks before tentative ones, then the smallest
//!    distance first (ties broken by track id, then cluster index, so the result is deterministic);
//!    a cluster that comes with a measured velocity (`GP-KF`) subtracts 2 ln of how much likelier
//!    this track finds that velocity than a new track would (when it is likelier), so a track
//!    keeps the object moving its way, and a cluster without a reading competes on the same
//!    footing (its ratio is 1);
//! 4. update the associated tracks, then set each one's reference for the next scan (an anchor,
//!    a box or the centroid); a tentative track becomes confirmed after `confirm_hits`
//!    consecutive hits;
//! 5. track end: a tentative track is deleted at its first miss, a confirmed one after more than
//!    `max_misses` consecutive misses (it coasts on its prediction meanwhile);
//! 6. track start: every unassociated cluster starts a tentative track.
//!
//! Life-cycle after Deep SORT (reference/baselines.md §2.2). The tracker never looks at the target
//! id: the benchmark only reads out the confirmed track that took the target cluster.

use patchflow_learn::ObjectEnd;

use crate::error::EvalError;
use crate::methods::baselines::box_reference::{
    BoxReference, measured_centre, measured_reach_m, next_box, reach_m,
};
use crate::methods::baselines::kalman::{ConstantVelocityKalman, KalmanParams};
use crate::methods::baselines::reference_point::{
    Anchor, MIN_ANCHOR_SPEED_MPS, measured_point, next_reference,
};
use crate::methods::baselines::track_filter::TrackFilter;
use crate::methods::baselines::velocity_measurement::VelocityMeasurement;

/// Knobs of the tracker.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackerParams {
    /// Filter of each track.
    pub kalman: KalmanParams,
    /// Gate on the squared Mahalanobis distance (χ² with 2 dof; 9.21 = 99 %).
    pub gate_chi2: f64,
    /// Consecutive hits before a tentative track is confirmed.
    pub confirm_hits: usize,
    /// A confirmed track is deleted after more consecutive misses than this.
    pub max_misses: usize,
}

impl Default for TrackerParams {
    fn default() -> Self {
        Self {
            kalman: KalmanParams::default(),
            gate_chi2: 9.21,
            confirm_hits: 3,
            max_misses: 3,
        }
    }
}

/// What a `GP-KF` track sees of a cluster besides its centroid.
#[derive(Debug, Clone, Copy, Default)]
pub struct ClusterOutline<'a> {
    /// The cluster's points of smallest and of largest bearing, each with whether a nearer return
    /// hides what lies beyond it (`RangeProfile::ends`).
    pub ends: Option<[ObjectEnd; 2]>,
    /// The cluster's points, world frame, metres.
    pub points_xy: &'a [[f64; 2]],
}

/// Whether a track has earned trust yet.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TrackStatus {
    /// Started recently; not reported.
    Tentative,
    /// Seen `confirm_hits` times in a row; reported.
    Confirmed,
}

/// One tracked object.
#[derive(Debug, Clone, PartialEq)]
pub struct Track<F = ConstantVelocityKalman> {
    /// Unique id, never reused.
    pub id: usize,
    /// Its filter.
    pub filter: F,
    /// Tentative or confirmed.
    pub status: TrackStatus,
    /// Consecutive scans with an associated cluster.
    pub consecutive_hits: usize,
    /// Consecutive scans without.
    pub consecutive_misses: usize,
    /// The visible end the track measures while an end of its object is hidden; `None`: the
    /// centroid (`reference_point`).
    pub anchor: Option<Anchor>,
    /// The box whose centre the track measures while its object shows whole and moves
    /// (`box_reference`); `None`: the centroid.
    pub reference: Option<BoxReference>,
}

/// The tracker state.
#[derive(Debug, Clone)]
pub struct MultiTargetTracker<F = ConstantVelocityKalman> {
    params: TrackerParams,
    tracks: Vec<Track<F>>,
    next_id: usize,
    last_stamp_secs: Option<f64>,
}

impl MultiTargetTracker {
    /// An empty tracker of constant-velocity filters (`KF-AUTO`).
    pub fn new(params: TrackerParams) -> Result<Self, EvalError> {
        Self::with_track_filter(params)
    }
}

impl<F: TrackFilter> MultiTargetTracker<F> {
    /// An empty tracker whose tracks run the filter `F` (`GP-KF`: `GpTrustFilter`, an interacting
    /// multiple model over the GP's trust).
    pub fn with_track_filter(params: TrackerParams) -> Result<Self, EvalError> {
        params.kalman.validate()?;
        if params.gate_chi2.is_nan() || params.gate_chi2 <= 0.0 {
            return Err(EvalError::BadParameter {
                name: "TrackerParams.gate_chi2",
                reason: format!("must be positive, got {}", params.gate_chi2),
            });
        }
        Ok(Self {
            params,
            tracks: Vec::new(),
            next_id: 0,
            last_stamp_secs: None,
        })
    }

    /// The live tracks.
    pub fn tracks(&self) -> &[Track<F>] {
        &self.tracks
    }

    /// The live track with this id.
    pub fn track(&self, id: usize) -> Option<&Track<F>> {
        self.tracks.iter().find(|t| t.id == id)
    }

    /// Processes one scan's cluster centroids; returns, per cluster, the id of the track (tentative
    /// or confirmed) that took it. `scan` only labels errors.
    pub fn step(
        &mut self,
        scan: usize,
        stamp_secs: f64,
        centroids_xy: &[[f64; 2]],
    ) -> Result<Vec<Option<usize>>, EvalError> {
        self.step_measured(scan, stamp_secs, centroids_xy, &[])
    }

    /// [`Self::step`] where cluster `c` may also come with a measured velocity
    /// (`velocities[c]`, `GP-KF`): the track that takes it, or the track it starts, is also
    /// corrected by it. A shorter slice means the rest have none.
    pub fn step_measured(
        &mut self,
        scan: usize,
        stamp_secs: f64,
        centroids_xy: &[[f64; 2]],
        velocities: &[Option<VelocityMeasurement>],
    ) -> Result<Vec<Option<usize>>, EvalError> {
        self.step_anchored(scan, stamp_secs, centroids_xy, &[], velocities, [0.0, 0.0])
    }

    /// [`Self::step_measured`] where cluster `c` may also come with its outline (`outlines[c]`),
    /// seen from the sensor at `sensor_xy`: while one end of an object is hidden its track
    /// measures the visible end instead of the centroid (`reference_point`), and while a moving
    /// object shows whole, the centre of its box (`box_reference`). A shorter slice means the
    /// rest have none.
    pub fn step_anchored(
        &mut self,
        scan: usize,
        stamp_secs: f64,
        centroids_xy: &[[f64; 2]],
        outlines: &[ClusterOutline<'_>],
        velocities: &[Option<VelocityMeasurement>],
        sensor_xy: [f64; 2],
    ) -> Result<Vec<Option<usize>>, EvalError> {
        let velocity_of = |c: usize| velocities.get(c).copied().flatten();
        let ends_of = |c: usize| outlines.get(c).and_then(|o| o.ends.as_ref());
        let outline_of = |c: usize| outlines.get(c).map_or(&[][..], |o| o.points_xy);
        // 1. Predict.
        if let Some(last) = self.last_stamp_secs {
            let dt = stamp_secs - last;
            if !(dt > 0.0 && dt.is_finite()) {
                return Err(EvalError::BadObservation {
                    situation: "-".into(),
                    scan,
                    reason: format!("time stamp {stamp_secs} s does not follow {last} s"),
                });
            }
            self.tracks.iter_mut().for_each(|t| t.filter.predict(dt));
        }
        self.last_stamp_secs = Some(stamp_secs);
        // The heading each track's box is aligned with this scan (`box_reference`).
        let headings: Vec<Option<f64>> = self
            .tracks
            .iter()
            .map(|t| t.filter.estimate().map(|e| e.heading_rad))
            .collect();
        let centre = |track: &Track<F>, ti: usize, ci: usize| {
            let outline = outline_of(ci);
            measured_centre(
                track.reference.as_ref(),
                headings[ti],
                outline,
                centroids_xy[ci],
            )
        };
        // 2. Gate.
        let new_track_log_likelihood = (0..centroids_xy.len())
            .map(|ci| {
                velocity_of(ci)
                    .map(|v| F::start([0.0, 0.0], self.params.kalman)?.velocity_log_likelihood(&v))
                    .transpose()
            })
            .collect::<Result<Vec<_>, EvalError>>()?;
        let mut candidates = Vec::new();
        // How far each cluster's points lie from its centroid: a track without an anchor measures
        // a point within reach of it (`box_reference`), so a cluster whose reach lies wholly
        // beyond the gate needs no box fitted to it (the same pairs as fitting every one).
        let cluster_reach_m: Vec<f64> = (0..centroids_xy.len())
            .map(|ci| reach_m(outline_of(ci), centroids_xy[ci]))
            .collect();
        // Each track's gate once per scan (none when there is no cluster to gate).
        let gated = if centroids_xy.is_empty() {
            &[][..]
        } else {
            &self.tracks[..]
        };
        for (ti, track) in gated.iter().enumerate() {
            let gate = track.filter.centroid_gate()?;
            let gate_reach_m = gate.reach_m(self.params.gate_chi2);
            let box_now = track.reference.as_ref().filter(|_| headings[ti].is_some());
            for (ci, &new_track) in new_track_log_likelihood.iter().enumerate() {
                if track.anchor.is_none() {
                    let reach = measured_reach_m(box_now, cluster_reach_m[ci]);
                    if gate.beyond(centroids_xy[ci], reach, gate_reach_m) {
                        continue;
                    }
                }
                let point =
                    measured_point(track.anchor.as_ref(), centre(track, ti, ci), ends_of(ci));
                let d2 = gate.mahalanobis_sq(point);
                if d2 <= self.params.gate_chi2 {
                    let rank = usize::from(track.status == TrackStatus::Tentative);
                    // A cluster with a measured velocity (GP-KF) adds the velocity's evidence
                    // for this track against a new one: −2 ln of the likelihood ratio (a
                    // feature-aided track score; Blackman and Popoli 1999, §6.2). A cluster
                    // without a reading adds nothing, which is that ratio's value for a
                    // dimension not measured, so clusters with and without a reading compare
                    // like with like. Only evidence for counts: the GP misreads the right
                    // object for runs of scans, and where only one cluster carries a reading
                    // (the per-target protocol) a penalty would push the track off it alone.
                    let cost = match (velocity_of(ci), new_track) {
                        (Some(v), Some(new_track)) => {
                            let ratio = track.filter.velocity_log_likelihood(&v)? - new_track;
                            d2 - 2.0 * ratio.max(0.0)
                        }
                        _ => d2,
                    };
                    candidates.push((rank, cost, track.id, ti, ci));
                }
            }
        }
        // 3. Greedy one-to-one nearest neighbour, confirmed tracks first.
        candidates.sort_by(|a, b| {
            a.0.cmp(&b.0)
                .then(a.1.total_cmp(&b.1))
                .then(a.2.cmp(&b.2))
                .then(a.4.cmp(&b.4))
        });
        let mut track_cluster: Vec<Option<usize>> = vec![None; self.tracks.len()];
        let mut cluster_track: Vec<Option<usize>> = vec![None; centroids_xy.len()];
        for (_, _, id, ti, ci) in candidates {
            if track_cluster[ti].is_none() && cluster_track[ci].is_none() {
                track_cluster[ti] = Some(ci);
                cluster_track[ci] = Some(id);
            }
        }
        // 4. Update hits, 5. count misses.
        for (ti, (track, cluster)) in self.tracks.iter_mut().zip(&track_cluster).enumerate() {
            match cluster {
                Some(ci) => {
                    let (centre, ends) = (centre(track, ti, *ci), ends_of(*ci));
                    track
                        .filter
                        .update(measured_point(track.anchor.as_ref(), centre, ends))?;
                    let reference = track.filter.position();
                    // Only a confirmed track that sees its object move takes an anchor
                    // (`reference_point`).
                    let moving = track.status == TrackStatus::Confirmed
                        && track
                            .filter
                            .estimate()
                            .is_some_and(|e| e.speed_mps >= MIN_ANCHOR_SPEED_MPS);
                    let ends = ends.filter(|_| moving || track.anchor.is_some());
                    let anchored = track.anchor.is_some();
                    let (anchor, mut shift) = next_reference(track.anchor, centre, ends, reference);
                    if !anchored && anchor.is_none() {
                        // A moving object in view measured by its box from now on, re-fitted to
                        // this scan; the state moves by what the change of reference measures.
                        let (next, moved) = next_box(
                            track.reference.as_ref(),
                            headings[ti].filter(|_| moving),
                            outline_of(*ci),
                            sensor_xy,
                            centroids_xy[*ci],
                        );
                        shift = [
                            shift[0] + moved[0] - centre[0],
                            shift[1] + moved[1] - centre[1],
                        ];
                        track.reference = next;
                    }
                    track.filter.shift_position(shift);
                    track.anchor = anchor;
                    if let Some(v) = velocity_of(*ci) {
                        track.filter.update_velocity(&v)?;
                    }
                    track.consecutive_hits += 1;
                    track.consecutive_misses = 0;
                    if track.consecutive_hits >= self.params.confirm_hits {
                        track.status = TrackStatus::Confirmed;
                    }
                }
                None => {
                    track.consecutive_hits = 0;
                    track.consecutive_misses += 1;
                }
            }
        }
        let max_misses = self.params.max_misses;
        self.tracks.retain(|t| match t.status {
            TrackStatus::Tentative => t.consecutive_misses == 0,
            TrackStatus::Confirmed => t.consecutive_misses <= max_misses,
        });
        // 6. Start tracks on the unassociated clusters.
        for (ci, assigned) in cluster_track.iter_mut().enumerate() {
            if assigned.is_none() {
                let mut track = Track {
                    id: self.next_id,
                    filter: F::start(centroids_xy[ci], self.params.kalman)?,
                    status: TrackStatus::Tentative,
                    consecutive_hits: 1,
                    consecutive_misses: 0,
                    anchor: None,
                    reference: None,
                };
                if self.params.confirm_hits <= 1 {
                    track.status = TrackStatus::Confirmed;
                }
                if let Some(v) = velocity_of(ci) {
                    track.filter.update_velocity(&v)?;
                }
                *assigned = Some(track.id);
                self.next_id += 1;
                self.tracks.push(track);
            }
        }
        Ok(cluster_track)
    }
}

#[cfg(test)]
#[path = "tracker_tests.rs"]
mod tests;
