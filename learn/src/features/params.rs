//! Parameters of the feature pipeline with the thesis defaults (SPEC §5, thesis 2.1-2.2 and 4.3).

use crate::features::grid::GridWindow;
use crate::{LearnError, Result};

/// Every knob of the feature pipeline; `Default` gives the thesis values.
///
/// ```
/// let params = patchflow_learn::FeatureParams::default();
/// assert_eq!(params.cell_m, 0.10);
/// assert_eq!(params.prior, 0.5);
/// let checked = params.check().unwrap();
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct FeatureParams {
    /// Lower edge of the height slice above the ground, metres (thesis 2.1.1: 0.5 m).
    pub slice_min_m: f64,
    /// Upper edge of the height slice above the ground, metres (thesis 2.1.1: 1.0 m).
    pub slice_max_m: f64,
    /// Which ground the slice is measured from: the world plane z = 0 (the thesis' flat road) or
    /// the ground estimated from each sweep (the thesis' future work, 6).
    pub ground: GroundMode,
    /// Side of a map cell, metres (thesis 4.3: 0.10 m): the maps the clusters' cells, the
    /// moving classifier and the map views read.
    pub cell_m: f64,
    /// Side of a cell of the maps the motion patches sample, metres. The thesis samples its
    /// 11 × 11 patches from the maps themselves (`cell_m`, so 1.1 m patches); another value
    /// builds a second pair of maps for the patches alone, whose 11 × 11 samples then reach
    /// further (0.20 m cells: 2.2 m patches, by the thesis' rule of 2-10 m/s for 0.10 m cells
    /// at 10 Hz, 4.3, the motion of 4-20 m/s). The estimator predicts once per occupied cell of
    /// these maps.
    pub patch_cell_m: f64,
    /// Half the side of the square map window centred on the ego sensor, metres. 40 m covers the
    /// thesis' usable range ("about 40 to 50 metres", 4.1) and gives 800 × 800 cells.
    pub half_extent_m: f64,
    /// Occupancy of cells no sliced beam touched (thesis 2.1.2: 0.5, or the learned 0.01).
    pub prior: f64,
    /// Share of each hit or miss given to each side neighbour per axis (the rest stays in the
    /// cell). With 1/6 a hit keeps 4/9 of its mass, each edge neighbour gets 1/9 and each corner
    /// neighbour 1/36: the separable kernel `[1/6, 2/3, 1/6] ⊗ [1/6, 2/3, 1/6]` (thesis 2.1.1,
    /// "some mass of the hits and misses was spread to neighboring cells").
    pub spread: f64,
    /// Single-link cut: points closer than this (in x, y) share a cluster. The thesis gives no
    /// value; 0.5 m keeps an HDL-64E's points on a car at 40 m together (ring spacing there about
    /// 0.23 m, azimuth spacing 0.14 m) while a car passing a wall at more than 0.5 m stays apart.
    pub cluster_gap_m: f64,
    /// Training only: standard deviation of the Gaussian error added to the true heading that a
    /// training speed patch is aligned to, degrees; 0 aligns to the exact true heading (thesis
    /// 2.2.2). At run time speed patches follow the *estimated* heading (thesis 3.1.1), whose
    /// error the thesis names as the main cause of bad speeds (4.4, situation 2); a speed GP
    /// that only ever saw exactly aligned patches reads a car 30° off its axis as nearly still.
    /// 25° is about the merged-heading RMSE the thesis reports on real data (Tables 4.6-4.14:
    /// 8.7° to 24°). Measured effect in docs/estimator.md.
    pub speed_jitter_deg: f64,
    /// Gabor filter bank (thesis 2.2.3).
    pub gabor: GaborParams,
}

impl Default for FeatureParams {
    fn default() -> Self {
        Self {
            slice_min_m: 0.5,
            slice_max_m: 1.0,
            ground: GroundMode::Estimated,
            cell_m: 0.10,
            patch_cell_m: 0.10,
            half_extent_m: 40.0,
            prior: 0.5,
            spread: 1.0 / 6.0,
            cluster_gap_m: 0.5,
            speed_jitter_deg: 25.0,
            gabor: GaborParams::default(),
        }
    }
}

/// Most cells along a side of the map window: 2,000 (25 times the thesis' 800 × 800 cells in
/// area) keep the maps of one sweep pair near 0.26 GB.
pub const MAX_MAP_SIDE_CELLS: f64 = 2000.0;

/// Memory per map cell while a sweep pair's maps are built, bytes: hits and misses of both
/// sweeps (f32), reflection and difference values (f64), and the spread's scratch rows, rounded up.
const MAP_BYTES_PER_CELL: f64 = 64.0;

impl FeatureParams {
    /// The map window of a sweep: centred on its sensor, `half_extent_m` each way, `cell_m`
    /// cells. Built once per sweep and handed to the maps, the points and the clusters.
    pub fn map_window(&self, sensor_xy: [f64; 2]) -> GridWindow {
        GridWindow::centred(sensor_xy, self.half_extent_m, self.cell_m)
    }

