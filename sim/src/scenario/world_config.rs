//! The `[world]` table: what the world around the roads looks like. Every knob is optional; a
//! missing one takes the value of the scenario's realism rung, so the resolved scenario states
//! them all. Zero switches a feature off.

use serde::{Deserialize, Serialize};

use super::bounds::Bound;
use super::realism::Realism;

/// Knobs of the procedural street world, as written in a scenario file.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorldConfig {
    /// Cross slope of the road from its crown to the curb (0.02 = 2 %).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camber: Option<f64>,
    /// Height of the curb above the gutter, metres (0: no curbs, no raised sidewalks).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curb_height_m: Option<f64>,
    /// Width of the sidewalk behind each curb, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sidewalk_width_m: Option<f64>,
    /// Half width of a street's carriageway (centre line to curb), metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub road_half_width_m: Option<f64>,
    /// Amplitude of the gentle grade changes of the whole ground, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grade_m: Option<f64>,
    /// Amplitude of the low-frequency relief of the terrain beyond the sidewalks, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub terrain_relief_m: Option<f64>,
    /// Amplitude of the short-wavelength roughness of every ground surface, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness_m: Option<f64>,
    /// Street clutter density (trees, bushes, signs, bollards, traffic lights, bins); 1 = a
    /// typical city street, 0 = none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clutter: Option<f64>,
    /// Parked cars per 100 m of each street side.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parked_cars_per_100m: Option<f64>,
    /// Building façades with piers, floor bands, recessed glass and balconies instead of flat boxes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub facade_detail: Option<bool>,
    /// Vehicles, cyclists and pedestrians as compound shapes instead of boxes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shapes: Option<bool>,
    /// Cars and trucks without an explicit `size_m` get their dimensions and belt-line height
    /// drawn per vehicle from published fleet statistics (`VehicleBody`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fleet: Option<bool>,
}

/// The resolved `[world]` knobs as plain values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldKnobs {
    /// See [`WorldConfig::camber`].
    pub camber: f64,
    /// See [`WorldConfig::curb_height_m`].
    pub curb_height_m: f64,
    /// See [`WorldConfig::sidewalk_width_m`].
    pub sidewalk_width_m: f64,
    /// See [`WorldConfig::road_half_width_m`].
    pub road_half_width_m: f64,
    /// See [`WorldConfig::grade_m`].
    pub grade_m: f64,
    /// See [`WorldConfig::terrain_relief_m`].
    pub terrain_relief_m: f64,
    /// See [`WorldConfig::roughness_m`].
    pub roughness_m: f64,
    /// See [`WorldConfig::clutter`].
    pub clutter: f64,
    /// See [`WorldConfig::parked_cars_per_100m`].
    pub parked_cars_per_100m: f64,
    /// See [`WorldConfig::facade_detail`].
    pub facade_detail: bool,
    /// See [`WorldConfig::shapes`].
    pub shapes: bool,
    /// See [`WorldConfig::fleet`].
    pub fleet: bool,
}

impl WorldKnobs {
    /// The knobs of a rung.
    pub fn of(rung: Realism) -> Self {
        match rung {
            Realism::Ideal => Self {
                camber: 0.0,
                curb_height_m: 0.0,
                sidewalk_width_m: 0.0,
                road_half_width_m: 6.0,
                grade_m: 0.0,
                terrain_relief_m: 0.0,
                roughness_m: 0.0,
                clutter: 0.0,
                parked_cars_per_100m: 0.0,
                facade_detail: false,
                shapes: false,
                fleet: false,
            },
            Realism::Urban => Self {
                camber: 0.02,
                curb_height_m: 0.13,
                sidewalk_width_m: 3.0,
                road_half_width_m: 6.0,
                grade_m: 0.15,
                terrain_relief_m: 0.4,
                roughness_m: 0.02,
                clutter: 1.0,
                parked_cars_per_100m: 15.0,
                facade_detail: true,
                shapes: true,
                fleet: true,
            },
            Realism::Harsh => Self {
                camber: 0.03,
                curb_height_m: 0.15,
                sidewalk_width_m: 3.0,
                road_half_width_m: 6.0,
                grade_m: 0.3,
                terrain_relief_m: 0.8,
                roughness_m: 0.04,
                clutter: 2.0,
                parked_cars_per_100m: 16.0,
                facade_detail: true,
                shapes: true,
                fleet: true,
            },
        }
    }

    /// True if the ground is the flat plane z = 0 of the first release.
    pub fn flat_ground(&self) -> bool {
        self.camber == 0.0
            && self.curb_height_m == 0.0
            && self.grade_m == 0.0
            && self.terrain_relief_m == 0.0
            && self.roughness_m == 0.0
    }
}

