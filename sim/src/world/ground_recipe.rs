//! What the ground of a street world is at a point: its height and material. Streets are
//! cambered from their crown, the sidewalk band is raised by the curb height (the sidewalk slabs
//! and their curb faces are boxes on top, see `street_furniture.rs`), and the terrain beyond has
//! hummocks on two scales and grass tufts; everything rides on gentle grade changes and a
//! short-wavelength roughness. [`GroundField`](super::GroundField) samples it on its grid.

use patchflow_dataset::SemanticClass;

use super::noise::ValueNoise;
use super::street_map::{LANE_OFFSET_M, StreetMap};
use crate::scenario::WorldKnobs;
use crate::seed::sub_seed;

/// Width of the terrain's rise from the sidewalk's edge to its full relief, metres.
const TERRAIN_RAMP_M: f64 = 5.0;

/// What a ground cell is made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub(crate) enum GroundMaterial {
    /// Asphalt of a carriageway.
    Road = 0,
    /// Paving of a sidewalk.
    Sidewalk = 1,
    /// Grass.
    Grass = 2,
    /// Gravel or bare soil.
    Gravel = 3,
}

impl GroundMaterial {
    pub(crate) fn semantic(self) -> SemanticClass {
        match self {
            Self::Road => SemanticClass::Road,
            Self::Sidewalk => SemanticClass::Sidewalk,
            Self::Grass | Self::Gravel => SemanticClass::Terrain,
        }
    }
}

/// What the street world's ground height depends on.
pub(crate) struct GroundRecipe<'a> {
    pub streets: &'a StreetMap,
    pub knobs: WorldKnobs,
    pub road_reflectivity: f64,
    pub seed: u64,
}

impl GroundRecipe<'_> {
    /// The gentle grade of the whole world at `p`, metres.
    pub(crate) fn base_m(&self, p: [f64; 2]) -> f64 {
        self.knobs.grade_m * ValueNoise::new(sub_seed(self.seed, 1), 160.0, 2).at(p[0], p[1])
    }

    /// Top of a sidewalk at `p` (the road's gutter plus the curb), metres.
    pub(crate) fn sidewalk_top_m(&self, p: [f64; 2], half_width_m: f64) -> f64 {
        self.base_m(p)
            + self.knobs.camber * (LANE_OFFSET_M - half_width_m)
            + self.knobs.curb_height_m
    }

    /// Height and material at `p`: road, sidewalk band or terrain by the distance to the nearest
    /// street's centre line.
    pub(super) fn sample(&self, p: [f64; 2], cell_m: f64) -> (f64, GroundMaterial, f64) {
        let k = &self.knobs;
        let rough = ValueNoise::new(sub_seed(self.seed, 2), 3.0, 2).at(p[0], p[1]);
        let patch = ValueNoise::new(sub_seed(self.seed, 3), 12.0, 2).at(p[0], p[1]);
        let base = self.base_m(p);
        let (d, w) = self
            .streets
            .nearest(p)
            .unwrap_or((f64::INFINITY, k.road_half_width_m));
        let road = base + k.camber * (LANE_OFFSET_M - d) + 0.5 * k.roughness_m * rough;
        let band = k.sidewalk_width_m.max(0.0);
        let raised = k.curb_height_m > 0.0 && band > 0.0;
        if d < w {
            let reflectivity = self.road_reflectivity * (1.0 + 0.3 * patch);
            return (road, GroundMaterial::Road, reflectivity);
        }
        let sidewalk = if raised {
            self.sidewalk_top_m(p, w) - 0.02
        } else {
            road
        };
        if d < w + band {
            // Right behind the curb the field stays at road level, so its rise to the sidewalk
            // happens under the sidewalk slab, never in front of the curb face.
            let z = if raised && d < w + cell_m {
                road
            } else {
                sidewalk
            };
            return (z, GroundMaterial::Sidewalk, 0.3 + 0.05 * patch);
        }
        let t = ((d - w - band) / TERRAIN_RAMP_M).min(1.0);
        let ramp = t * t * (3.0 - 2.0 * t);
        // Hummocks on two scales and grass tufts: at grazing incidence the beams land on the
        // faces of world-fixed bumps, not on rings that move with the sensor.
        let relief = 0.6 * ValueNoise::new(sub_seed(self.seed, 4), 30.0, 2).at(p[0], p[1])
            + 0.4 * ValueNoise::new(sub_seed(self.seed, 5), 6.0, 2).at(p[0], p[1]);
        let tufts = ValueNoise::new(sub_seed(self.seed, 6), 1.5, 2).at(p[0], p[1]);
        let z = sidewalk * (1.0 - ramp)
            + (base + k.terrain_relief_m * relief + 4.0 * k.roughness_m * tufts) * ramp
            + k.roughness_m * rough;
        if patch > 0.25 {
            (z, GroundMaterial::Gravel, 0.25 + 0.1 * rough)
        } else {
            (z, GroundMaterial::Grass, 0.45 + 0.1 * rough)
        }
    }
}