    /// The window of the maps the patches sample: [`Self::map_window`] with cells of
    /// `patch_cell_m` (the same window when both cells are equal).
    pub fn patch_window(&self, sensor_xy: [f64; 2]) -> GridWindow {
        GridWindow::centred(sensor_xy, self.half_extent_m, self.patch_cell_m)
    }

    /// Whether the patches sample maps of their own ([`Self::patch_cell_m`] differs from
    /// [`Self::cell_m`]).
    pub fn has_patch_maps(&self) -> bool {
        self.patch_cell_m != self.cell_m
    }

    /// These parameters with the patch cell as the map cell: the maps of a pipeline that needs
    /// only patches (the training sampler) are the patch maps.
    pub fn patch_only(&self) -> Self {
        Self {
            cell_m: self.patch_cell_m,
            ..self.clone()
        }
    }

    /// These parameters without patch maps of their own (the patch cell set to the map cell):
    /// for a pipeline that reads the maps but no patches (the moving classifier).
    pub fn without_patch_maps(&self) -> Self {
        Self {
            patch_cell_m: self.cell_m,
            ..self.clone()
        }
    }

    /// Cells along a side of the map window.
    pub fn map_side_cells(&self) -> f64 {
        (2.0 * self.half_extent_m / self.cell_m).ceil()
    }

    /// The defaults with another map prior (the thesis compares 0.5 and 0.01).
    pub fn with_prior(prior: f64) -> Self {
        Self {
            prior,
            ..Self::default()
        }
    }

    /// Checks ranges; [`Self::check`] runs this once at the boundary, and every stage below
    /// takes the checked [`FeatureValidParams`](crate::FeatureValidParams).
    pub(crate) fn validate(&self) -> Result<()> {
        let bad = |what: &str| Err(LearnError::invalid_params(what.to_owned()));
        let finite = [
            self.slice_min_m,
            self.slice_max_m,
            self.cell_m,
            self.patch_cell_m,
            self.half_extent_m,
            self.prior,
            self.spread,
            self.cluster_gap_m,
            self.speed_jitter_deg,
        ]
        .iter()
        .all(|v| v.is_finite());
        if !finite {
            return bad("every feature parameter must be finite");
        }
        if self.slice_min_m >= self.slice_max_m {
            return bad("slice_min_m must be below slice_max_m");
        }
        if !(0.01..=2.0).contains(&self.cell_m) {
            return bad(&format!(
                "cell_m = {} m is outside 0.01 to 2 m (the thesis uses 0.10 m)",
                self.cell_m
            ));
        }
        if !(0.01..=2.0).contains(&self.patch_cell_m) {
            return bad(&format!(
                "patch_cell_m = {} m is outside 0.01 to 2 m (the thesis samples its patches from the maps themselves: patch_cell_m = cell_m = 0.10 m)",
                self.patch_cell_m
            ));
        }
        if !(1.0..=500.0).contains(&self.half_extent_m) {
            return bad(&format!(
                "half_extent_m = {} m is outside 1 to 500 m (maps cover at least 40 m around the ego)",
                self.half_extent_m
            ));
        }
        let finest_m = self.cell_m.min(self.patch_cell_m);
        let side = (2.0 * self.half_extent_m / finest_m).ceil();
        if side > MAX_MAP_SIDE_CELLS {
            let gb = |cells: f64| cells * MAP_BYTES_PER_CELL / 1e9;
            return bad(&format!(
                "cells of {} m and half_extent_m = {} m give maps of {side:.0} × {side:.0} cells, about {:.1} GB per sweep pair; at most {MAX_MAP_SIDE_CELLS} cells a side ({:.2} GB)",
                finest_m,
                self.half_extent_m,
                gb(side * side),
                gb(MAX_MAP_SIDE_CELLS * MAX_MAP_SIDE_CELLS)
            ));
        }
        if !(0.0..=1.0).contains(&self.prior) {
            return bad("prior must lie in [0, 1]");
        }
        if !(0.0..0.5).contains(&self.spread) {
            return bad("spread must lie in [0, 0.5)");
        }
        if self.cluster_gap_m <= 0.0 {
            return bad("cluster_gap_m must be positive");
        }
        if !(0.0..=90.0).contains(&self.speed_jitter_deg) {
            return bad("speed_jitter_deg must lie in [0, 90]");
        }
        self.gabor.validate()
    }
}

/// The ground the height slice is measured from (thesis 2.1.1 assumes a flat road; 6 names ground
/// extraction as future work).
///
/// ```
/// use patchflow_learn::GroundMode;
/// assert_eq!(GroundMode::default(), GroundMode::Estimated);
/// assert_eq!(GroundMode::parse("flat"), Some(GroundMode::Flat));
/// assert_eq!(GroundMode::Estimated.name(), "estimated");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum GroundMode {
    /// The world plane z = 0: right for the `ideal` world, wrong on cambered and sloped roads.
    Flat,
    /// A height field estimated from each sweep's own points ([`GroundGrid`](crate::GroundGrid)).
    #[default]
    Estimated,
}

impl GroundMode {
    /// Every mode, in a fixed order.
    pub const ALL: [Self; 2] = [Self::Flat, Self::Estimated];

