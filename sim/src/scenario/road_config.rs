//! One optional `[[roads]]` entry: a street centre line the procedural world lays its road,
//! curbs, sidewalks and clutter along. Without any, streets are derived from the vehicle paths
//! (ego, cars, trucks: the centre line is 1.75 m left of a right-hand lane) and the
//! random-traffic grid.

use serde::{Deserialize, Serialize};

use super::bounds::{COORD_M, MAX_PATH_POINTS, check_count};
use super::world_config::ROAD_HALF_WIDTH_M;

/// A street centre line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoadConfig {
    /// Centre-line waypoints `[[x, y], …]`, metres (at least two).
    pub path_m: Vec<[f64; 2]>,
    /// Half width of the carriageway (default: `[world] road_half_width_m`), metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub half_width_m: Option<f64>,
}

impl RoadConfig {
    /// Every problem, with the field's name.
    pub(crate) fn problems(&self) -> Vec<(&'static str, String)> {
        let count = check_count(
            "path_m",
            self.path_m.len() as u64,
            2,
            MAX_PATH_POINTS,
            "points of a road's centre line",
        );
        let width = self
            .half_width_m
            .and_then(|w| ROAD_HALF_WIDTH_M.check("half_width_m", w));
        [
            count,
            COORD_M.check_each("path_m", self.path_m.iter().flatten()),
            width,
        ]
        .into_iter()
        .flatten()
        .collect()
    }
}
