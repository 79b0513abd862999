//! A running simulation of one scenario: the scene, the lidar, and the labelled sweeps with their
//! ground truth (SPEC §4). Sweep `i` depends only on (scenario, seed, i), so sweeps can be made in
//! any order and a resumed run writes the same bytes.

use patchflow_dataset::{ObjectTruth, Pose, Sweep};

use crate::error::Result;
use crate::lidar::Lidar;
use crate::motion::MotionState;
use crate::scenario::{ActorConfig, Scenario, random_traffic};
use crate::scene::{Scene, SceneActor};
use crate::seed::sweep_key;

/// Speed from which an actor counts as moving (moving SemanticKITTI classes), m/s.
pub const MOVING_SPEED_MPS: f64 = 0.05;

/// One scenario's scene and lidar, ready to produce sweeps.
///
/// ```
/// let text = "sweeps = 1\n[lidar]\nchannels = 8\nazimuth_steps = 90\nblocks = 9\n[ego]\npath_m = [[0.0, 0.0], [50.0, 0.0]]\nspeed_mps = 5.0\n";
/// let scenario = patchflow_sim::Scenario::from_toml(text, "doc.toml", "doc").unwrap();
/// let mut sim = patchflow_sim::Simulation::new(&scenario, 1).unwrap();
/// let sweep = sim.sweep(0);
/// assert!(sweep.len() > 0);
/// ```
pub struct Simulation {
    scenario: Scenario,
    seed: u64,
    scene: Scene,
    lidar: Lidar,
}

impl Simulation {
    /// Builds the scene of a validated scenario; random traffic is drawn from `seed`.
    pub fn new(scenario: &Scenario, seed: u64) -> Result<Self> {
        let mut actors: Vec<ActorConfig> = scenario.actors.clone();
        let horizon_secs = scenario.sweep_start_secs(scenario.sweeps) + 1.0;
        actors.extend(random_traffic(
            &scenario.traffic,
            seed,
            &scenario.name,
            horizon_secs,
        ));
        let scene = Scene::build(scenario, &actors)?;
        Ok(Self {
            scenario: scenario.clone(),
            seed,
            scene,
            lidar: Lidar::new(&scenario.lidar),
        })
    }

    /// The scenario.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// The scene (for inspection and benchmarks).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The scene, mutable (for benchmarks that move it).
    pub fn scene_mut(&mut self) -> &mut Scene {
        &mut self.scene
    }

    /// The lidar.
    pub fn lidar(&self) -> &Lidar {
        &self.lidar
    }

    /// Reference time of sweep `index`: the instant its first azimuth column fires, scenario seconds.
    pub fn stamp_secs(&self, index: u32) -> f64 {
        self.scenario.sweep_start_secs(index)
    }

    /// `world_from_sensor` at the reference time of sweep `index`.
    pub fn world_from_sensor(&self, index: u32) -> Pose {
        self.lidar
            .world_from_sensor(&self.scene.ego().trajectory.state_at(self.stamp_secs(index)))
    }

    /// Produces sweep `index`: cast (rolling shutter), labels, flow, time, and the truth of every actor.
    pub fn sweep(&mut self, index: u32) -> Sweep {
        let start = self.stamp_secs(index);
        let scan = self.lidar.scan(
            &mut self.scene,
            start,
            sweep_key(self.seed, &self.scenario.name, index),
        );
        let objects = self
            .scene
            .actors()
            .iter()
            .zip(&scan.actor_point_counts)
            .map(|(actor, &count)| object_truth(actor, &actor.trajectory.state_at(start), count))
            .collect();
        Sweep {
            index,
            stamp_secs: start - self.scenario.start_secs,
            world_from_sensor: self.world_from_sensor(index),
            points_in_sensor: scan.points_in_sensor,
            intensities: scan.intensities,
            labels: scan.labels,
            flow_in_world_mps: scan.flow_in_world_mps,
            time_in_sweep_secs: scan.time_in_sweep_secs,
            objects,
        }
    }
}

/// The truth of one actor at one instant, world frame.
fn object_truth(actor: &SceneActor, state: &MotionState, point_count: u32) -> ObjectTruth {
    ObjectTruth {
        id: actor.id,
        name: actor.name.clone(),
        class: actor.class,
        target: actor.target,
        moving: state.speed_mps >= MOVING_SPEED_MPS,
        centre_m: [
            state.position_m[0],
            state.position_m[1],
            actor.size_m[2] / 2.0,
        ],
        size_m: actor.size_m,
        yaw_rad: state.yaw_rad,
        velocity_mps: [state.velocity_mps[0], state.velocity_mps[1], 0.0],
        speed_mps: state.speed_mps,
        heading_rad: state.heading_rad,
        yaw_rate_radps: state.yaw_rate_radps,
        point_count,
    }
}
