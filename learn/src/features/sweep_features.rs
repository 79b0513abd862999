//! One sweep's motion features (thesis Chapter 2 end to end): the height slice, the reflection
//! and difference maps, the clusters, and patches and Gabor responses on demand.

use std::time::Instant;

use patchflow_dataset::Sweep;
use rayon::prelude::*;

use crate::features::cell_samples::CellSamples;
use crate::features::cluster::Clusters;
use crate::features::cluster_shape::ClusterShape;
use crate::features::difference_map::MapPair;
use crate::features::feature_kind::FeatureKind;
use crate::features::gabor::{GABOR_FILTERS, GaborBank};
use crate::features::grid::{GridMap, GridWindow};
use crate::features::patch::{PATCH_LEN, Patch};
use crate::features::slice::{HeightSlice, SlicedPoint};
use crate::timing::timed;
use crate::{FeatureParams, FeatureValidParams, Result};

/// The features of the current sweep given the previous one. Point indices `i` below index
/// [`Self::points`], the sliced end points inside the map window; `points()[i].index` is the
/// index into the sweep's own arrays.
///
/// ```
/// use patchflow_learn::{FeatureParams, SweepFeatures};
/// use patchflow_learn::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
/// let scene = SyntheticScene { boxes: vec![SceneBox::car(1, [12.0, 0.0], 3.14, 5.0)] };
/// let lidar = SyntheticLidar::with_resolution(32, 720);
/// let prev = scene.scan(&lidar, [0.0, 0.0], 0.0, 0);
/// let curr = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
/// let features = SweepFeatures::compute(&prev, &curr, &FeatureParams::default()).unwrap();
/// assert_eq!(features.clusters().len(), 1);
/// let patch = features.heading_patch(0);
/// assert!(patch.mean_abs_difference() > 0.0);
/// ```
#[derive(Debug, Clone)]
pub struct SweepFeatures {
    sensor_xy: [f64; 2],
    points: Vec<SlicedPoint>,
    clusters: Clusters,
    maps: MapPair,
    /// The maps the patches sample when their cells differ from the maps'
    /// ([`FeatureParams::patch_cell_m`]); `None`: the patches sample `maps` (the thesis).
    patch_maps: Option<MapPair>,
    gabor: GaborBank,
    params: FeatureParams,
    timing: FeatureTiming,
}

/// What the feature pipeline of one scan cost, seconds of wall time.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FeatureTiming {
    /// Height slice of the sweeps cut for this scan (both, or only the current one in a stream).
    pub slice_secs: f64,
    /// Reflection and difference maps (thesis 2.1), measured inside their parallel branch.
    pub maps_secs: f64,
    /// End points in the window and their single-link clusters (thesis 2.2.1), measured inside
    /// their parallel branch.
    pub clusters_secs: f64,
    /// Maps and clusters together, as they run side by side.
    pub maps_and_clusters_secs: f64,
}

impl SweepFeatures {
    /// Runs the per-sweep pipeline on two consecutive sweeps (checking `params` first; a loop
    /// over sweeps checks them once and calls [`Self::compute_checked`]).
    pub fn compute(prev: &Sweep, curr: &Sweep, params: &FeatureParams) -> Result<Self> {
        Self::compute_checked(prev, curr, &params.check()?)
    }

    /// [`Self::compute`] with parameters checked beforehand.
    pub fn compute_checked(
        prev: &Sweep,
        curr: &Sweep,
        params: &FeatureValidParams,
    ) -> Result<Self> {
        let start = Instant::now();
        // 2.1.1: cut both sweeps to the height slice.
        let (prev_slice, curr_slice) = rayon::join(
            || HeightSlice::cut(prev, params),
            || HeightSlice::cut(curr, params),
        );
        let (prev_slice, curr_slice) = (prev_slice?, curr_slice?);
        let slice_secs = start.elapsed().as_secs_f64();
        let mut features = Self::from_slices(&prev_slice, &curr_slice, params)?;
        features.set_slice_secs(slice_secs);
        Ok(features)
    }

