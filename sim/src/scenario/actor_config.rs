//! One `[[actors]]` entry (or the `[ego]` table): a box (or a mesh fitted to it) that follows a
//! smooth path with a speed profile.

use patchflow_dataset::ActorClass;
use serde::{Deserialize, Serialize};

use crate::motion::{Path, SpeedProfile, Trajectory};

use super::bounds::{
    Bound, COORD_M, MAX_PATH_POINTS, SIZE_M, TIME_SECS, TURN_RADIUS_M, check_count,
    reflectivity_problem, show,
};

/// Acceleration and braking limit of any actor.
const ACCEL_MPS2: Bound = Bound::new(0.01, 10.0, "m/s²", "from a crawl to a sports car's braking");

/// Car body styles; they set the default box size of a car.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CarModel {
    /// 3.9 × 1.7 × 1.45 m.
    Compact,
    /// 4.7 × 1.8 × 1.45 m.
    Sedan,
    /// 5.1 × 1.95 × 1.95 m.
    Van,
}

/// A moving actor: class, box, path and speed profile. Optional fields get class defaults
/// when the scenario is resolved (see `scenarios/README.md`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActorConfig {
    /// Name, unique within the scenario (written into the object truth).
    #[serde(default)]
    pub name: String,
    /// Actor class.
    #[serde(default = "default_class")]
    pub class: ActorClass,
    /// Car body style (cars only); sets the default size.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<CarModel>,
    /// Box size: length, width, height, metres (default from class and model).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size_m: Option<[f64; 3]>,
    /// True for the one actor a situation evaluates.
    #[serde(default)]
    pub target: bool,
    /// Waypoints in the ground plane, metres; corners are rounded with `turn_radius_m`.
    pub path_m: Vec<[f64; 2]>,
    /// Radius of the circular arcs joining straight segments, metres (class default; never below the class minimum).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub turn_radius_m: Option<f64>,
    /// Cruise speed reached after `start_secs`, m/s.
    pub speed_mps: f64,
    /// Speed before `start_secs`, m/s (default: `speed_mps`, a flying start).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial_speed_mps: Option<f64>,
    /// Acceleration and braking limit, m/s² (class default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accel_mps2: Option<f64>,
    /// Time the actor passes the first waypoint, seconds; before it moves at `initial_speed_mps` on the straight lead-in (or waits there if that is 0).
    #[serde(default)]
    pub start_secs: f64,
    /// Later speed targets `[time_secs, speed_mps]`, approached within the acceleration limit.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub speed_changes: Vec<[f64; 2]>,
    /// Lidar reflectivity of the surface in [0, 1] (class default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reflectivity: Option<f64>,
    /// The actor's own shape: a Wavefront OBJ file, its path relative to the scenario file,
    /// scaled to `size_m` (its truth stays that box). Used where the world has vehicle shapes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<String>,
    /// The mesh read from `mesh` when the scenario was loaded.
    #[serde(skip)]
    pub mesh_data: Option<std::sync::Arc<super::VehicleMesh>>,
}

fn default_class() -> ActorClass {
    ActorClass::Car
}

/// Per-class defaults and limits.
pub(crate) struct ClassLimits {
    /// Smallest turn radius the class can drive, metres.
    pub min_turn_radius_m: f64,
    /// Default turn radius, metres.
    pub turn_radius_m: f64,
    /// Default acceleration limit, m/s².
    pub accel_mps2: f64,
    /// Highest plausible speed, m/s.
    pub max_speed_mps: f64,
    /// Default lidar reflectivity.
    pub reflectivity: f64,
}

/// Defaults and limits of a class.
pub(crate) fn class_limits(class: ActorClass) -> ClassLimits {
    match class {
        ActorClass::Car => ClassLimits {
            min_turn_radius_m: 4.5,
            turn_radius_m: 8.0,
            accel_mps2: 2.5,
            max_speed_mps: 40.0,
            reflectivity: 0.55,
        },
        ActorClass::Truck => ClassLimits {
            min_turn_radius_m: 8.0,
            turn_radius_m: 12.0,
            accel_mps2: 1.2,
            max_speed_mps: 30.0,
            reflectivity: 0.6,
        },
        ActorClass::Pedestrian => ClassLimits {
            min_turn_radius_m: 0.3,
            turn_radius_m: 1.0,
            accel_mps2: 1.0,
            max_speed_mps: 4.0,
            reflectivity: 0.35,
        },
        ActorClass::Cyclist => ClassLimits {
            min_turn_radius_m: 2.0,
            turn_radius_m: 4.0,
            accel_mps2: 1.5,
            max_speed_mps: 15.0,
            reflectivity: 0.4,
        },
    }
}

/// Default box size of a class (and car model): length, width, height, metres.
pub(crate) fn default_size(class: ActorClass, model: Option<CarModel>) -> [f64; 3] {
    match (class, model) {
        (ActorClass::Car, Some(CarModel::Compact)) => [3.9, 1.7, 1.45],
        (ActorClass::Car, Some(CarModel::Van)) => [5.1, 1.95, 1.95],
        (ActorClass::Car, _) => [4.7, 1.8, 1.45],
        (ActorClass::Truck, _) => [9.0, 2.5, 3.4],
        (ActorClass::Pedestrian, _) => [0.5, 0.6, 1.75],
        (ActorClass::Cyclist, _) => [1.8, 0.6, 1.7],
    }
}

