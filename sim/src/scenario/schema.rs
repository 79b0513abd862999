//! The scenario: what a scenario file describes, with every default filled in code.

use serde::{Deserialize, Serialize};

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

/// The problem with a surface's lidar reflectivity, if it lies outside [0, 1].
pub(crate) fn reflectivity_problem(reflectivity: Option<f64>) -> Option<(&'static str, String)> {
    let r = reflectivity?;
    (!(0.0..=1.0).contains(&r)).then(|| {
        (
            "reflectivity",
            format!("reflectivity must be in [0, 1], got {r}"),
        )
    })
}

impl TrafficConfig {
    pub(crate) fn problems(&self) -> Vec<(&'static str, String)> {
        let mut out = Vec::new();
        if self.random_cars + self.random_pedestrians > 2000 {
            out.push(("random_cars", "at most 2000 random actors".to_owned()));
        }
        if !self.grid_spacing_m.is_finite() || self.grid_spacing_m < 30.0 {
            out.push((
                "grid_spacing_m",
                format!(
                    "grid spacing must be at least 30 m, got {}",
                    self.grid_spacing_m
                ),
            ));
        }
        if !self.extent_m.is_finite() || self.extent_m <= 0.0 {
            out.push((
                "extent_m",
                format!("extent must be positive, got {}", self.extent_m),
            ));
        }
        if self.centre_m.iter().any(|v| !v.is_finite()) {
            out.push(("centre_m", "centre must be finite".to_owned()));
        }
        let [lo, hi] = self.car_speed_mps;
        if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo <= hi && hi <= 40.0) {
            out.push((
                "car_speed_mps",
                format!(
                    "car speeds must satisfy 0 < min ≤ max ≤ 40 m/s, got {:?}",
                    self.car_speed_mps
                ),
            ));
        }
        out
    }
}

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