    /// The pipeline after the height slice, on both sweeps' slices (a [`ScanStream`](crate::ScanStream)
    /// cuts each sweep once and hands its slice on to the next scan).
    pub fn from_slices(
        prev_slice: &HeightSlice,
        curr_slice: &HeightSlice,
        params: &FeatureValidParams,
    ) -> Result<Self> {
        let start = Instant::now();
        // 2.1.1 and 2.1.2, Eq. 2.8-2.9: both reflection maps on the current window, their
        // difference (and the same on the patches' own cells when they differ); in
        // parallel, 2.2.1: single-link clusters of the end points the maps cover.
        let window = params.map_window(curr_slice.sensor_xy);
        let (mut maps_secs, mut clusters_secs) = (0.0, 0.0);
        let ((maps, patch_maps), (points, clusters)) = rayon::join(
            || {
                timed(&mut maps_secs, || {
                    let patch_maps = || {
                        params.has_patch_maps().then(|| {
                            let patch_window = params.patch_window(curr_slice.sensor_xy);
                            MapPair::build(prev_slice, curr_slice, patch_window, params)
                        })
                    };
                    rayon::join(
                        || MapPair::build(prev_slice, curr_slice, window, params),
                        patch_maps,
                    )
                })
            },
            || {
                timed(&mut clusters_secs, || {
                    let points = points_in_window(curr_slice, &window);
                    let xy: Vec<[f64; 2]> = points.iter().map(|p| [p.x_m, p.y_m]).collect();
                    let clusters = Clusters::single_link(&xy, params.cluster_gap_m);
                    (points, clusters)
                })
            },
        );
        Ok(Self {
            sensor_xy: curr_slice.sensor_xy,
            points,
            clusters,
            maps,
            patch_maps,
            gabor: GaborBank::new(&params.gabor, params.patch_cell_m),
            params: params.params().clone(),
            timing: FeatureTiming {
                slice_secs: 0.0,
                maps_secs,
                clusters_secs,
                maps_and_clusters_secs: start.elapsed().as_secs_f64(),
            },
        })
    }

    /// The features of a current slice from maps built elsewhere (the training sampler builds
    /// the maps of several priors at once, on one window), without clusters: [`Self::clusters`]
    /// is empty. The patches sample `maps` (`params` as [`FeatureParams::patch_only`] gives
    /// them).
    pub(crate) fn without_clusters(
        curr_slice: &HeightSlice,
        maps: MapPair,
        params: FeatureParams,
        gabor: GaborBank,
    ) -> Self {
        Self {
            sensor_xy: curr_slice.sensor_xy,
            points: points_in_window(curr_slice, maps.reflection.window()),
            clusters: Clusters::default(),
            maps,
            patch_maps: None,
            gabor,
            params,
            timing: FeatureTiming::default(),
        }
    }

    /// The feature parameters these features were computed with.
    pub fn params(&self) -> &FeatureParams {
        &self.params
    }

    /// The sliced end points inside the map window, in sweep order.
    pub fn points(&self) -> &[SlicedPoint] {
        &self.points
    }

    /// Number of sliced points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True if no end point fell into the slice.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Sensor position of the current sweep, world x, y.
    pub fn sensor_xy(&self) -> [f64; 2] {
        self.sensor_xy
    }

    /// The single-link clusters of the points (ids follow the smallest member).
    pub fn clusters(&self) -> &Clusters {
        &self.clusters
    }

    /// Ids of the clusters that can be one object (thesis 3.1, step 1: "each cluster is taken as
    /// a dynamic object hypothesis"), leaving out those longer than any road user (building
    /// fronts, walls and fences) and those of a handful of points
    /// ([`ClusterShape::is_object_hypothesis`]).
    pub fn object_hypotheses(&self) -> Vec<usize> {
        (0..self.clusters.len())
            .filter(|&c| self.cluster_shape(c).is_object_hypothesis())
            .collect()
    }

    /// Extent of cluster `c` along its principal axes.
    pub fn cluster_shape(&self, c: usize) -> ClusterShape {
        let members = self.clusters.members(c);
        ClusterShape::of(
            members
                .iter()
                .map(|&i| [self.points[i].x_m, self.points[i].y_m]),
        )
    }

    /// What computing these features cost.
    pub fn timing(&self) -> FeatureTiming {
        self.timing
    }

    /// Records the time the height slice took where it was cut (a stream cuts it beforehand).
    pub(crate) fn set_slice_secs(&mut self, slice_secs: f64) {
        self.timing.slice_secs = slice_secs;
    }

    /// Cluster id of point `i`.
    pub fn cluster_of(&self, i: usize) -> usize {
        self.clusters.cluster_of(i)
    }