impl WorldConfig {
    /// Fills every missing knob from `rung`.
    pub(crate) fn resolve(&mut self, rung: Realism) {
        let k = WorldKnobs::of(rung);
        self.camber.get_or_insert(k.camber);
        self.curb_height_m.get_or_insert(k.curb_height_m);
        self.sidewalk_width_m.get_or_insert(k.sidewalk_width_m);
        self.road_half_width_m.get_or_insert(k.road_half_width_m);
        self.grade_m.get_or_insert(k.grade_m);
        self.terrain_relief_m.get_or_insert(k.terrain_relief_m);
        self.roughness_m.get_or_insert(k.roughness_m);
        self.clutter.get_or_insert(k.clutter);
        self.parked_cars_per_100m
            .get_or_insert(k.parked_cars_per_100m);
        self.facade_detail.get_or_insert(k.facade_detail);
        self.shapes.get_or_insert(k.shapes);
        self.fleet.get_or_insert(k.fleet);
    }

    /// The knobs as plain values (those still missing from the `urban` rung).
    pub fn knobs(&self) -> WorldKnobs {
        let k = WorldKnobs::of(Realism::Urban);
        WorldKnobs {
            camber: self.camber.unwrap_or(k.camber),
            curb_height_m: self.curb_height_m.unwrap_or(k.curb_height_m),
            sidewalk_width_m: self.sidewalk_width_m.unwrap_or(k.sidewalk_width_m),
            road_half_width_m: self.road_half_width_m.unwrap_or(k.road_half_width_m),
            grade_m: self.grade_m.unwrap_or(k.grade_m),
            terrain_relief_m: self.terrain_relief_m.unwrap_or(k.terrain_relief_m),
            roughness_m: self.roughness_m.unwrap_or(k.roughness_m),
            clutter: self.clutter.unwrap_or(k.clutter),
            parked_cars_per_100m: self.parked_cars_per_100m.unwrap_or(k.parked_cars_per_100m),
            facade_detail: self.facade_detail.unwrap_or(k.facade_detail),
            shapes: self.shapes.unwrap_or(k.shapes),
            fleet: self.fleet.unwrap_or(k.fleet),
        }
    }

    /// Every knob outside its range, with the field's name.
    pub(crate) fn problems(&self) -> Vec<(&'static str, String)> {
        let k = self.knobs();
        [
            CAMBER.check("camber", k.camber),
            CURB_HEIGHT_M.check("curb_height_m", k.curb_height_m),
            SIDEWALK_WIDTH_M.check("sidewalk_width_m", k.sidewalk_width_m),
            ROAD_HALF_WIDTH_M.check("road_half_width_m", k.road_half_width_m),
            GRADE_M.check("grade_m", k.grade_m),
            TERRAIN_RELIEF_M.check("terrain_relief_m", k.terrain_relief_m),
            ROUGHNESS_M.check("roughness_m", k.roughness_m),
            CLUTTER.check("clutter", k.clutter),
            PARKED_CARS_PER_100M.check("parked_cars_per_100m", k.parked_cars_per_100m),
        ]
        .into_iter()
        .flatten()
        .collect()
    }
}

// Documented in scenarios/README.md ("The realism ladder"); change both together.

/// Cross slope of a road.
const CAMBER: Bound = Bound::new(0.0, 0.1, "", "real roads slope 1.5-3 % to the gutter");
/// Curb height.
const CURB_HEIGHT_M: Bound =
    Bound::new(0.0, 0.3, "m", "curbs stand 0.1-0.2 m; 0 switches them off");
/// Sidewalk width.
const SIDEWALK_WIDTH_M: Bound = Bound::new(0.0, 10.0, "m", "from none to a wide promenade");
/// Half width of a carriageway.
pub(crate) const ROAD_HALF_WIDTH_M: Bound =
    Bound::new(3.0, 15.0, "m", "one lane to a four-lane avenue each way");
/// Amplitude of the grade changes.
const GRADE_M: Bound = Bound::new(0.0, 2.0, "m", "gentle grade changes over 160 m, not hills");
/// Amplitude of the terrain relief.
const TERRAIN_RELIEF_M: Bound = Bound::new(0.0, 3.0, "m", "hummocks and verges, not hills");
/// Amplitude of the surface roughness.
const ROUGHNESS_M: Bound = Bound::new(0.0, 0.2, "m", "potholes and tufts, not relief");
/// Clutter density.
const CLUTTER: Bound = Bound::new(0.0, 5.0, "", "up to five times a typical city street");
/// Parked cars per 100 m.
const PARKED_CARS_PER_100M: Bound = Bound::new(0.0, 20.0, "", "a car every 5 m fills a curb");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ideal_rung_has_a_flat_ground_and_the_others_do_not() {
        assert!(WorldKnobs::of(Realism::Ideal).flat_ground());
        assert!(!WorldKnobs::of(Realism::Urban).flat_ground());
        assert!(!WorldKnobs::of(Realism::Harsh).flat_ground());
    }

    #[test]
    fn a_knob_set_alone_survives_resolution_and_the_rest_come_from_the_rung() {
        let mut config = WorldConfig {
            camber: Some(0.05),
            ..WorldConfig::default()
        };
        config.resolve(Realism::Ideal);
        let k = config.knobs();
        assert_eq!(k.camber, 0.05);
        assert_eq!(k.clutter, 0.0);
        assert!(config.problems().is_empty());
    }
}
