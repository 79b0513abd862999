//! The scenario: what a scenario file describes, with every default filled in code.

use serde::{Deserialize, Serialize};

use super::bounds::{Bound, COORD_M, MAX_RANDOM_ACTORS, check_count};
use super::{
    ActorConfig, LidarConfig, PoseErrorConfig, Realism, RoadConfig, SensorConfig, StructureConfig,
    WorldConfig,
};

/// A seeded random-traffic option for larger training sets: cars and pedestrians on a
/// Manhattan grid of streets around `centre_m`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TrafficConfig {
    /// Number of random cars driving the street grid.
    pub random_cars: u32,
    /// Number of random pedestrians walking the sidewalks.
    pub random_pedestrians: u32,
    /// Distance between parallel streets, metres.
    pub grid_spacing_m: f64,
    /// Half-width of the square the traffic starts in, metres.
    pub extent_m: f64,
    /// Centre of that square, metres.
    pub centre_m: [f64; 2],
    /// Range of car cruise speeds `[min, max]`, m/s.
    pub car_speed_mps: [f64; 2],
}

impl Default for TrafficConfig {
    fn default() -> Self {
        Self {
            random_cars: 0,
            random_pedestrians: 0,
            grid_spacing_m: 60.0,
            extent_m: 120.0,
            centre_m: [0.0, 0.0],
            car_speed_mps: [2.0, 10.0],
        }
    }
}

impl TrafficConfig {
    pub(crate) fn problems(&self) -> Vec<(&'static str, String)> {
        let random = u64::from(self.random_cars) + u64::from(self.random_pedestrians);
        let mut out: Vec<(&'static str, String)> = [
            check_count(
                "random_cars",
                random,
                0,
                MAX_RANDOM_ACTORS,
                "random cars and pedestrians together",
            ),
            GRID_SPACING_M.check("grid_spacing_m", self.grid_spacing_m),
            EXTENT_M.check("extent_m", self.extent_m),
            COORD_M.check_each("centre_m", &self.centre_m),
            CAR_SPEED_MPS.check_each("car_speed_mps", &self.car_speed_mps),
        ]
        .into_iter()
        .flatten()
        .collect();
        let [lo, hi] = self.car_speed_mps;
        if out.is_empty() && lo > hi {
            out.push((
                "car_speed_mps",
                format!(
                    "car speeds must be [min, max], got {:?}",
                    self.car_speed_mps
                ),
            ));
        }
        out
    }
}

/// Distance between parallel streets of random traffic.
const GRID_SPACING_M: Bound = Bound::new(30.0, 10_000.0, "m", "a block fits two turns");
/// Half-width of the square random traffic starts in.
const EXTENT_M: Bound = Bound::new(
    1.0,
    10_000.0,
    "m",
    "the traffic's square lies within the world",
);
/// Cruise speeds of random cars.
const CAR_SPEED_MPS: Bound = Bound::new(0.1, 40.0, "m/s", "a moving car");

/// A traffic scenario: sensor, ego path, actors, static structures and random traffic.
///
/// Load one with [`Scenario::from_toml`] (validates and resolves defaults); see
/// `scenarios/README.md` for every field with unit and default.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// Name of the scenario and of its sequence folder (default: the file stem).
    #[serde(default)]
    pub name: String,
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// Number of sweeps to generate.
    #[serde(default = "default_sweeps")]
    pub sweeps: u32,
    /// Scenario time of sweep 0's start, seconds.
    #[serde(default)]
    pub start_secs: f64,
    /// Lidar reflectivity of the road surface.
    #[serde(default = "default_ground_reflectivity")]
    pub ground_reflectivity: f64,
    /// Rung of the realism ladder whose knobs fill every `[world]`, `[sensor]` and
    /// `[pose_error]` knob the file leaves out (SPEC §3a).
    #[serde(default)]
    pub realism: Realism,
    /// The procedural street world: ground, curbs, sidewalks, clutter, façades, shapes.
    #[serde(default)]
    pub world: WorldConfig,
    /// Sensor errors beyond the ideal lidar.
    #[serde(default)]
    pub sensor: SensorConfig,
    /// The ego's localisation error.
    #[serde(default)]
    pub pose_error: PoseErrorConfig,
    /// Street centre lines for the procedural world (optional; else derived from the paths).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub roads: Vec<RoadConfig>,
    /// The lidar.
    #[serde(default)]
    pub lidar: LidarConfig,
    /// The ego car carrying the lidar (a car; its `name` and `target` are ignored).
    pub ego: ActorConfig,
    /// Moving actors; actor `i` gets instance id `i + 1`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub actors: Vec<ActorConfig>,
    /// Static structures.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub structures: Vec<StructureConfig>,
    /// Seeded random traffic, added after the listed actors.
    #[serde(default)]
    pub traffic: TrafficConfig,
}

fn default_sweeps() -> u32 {
    100
}

fn default_ground_reflectivity() -> f64 {
    0.15
}

impl Scenario {
    /// Reference time of sweep `index` (its start), seconds of scenario time.
    pub fn sweep_start_secs(&self, index: u32) -> f64 {
        self.start_secs + f64::from(index) * self.lidar.period_secs()
    }

    /// The actor marked `target`, if any.
    pub fn target(&self) -> Option<&ActorConfig> {
        self.actors.iter().find(|a| a.target)
    }

    /// The resolved scenario as TOML text, every default written out (stored beside the data).
    pub fn to_toml(&self) -> String {
        // Serialising plain data with finite numbers cannot fail; fall back to Debug if it ever does.
        toml::to_string(self)
            .unwrap_or_else(|e| format!("# could not serialise: {e}\n# {self:?}\n"))
    }
}
