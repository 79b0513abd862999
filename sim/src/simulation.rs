//! A running simulation of one scenario: the scene, the lidar, and the labelled sweeps with their
//! ground truth (SPEC §4). Sweep `i` depends only on (scenario, seed, i), so sweeps can be made in
//! any order and a resumed run writes the same bytes.

use patchflow_dataset::{ObjectTruth, Pose, Sweep};

use crate::error::Result;
use crate::lidar::Lidar;
use crate::motion::{MOVING_SPEED_MPS, MotionState};
use crate::scenario::{ActorConfig, Scenario, random_traffic, reopen_for_fleet};
use crate::scene::{Scene, SceneActor};
use crate::seed::sweep_key;

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
    /// Builds the scene of a scenario (checked again here, for scenarios built in code); random
    /// traffic is drawn from `seed`.
    pub fn new(scenario: &Scenario, seed: u64) -> Result<Self> {
        scenario.validate()?;
        let mut actors: Vec<ActorConfig> = scenario.actors.clone();
        let horizon_secs = scenario.sweep_start_secs(scenario.sweeps) + 1.0;
        let mut traffic = random_traffic(&scenario.traffic, seed, &scenario.name, horizon_secs);
        if scenario.world.knobs().fleet {
            reopen_for_fleet(&mut traffic);
        }
        actors.extend(traffic);
        let scene = Scene::build_seeded(scenario, &actors, seed)?;
        Ok(Self {
            scenario: scenario.clone(),
            seed,
            scene,
            lidar: Lidar::for_scenario(scenario, seed),
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

    /// `world_from_sensor` at the reference time of sweep `index`: the truth.
    pub fn world_from_sensor(&self, index: u32) -> Pose {
        self.lidar
            .world_from_sensor(&self.scene.ego().trajectory.state_at(self.stamp_secs(index)))
    }

    /// The ego's own estimate of `world_from_sensor` at the reference time of sweep `index`
    /// (the truth where the scenario has no pose error).
    pub fn estimated_world_from_sensor(&self, index: u32) -> Pose {
        let t = self.stamp_secs(index);
        let truth = self.scene.ego().trajectory.state_at(t);
        self.lidar
            .world_from_sensor(&self.lidar.estimate(&truth, t))
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
            estimated_world_from_sensor: Some(self.estimated_world_from_sensor(index)),
            points_in_sensor: scan.points_in_sensor,
            intensities: scan.intensities,
            labels: scan.labels,
            flow_in_world_mps: scan.flow_in_world_mps,
            time_in_sweep_secs: scan.time_in_sweep_secs,
            rings: scan.rings,
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
            actor.centre_z_m(state.position_m[0], state.position_m[1]),
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

#[cfg(test)]
mod tests {
    use super::*;

    const TINY: &str = include_str!("../../scenarios/tiny.toml");

    fn tiny(edit: &str) -> Simulation {
        let text = format!("{edit}\n{TINY}");
        let scenario = Scenario::from_toml(&text, "tiny.toml", "tiny").unwrap();
        Simulation::new(&scenario, 5).unwrap()
    }

    #[test]
    fn every_point_has_one_label_flow_and_time() {
        let sweep = tiny("").sweep(1);
        assert!(sweep.len() > 1000, "{} points", sweep.len());
        sweep.check_lengths().unwrap();
        assert!(
            sweep
                .time_in_sweep_secs
                .iter()
                .all(|t| (0.0..0.1).contains(t))
        );
    }

    #[test]
    fn the_target_is_hit_and_its_points_carry_its_true_velocity() {
        let sweep = tiny("").sweep(0);
        let target = sweep.target().unwrap();
        assert!(
            target.point_count > 20,
            "{} target points",
            target.point_count
        );
        let on_target: Vec<usize> = (0..sweep.len())
            .filter(|&i| sweep.labels[i].instance() == target.id)
            .collect();
        assert_eq!(on_target.len(), target.point_count as usize);
        for i in on_target {
            assert_eq!(sweep.labels[i].semantic(), 252);
            let flow = sweep.flow_in_world_mps[i];
            // A straight-driving target: every surface point moves with the centre.
            assert!(
                (f64::from(flow[0]) - target.velocity_mps[0]).abs() < 1e-5
                    && (f64::from(flow[1]) - target.velocity_mps[1]).abs() < 1e-5,
                "{flow:?}"
            );
        }
    }

    #[test]
    fn on_urban_the_object_size_is_the_drawn_body_and_an_explicit_size_is_kept() {
        let drawn = crate::scenario::VehicleBody::draw(
            patchflow_dataset::ActorClass::Car,
            None,
            crate::scenario::fleet_key(5, "tiny", "crossing"),
        )
        .unwrap();
        let target = tiny("").sweep(0).target().unwrap().clone();
        assert_eq!(target.size_m, drawn.size_m);
        assert_ne!(target.size_m, [4.7, 1.8, 1.45]);
        let text = TINY.replace(
            "target = true\n",
            "target = true\nsize_m = [4.2, 1.75, 1.5]\n",
        );
        let scenario = Scenario::from_toml(&text, "tiny.toml", "tiny").unwrap();
        let sweep = Simulation::new(&scenario, 5).unwrap().sweep(0);
        assert_eq!(sweep.target().unwrap().size_m, [4.2, 1.75, 1.5]);
        let ideal = tiny("realism = \"ideal\"").sweep(0);
        assert_eq!(ideal.target().unwrap().size_m, [4.7, 1.8, 1.45]);
    }

    #[test]
    fn no_point_lies_inside_the_ego_car() {
        let mut sim = tiny("");
        let sweep = sim.sweep(2);
        let ego = sim.scene().ego().clone();
        for i in 0..sweep.len() {
            let p = sweep.point_in_world(i);
            let state = ego
                .trajectory
                .state_at(sweep.stamp_secs + f64::from(sweep.time_in_sweep_secs[i]));
            let (dx, dy) = (p.x - state.position_m[0], p.y - state.position_m[1]);
            let (s, c) = state.yaw_rad.sin_cos();
            let (along, across) = (c * dx + s * dy, -s * dx + c * dy);
            let inside = along.abs() < ego.size_m[0] / 2.0
                && across.abs() < ego.size_m[1] / 2.0
                && p.z > 0.05
                && p.z < ego.size_m[2];
            assert!(!inside, "point {i} at {p:?} is inside the ego car");
        }
    }

    #[test]
    fn static_structure_lines_up_after_removing_the_ego_motion() {
        // The wall's near face is the plane x = 39.75 in the world; the ego drives at 2 m/s, so
        // without compensation its points would spread over 0.2 m along x.
        let sweep = tiny("realism = \"ideal\"").sweep(2);
        let xs: Vec<f64> = (0..sweep.len())
            .filter(|&i| sweep.labels[i].semantic() == 51)
            .map(|i| sweep.point_in_world(i).x)
            .collect();
        assert!(xs.len() > 50);
        let max_err = xs.iter().map(|x| (x - 39.75).abs()).fold(0.0, f64::max);
        assert!(max_err < 0.1, "wall points off the plane by {max_err} m");
    }

    #[test]
    fn with_a_drifting_pose_estimate_static_structure_lines_up_in_the_estimated_frame() {
        // Compensated with the estimate, the wall stands where the estimate puts it: in the
        // world frame through the estimated pose, its points keep within the noise of one
        // plane (the estimate drifts by millimetres over a sweep), though not at x = 39.75.
        let sweep = tiny("").sweep(2);
        let estimate = sweep.estimated_pose();
        // The wall's points (the street world's frontage has fences of the same class too; it
        // keeps a metre off the wall): within 0.5 m of its face by the true pose.
        let on_wall = |i: usize| {
            let p = sweep.point_in_world(i);
            sweep.labels[i].semantic() == 51 && (p.x - 39.75).abs() < 0.5 && p.y.abs() < 15.0
        };
        let xs: Vec<f64> = (0..sweep.len())
            .filter(|&i| on_wall(i))
            .map(|i| {
                let [x, y, z] = sweep.points_in_sensor[i];
                (estimate * nalgebra::Point3::new(f64::from(x), f64::from(y), f64::from(z))).x
            })
            .collect();
        assert!(xs.len() > 50);
        let mut sorted = xs.clone();
        sorted.sort_by(f64::total_cmp);
        let median = sorted[sorted.len() / 2];
        let near = xs.iter().filter(|x| (*x - median).abs() < 0.1).count();
        assert!(
            near as f64 > 0.9 * xs.len() as f64,
            "{near} of {} wall points",
            xs.len()
        );
        assert!(
            (median - 39.75).abs() < 2.0,
            "the estimate is off by {} m",
            median - 39.75
        );
    }

    #[test]
    fn another_seed_changes_the_noise_but_not_the_truth() {
        let scenario = Scenario::from_toml(TINY, "tiny.toml", "tiny").unwrap();
        let a = Simulation::new(&scenario, 1).unwrap().sweep(0);
        let b = Simulation::new(&scenario, 2).unwrap().sweep(0);
        let without_counts = |s: &Sweep| {
            let mut objects = s.objects.clone();
            // The street world is drawn from the seed, and each actor stands on its ground:
            // only the height of a box centre may change with it; so does the body the fleet
            // draws for a car without a size.
            objects.iter_mut().for_each(|o| {
                o.point_count = 0;
                o.centre_m[2] = 0.0;
                o.size_m = [0.0; 3];
            });
            objects
        };
        assert_eq!(without_counts(&a), without_counts(&b));
        assert_ne!(a.points_in_sensor, b.points_in_sensor);
        assert_eq!(a, Simulation::new(&scenario, 1).unwrap().sweep(0));
    }
}