impl ActorConfig {
    /// Builds the trajectory of a resolved actor; an error names the offending field.
    pub(crate) fn trajectory(&self) -> Result<Trajectory, (&'static str, String)> {
        let radius = self.turn_radius_m.unwrap_or(8.0);
        let path = Path::new(&self.path_m, radius).map_err(|reason| ("path_m", reason))?;
        let profile = SpeedProfile::new(
            self.start_secs,
            self.initial_speed_mps.unwrap_or(self.speed_mps),
            self.speed_mps,
            self.accel_mps2.unwrap_or(2.0),
            &self.speed_changes,
        );
        Ok(Trajectory::new(path, profile))
    }

    /// Fills every optional field with its class default, so the written scenario is explicit.
    pub(crate) fn resolve(&mut self) {
        self.resolve_in(false);
    }

    /// [`ActorConfig::resolve`] on a world whose `fleet` knob is `fleet`: there a car or truck
    /// without `size_m` keeps none (and a car without `model` none), since its body is drawn
    /// per vehicle from the run seed when the scene is built (`VehicleBody`).
    pub(crate) fn resolve_in(&mut self, fleet: bool) {
        let limits = class_limits(self.class);
        let drawn = fleet
            && self.size_m.is_none()
            && matches!(self.class, ActorClass::Car | ActorClass::Truck);
        if !drawn {
            if self.class == ActorClass::Car && self.model.is_none() && self.size_m.is_none() {
                self.model = Some(CarModel::Sedan);
            }
            self.size_m
                .get_or_insert(default_size(self.class, self.model));
        }
        self.turn_radius_m.get_or_insert(limits.turn_radius_m);
        self.initial_speed_mps.get_or_insert(self.speed_mps);
        self.accel_mps2.get_or_insert(limits.accel_mps2);
        self.reflectivity.get_or_insert(limits.reflectivity);
    }

    /// Reasons this actor is impossible, each with the offending field's name (call after `resolve`).
    pub(crate) fn problems(&self) -> Vec<(&'static str, String)> {
        let limits = class_limits(self.class);
        let mut out = Vec::new();
        if let Some(model) = self.model
            && self.class != ActorClass::Car
        {
            out.push((
                "model",
                format!(
                    "model = \"{}\" is a car body style; a {} has none (remove it, or set class = \"car\")",
                    format!("{model:?}").to_lowercase(),
                    format!("{:?}", self.class).to_lowercase()
                ),
            ));
        }
        let finite = |v: f64| v.is_finite();
        if self.path_m.len() < 2 {
            out.push((
                "path_m",
                format!(
                    "a path needs at least two points, got {}",
                    self.path_m.len()
                ),
            ));
        }
        out.extend(check_count(
            "path_m",
            self.path_m.len() as u64,
            2,
            MAX_PATH_POINTS,
            "waypoints of one path",
        ));
        out.extend(COORD_M.check_each("path_m", self.path_m.iter().flatten()));
        if self
            .path_m
            .windows(2)
            .any(|w| (w[0][0] - w[1][0]).hypot(w[0][1] - w[1][1]) < 1e-3)
        {
            out.push(("path_m", "two consecutive path points coincide".to_owned()));
        }
        if let Some(size) = &self.size_m {
            out.extend(SIZE_M.check_each("size_m", size));
        }
        let speed_ok = |v: f64| finite(v) && v >= 0.0 && v <= limits.max_speed_mps;
        if !speed_ok(self.speed_mps) {
            out.push((
                "speed_mps",
                format!(
                    "speed must be 0 to {} m/s for a {:?}, got {}",
                    limits.max_speed_mps,
                    self.class,
                    show(self.speed_mps)
                ),
            ));
        }
        if let Some(v) = self.initial_speed_mps
            && !speed_ok(v)
        {
            out.push((
                "initial_speed_mps",
                format!(
                    "speed must be 0 to {} m/s for a {:?}, got {}",
                    limits.max_speed_mps,
                    self.class,
                    show(v)
                ),
            ));
        }
        out.extend(check_count(
            "speed_changes",
            self.speed_changes.len() as u64,
            0,
            MAX_PATH_POINTS,
            "speed changes of one actor",
        ));
        out.extend(TIME_SECS.check_each("speed_changes", self.speed_changes.iter().map(|c| &c[0])));
        for (i, change) in self.speed_changes.iter().enumerate() {
            if !speed_ok(change[1]) || !finite(change[0]) {
                out.push(("speed_changes", format!("speed change {i} needs a finite time and a speed of 0 to {} m/s, got {change:?}", limits.max_speed_mps)));
            }
        }
        if self.speed_changes.windows(2).any(|w| w[1][0] <= w[0][0])
            || self
                .speed_changes
                .first()
                .is_some_and(|c| c[0] < self.start_secs)
        {
            out.push((
                "speed_changes",
                "speed changes must come after start_secs, in increasing time".to_owned(),
            ));
        }
        out.extend(TIME_SECS.check("start_secs", self.start_secs));
        if let Some(r) = self.turn_radius_m
            && r > TURN_RADIUS_M.max
        {
            out.extend(TURN_RADIUS_M.check("turn_radius_m", r));
        } else if let Some(r) = self.turn_radius_m
            && (!finite(r) || r < limits.min_turn_radius_m)
        {
            out.push((
                "turn_radius_m",
                format!(
                    "turn radius {r} m is below the {:?} minimum of {} m",
                    self.class, limits.min_turn_radius_m
                ),
            ));
        }
        if let Some(a) = self.accel_mps2 {
            out.extend(ACCEL_MPS2.check("accel_mps2", a));
        }
        out.extend(reflectivity_problem(self.reflectivity));
        out
    }
}
