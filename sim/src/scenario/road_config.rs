//! One optional `[[roads]]` entry: a street centre line the procedural world lays its road,
//! curbs, sidewalks and clutter along. Without any, streets are derived from the vehicle paths
//! (ego, cars, trucks: the centre line is 1.75 m left of a right-hand lane) and the
//! random-traffic grid.

use serde::{Deserialize, Serialize};

use super::realism::range_problem;

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
        let mut out = Vec::new();
        if self.path_m.len() < 2 {
            out.push((
                "path_m",
                format!(
                    "a road needs at least two points, got {}",
                    self.path_m.len()
                ),
            ));
        }
        if self.path_m.iter().flatten().any(|v| !v.is_finite()) {
            out.push(("path_m", "road points must be finite numbers".to_owned()));
        }
        if let Some(w) = self.half_width_m {
            out.extend(range_problem("half_width_m", w, 3.0, 15.0));
        }
        out
    }
}