    /// Reflection map of the current sweep.
    pub fn reflection_map(&self) -> &GridMap {
        &self.maps.reflection
    }

    /// Difference map, current minus previous.
    pub fn difference_map(&self) -> &GridMap {
        &self.maps.difference
    }

    /// Bearing of sensor → point `i` in the world frame, counter-clockwise from +x.
    pub fn bearing_rad(&self, i: usize) -> f64 {
        let p = &self.points[i];
        self.bearing_at([p.x_m, p.y_m])
    }

    /// Bearing of sensor → a world position, counter-clockwise from +x.
    pub fn bearing_at(&self, xy: [f64; 2]) -> f64 {
        (xy[1] - self.sensor_xy[1]).atan2(xy[0] - self.sensor_xy[0])
    }

    /// Patch of point `i` rotated to the axis `axis_rad` (thesis 2.2.2).
    pub fn patch_along(&self, i: usize, axis_rad: f64) -> Patch {
        let p = &self.points[i];
        self.patch_at([p.x_m, p.y_m], axis_rad)
    }

    /// The maps the patches sample: their own on cells of [`FeatureParams::patch_cell_m`], or
    /// the maps themselves.
    pub(super) fn patch_source(&self) -> &MapPair {
        self.patch_maps.as_ref().unwrap_or(&self.maps)
    }

    /// Patch centred on a world position, rotated to the axis `axis_rad` (thesis 2.2.2).
    pub fn patch_at(&self, xy: [f64; 2], axis_rad: f64) -> Patch {
        Patch::extract(self.patch_source(), xy, axis_rad)
    }

    /// [`SweepFeatures::patch_at`] written into `values` (a row of a GP input buffer).
    pub fn patch_values_at(&self, xy: [f64; 2], axis_rad: f64, values: &mut [f64; PATCH_LEN]) {
        Patch::extract_into(self.patch_source(), xy, axis_rad, values);
    }

    /// The world positions (x, y) of points `members`, in their order.
    pub fn positions_xy(&self, members: &[usize]) -> Vec<[f64; 2]> {
        members
            .iter()
            .map(|&i| [self.points[i].x_m, self.points[i].y_m])
            .collect()
    }

    /// The members of a cluster grouped by map cell, one sample at the mean of each cell's points
    /// (see `CellSamples`).
    pub fn cell_samples(&self, members: &[usize]) -> CellSamples {
        CellSamples::group(&self.points, members, self.maps.reflection.window())
    }

    /// The members of a cluster grouped by cell of the patches' maps (the maps' own cells unless
    /// [`FeatureParams::patch_cell_m`] differs): where the estimator predicts, once per cell
    /// its patches resolve.
    pub fn patch_cell_samples(&self, members: &[usize]) -> CellSamples {
        CellSamples::group(
            &self.points,
            members,
            self.patch_source().reflection.window(),
        )
    }

    /// Heading patch: aligned to the observation direction sensor → point.
    pub fn heading_patch(&self, i: usize) -> Patch {
        self.patch_along(i, self.bearing_rad(i))
    }

    /// Speed patch: aligned to a heading (the true one in training, the predicted one at run time).
    pub fn speed_patch(&self, i: usize, heading_rad: f64) -> Patch {
        self.patch_along(i, heading_rad)
    }

    /// Heading patches of many points, in parallel, in the order given.
    pub fn heading_patches(&self, indices: &[usize]) -> Vec<Patch> {
        indices.par_iter().map(|&i| self.heading_patch(i)).collect()
    }

    /// Gabor responses of a patch's difference half (thesis 2.2.3).
    pub fn gabor(&self, patch: &Patch) -> [f64; GABOR_FILTERS] {
        self.gabor.responses(patch)
    }

    /// The feature vector of a patch: its values or its Gabor responses.
    pub fn feature_of(&self, patch: &Patch, kind: FeatureKind) -> Vec<f64> {
        match kind {
            FeatureKind::Patch => patch.values.to_vec(),
            FeatureKind::Gabor => self.gabor(patch).to_vec(),
        }
    }
}

/// The sliced end points inside the map window.
fn points_in_window(curr_slice: &HeightSlice, window: &GridWindow) -> Vec<SlicedPoint> {
    curr_slice
        .points
        .iter()
        .filter(|p| window.cell_of(p.x_m, p.y_m).is_some())
        .copied()
        .collect()
}

#[cfg(test)]
#[path = "sweep_features_tests.rs"]
mod tests;