    /// The name written into model files and accepted on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Flat => "flat",
            Self::Estimated => "estimated",
        }
    }

    /// The mode called `name`, if any.
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// Shape of the Gabor filters (thesis Eq. 2.15, with the envelope *times* the cosine).
///
/// The orientations are fixed: 16 angles `2πk/16` over the full circle, phase offset π/2, so each
/// filter is odd along its axis: one lobe behind and one of opposite sign ahead, like the loss
/// and gain a moving car leaves on the difference map.
///
/// How the defaults were chosen (as the thesis did, by maximising the bank's response on a test
/// set): a car 14 m away approaching at 5 m/s (0.5 m per sweep) on synthetic sweeps, ego moving
/// 0.5 m, mean bank energy (sum of squared responses, unit-length filters) over the car's heading
/// patches, for λ ∈ {0.4 … 3.0} m and σ ∈ {0.15 … 0.6} m. With σ = 0.3 m: λ = 0.4: 0.7,
/// 0.6: 6.5, 0.8: 13.5, 1.0: 16.5, 1.2: 17.3, 2.0: 17.1, 3.0: 16.8. Beyond λ ≈ 1.2 m the
/// cosine is a ramp under the envelope (the filter becomes a derivative of a Gaussian) and the
/// energy stops growing; σ = 0.3 m was among the best at 5 and 10 m/s alike. A static wall of the
/// car's size gives about 1/230 of that energy. γ = 0.5 stretches the filter along the loss and
/// gain bands, which on a car's face are wider than deep. Tests:
/// `gabor::tests::a_moving_box_patch_excites_the_bank_far_more_than_a_static_wall` and
/// `gabor::tests::the_chosen_wavelength_is_near_the_best_for_a_half_metre_move`.
#[derive(Debug, Clone, PartialEq)]
pub struct GaborParams {
    /// Wavelength λ of the cosine, metres.
    pub wavelength_m: f64,
    /// Standard deviation σ of the Gaussian envelope, metres.
    pub sigma_m: f64,
    /// Spatial aspect ratio γ (ellipticity of the envelope).
    pub gamma: f64,
}

impl Default for GaborParams {
    fn default() -> Self {
        Self {
            wavelength_m: 1.2,
            sigma_m: 0.3,
            gamma: 0.5,
        }
    }
}

impl GaborParams {
    /// Checks that every value is positive and finite.
    pub fn validate(&self) -> Result<()> {
        let ok = [self.wavelength_m, self.sigma_m, self.gamma]
            .iter()
            .all(|v| v.is_finite() && *v > 0.0);
        if ok {
            Ok(())
        } else {
            Err(LearnError::invalid_params(
                "Gabor wavelength, sigma and gamma must be positive".into(),
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_are_valid_and_follow_the_thesis() {
        let p = FeatureParams::default();
        p.validate().unwrap();
        assert_eq!((p.slice_min_m, p.slice_max_m), (0.5, 1.0));
        assert_eq!(p.ground, GroundMode::Estimated);
        assert!((p.half_extent_m / p.cell_m - 400.0).abs() < 1e-9);
    }

    #[test]
    fn patches_sample_the_maps_themselves_by_default_as_the_thesis_does() {
        let p = FeatureParams::default();
        assert!(!p.has_patch_maps());
        assert_eq!(p.patch_window([3.0, 4.0]), p.map_window([3.0, 4.0]));
    }

    #[test]
    fn a_patch_map_too_fine_for_memory_is_refused_too() {
        let p = FeatureParams {
            patch_cell_m: 0.011,
            ..FeatureParams::default()
        };
        let err = p.validate().unwrap_err().to_string();
        assert!(err.contains("7273 × 7273 cells"), "{err}");
    }

    #[test]
    fn a_prior_outside_the_unit_interval_is_rejected() {
        assert!(FeatureParams::with_prior(1.5).validate().is_err());
        FeatureParams::with_prior(0.01).validate().unwrap();
    }

    #[test]
    fn a_map_too_fine_for_memory_is_refused_with_the_estimate() {
        let p = FeatureParams {
            cell_m: 0.011,
            ..FeatureParams::default()
        };
        let err = p.validate().unwrap_err().to_string();
        assert!(
            err.contains("7273 × 7273 cells") && err.contains("GB"),
            "{err}"
        );
    }

    #[test]
    fn a_negative_speed_jitter_is_rejected() {
        let p = FeatureParams {
            speed_jitter_deg: -1.0,
            ..FeatureParams::default()
        };
        assert!(p.validate().is_err());
    }

    #[test]
    fn every_ground_mode_parses_back_from_its_name() {
        for mode in GroundMode::ALL {
            assert_eq!(GroundMode::parse(mode.name()), Some(mode));
        }
        assert_eq!(GroundMode::parse("level"), None);
    }

    #[test]
    fn an_inverted_slice_is_rejected() {
        let p = FeatureParams {
            slice_min_m: 1.0,
            slice_max_m: 0.5,
            ..FeatureParams::default()
        };
        assert!(p.validate().is_err());
    }
}
