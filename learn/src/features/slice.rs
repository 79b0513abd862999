//! The height slice (thesis 2.1.1): the parts of the beams and the end points between 0.5 m and
//! 1.0 m above the ground, projected onto the ground plane. The ground is the flat road the
//! thesis assumes (world z = 0) or the local ground estimated from the sweep itself.

use patchflow_dataset::Sweep;
use rayon::prelude::*;

use std::sync::Arc;

use crate::features::beam_counts::BeamCounts;
use crate::features::grid::GridWindow;
use crate::features::ground_grid::{GroundGrid, points_in_world};
use crate::features::ground_slab::{SlabAboveGround, clip_to_slab};
use crate::features::sliced_beam::SlicedBeam;
use crate::features::traced_counts::TracedCounts;
use crate::{FeatureParams, GroundMode, Result};

/// Points per parallel task of the slice above an estimated ground (a sweep's ~120,000 make
/// about fifteen tasks; each clips its beams against the ground on its own).
const TASK_POINTS: usize = 8192;

/// An end point inside the slice: world x, y and its index among the sweep's points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlicedPoint {
    /// World x, metres.
    pub x_m: f64,
    /// World y, metres.
    pub y_m: f64,
    /// Index into the sweep's per-point arrays.
    pub index: usize,
}

/// One sweep cut to the height slice.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightSlice {
    /// Sensor position at the sweep's reference time, world x, y.
    pub sensor_xy: [f64; 2],
    /// Every part of a beam that crosses or ends in the slice, in point order (over uneven
    /// ground a beam may pass through the slice more than once).
    pub beams: Vec<SlicedBeam>,
    /// Every end point in the slice, in point order.
    pub points: Vec<SlicedPoint>,
    /// The beams' hit and miss counts, traced once per cell size.
    counts: TracedCounts,
}

impl HeightSlice {
    /// Cuts a sweep: beams run from the sensor origin to each end point, placed in the world
    /// with the ego's estimated pose ([`Sweep::estimated_pose`]), and heights are taken
    /// above the ground `params.ground` names (world z = 0, or the sweep's own estimated ground,
    /// [`GroundGrid`]). A non-finite point is an error.
    pub fn cut(sweep: &Sweep, params: &FeatureParams) -> Result<Self> {
        // The end points in the world frame.
        // The end points in the world frame of the ego's own pose estimate (a real car has no
        // other; the truth pose is for labels and metrics only).
        let points = points_in_world(sweep)?;
        let o = sweep.estimated_pose().translation.vector;
        let origin = [o.x, o.y, o.z];
        match params.ground {
            GroundMode::Flat => Ok(Self::above_flat(&points, origin, params)),
            GroundMode::Estimated => {
                // The ground under the sweep, from the sweep alone (thesis 6, future work).
                let ground =
                    GroundGrid::from_points_in_world(&points, [o.x, o.y], params.half_extent_m);
                // 2.1.1: the slice above it.
                Ok(Self::above(&points, origin, &ground, params))
            }
        }
    }

    /// Cuts a sweep above a given ground ([`Self::cut`] with `GroundMode::Estimated` is this
    /// with the sweep's own estimate).
    pub fn cut_above(sweep: &Sweep, ground: &GroundGrid, params: &FeatureParams) -> Result<Self> {
        let points = points_in_world(sweep)?;
        let o = sweep.estimated_pose().translation.vector;
        Ok(Self::above(&points, [o.x, o.y, o.z], ground, params))
    }

    /// The slice above the plane z = 0: one straight clip per beam (the thesis' flat road).
    fn above_flat(points: &[[f64; 3]], origin: [f64; 3], params: &FeatureParams) -> Self {
        let (zmin, zmax) = (params.slice_min_m, params.slice_max_m);
        let mut slice = Self::empty(origin);
        for (index, &end) in points.iter().enumerate() {
            let Some(interval) = clip_to_slab(origin[2], end[2], zmin, zmax) else {
                continue;
            };
            let hit = (zmin..=zmax).contains(&end[2]);
            slice.push(origin, end, index, &[interval], hit);
        }
        slice
    }

    /// The slice above `ground`: each beam in the pieces where it runs between `slice_min_m` and
    /// `slice_max_m` above the ground under it.
    fn above(
        points: &[[f64; 3]],
        origin: [f64; 3],
        ground: &GroundGrid,
        params: &FeatureParams,
    ) -> Self {
        let slab = SlabAboveGround::new(ground, origin, params.slice_min_m, params.slice_max_m);
        // Runs of points in parallel tasks, joined in point order: the beams and points of a
        // one-task loop.
        let parts: Vec<Self> = points
            .par_chunks(TASK_POINTS)
            .enumerate()
            .map(|(task, run)| {
                let mut part = Self::empty(origin);
                let mut intervals = Vec::new();
                for (k, &end) in run.iter().enumerate() {
                    intervals.clear();
                    let hit = slab.clip(end, &mut intervals);
                    part.push(origin, end, task * TASK_POINTS + k, &intervals, hit);
                }
                part
            })
            .collect();
        let mut slice = Self::empty(origin);
        slice
            .beams
            .reserve(parts.iter().map(|p| p.beams.len()).sum());
        slice
            .points
            .reserve(parts.iter().map(|p| p.points.len()).sum());
        for part in parts {
            slice.beams.extend(part.beams);
            slice.points.extend(part.points);
        }
        slice
    }

    fn empty(origin: [f64; 3]) -> Self {
        Self {
            sensor_xy: [origin[0], origin[1]],
            beams: Vec::new(),
            points: Vec::new(),
            counts: TracedCounts::default(),
        }
    }

    /// The beams' counts on a window holding `window` and where `window` starts in it: traced
    /// the first time a window of this cell size is asked for (with room for the next sweep's
    /// window), cut from those counts afterwards.
    pub(crate) fn counts_holding(&self, window: &GridWindow) -> (Arc<BeamCounts>, (usize, usize)) {
        self.counts.holding(&self.beams, window)
    }

    /// Adds the parts `intervals` (beam parameters, in order) of the beam to point `index`; the
    /// last part carries the hit if the end point lies in the slice.
    fn push(
        &mut self,
        origin: [f64; 3],
        end: [f64; 3],
        index: usize,
        intervals: &[(f64, f64)],
        hit: bool,
    ) {
        let at = |t: f64| {
            [
                origin[0] + t * (end[0] - origin[0]),
                origin[1] + t * (end[1] - origin[1]),
            ]
        };
        let last = intervals.len().saturating_sub(1);
        for (k, &(t0, t1)) in intervals.iter().enumerate() {
            self.beams.push(SlicedBeam {
                start_xy: at(t0),
                end_xy: at(t1),
                hit: hit && k == last,
            });
        }
        if hit {
            self.points.push(SlicedPoint {
                x_m: end[0],
                y_m: end[1],
                index,
            });
        }
    }
}

#[cfg(test)]
#[path = "slice_tests.rs"]
mod tests;
