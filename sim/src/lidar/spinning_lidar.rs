//! The spinning lidar: casts one sweep into a scene, each azimuth block against the scene at its
//! own instant (rolling shutter), all columns of the sweep in one parallel loop.
//! Also the bare `cast_ray` loop over the same rays, the yardstick of the SPEC §8 speed target.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rapier3d::prelude::{Ray, Vector};
use rayon::prelude::*;

use super::block_caster::{BlockCaster, EgoStates};
use super::firing_table::FiringTable;
use super::mixed_pixels::mix_edges;
use super::scan::{Scan, ScanSlots};
use super::self_occlusion::occluded_beams;
use super::sensor_model::SensorModel;
use crate::motion::MotionState;
use crate::pose_error::PoseError;
use crate::scenario::{LidarConfig, PoseErrorKnobs, Realism, Scenario, SensorKnobs, WorldKnobs};
use crate::scene::{QueryTree, Scene, SceneInstant};
use crate::seed::{hash_name, mix, sub_seed};

/// A spinning multi-beam lidar with its firing pattern computed once.
#[derive(Debug, Clone)]
pub struct Lidar {
    config: LidarConfig,
    table: FiringTable,
    sensor: SensorModel,
    pose_error: PoseError,
    /// Cast with the realistic return model (any world or sensor but the ideal ones).
    realistic: bool,
    /// Scratch slots reused by every sweep (no per-sweep zeroing or page faults).
    slots: ScanSlots,
}

impl Lidar {
    /// An ideal lidar with the given settings on a car that knows its pose exactly.
    pub fn new(config: &LidarConfig) -> Self {
        let channels = config.channels as usize;
        Self {
            config: config.clone(),
            table: FiringTable::new(config),
            sensor: SensorModel::new(SensorKnobs::of(Realism::Ideal), channels, 0),
            pose_error: PoseError::new(&PoseErrorKnobs::of(Realism::Ideal), 0, ""),
            realistic: false,
            slots: ScanSlots::default(),
        }
    }

    /// The lidar of a scenario: its `[lidar]` settings, its `[sensor]` errors with this unit's
    /// calibration and the ego's `[pose_error]`, drawn from `seed` and the scenario name.
    pub fn for_scenario(scenario: &Scenario, seed: u64) -> Self {
        let config = &scenario.lidar;
        let key = mix(seed ^ hash_name(&scenario.name));
        let sensor = SensorModel::new(
            scenario.sensor.knobs(),
            config.channels as usize,
            sub_seed(key, 0x5E45),
        );
        let world = scenario.world.knobs();
        let mut table = FiringTable::new(config)
            .with_elevation_errors(config, |c| sensor.elevation_error_rad(c));
        if world.shapes {
            table = table
                .with_occlusion(|rays| occluded_beams(rays, &scenario.ego, config.mount_height_m));
        }
        let world_ideal = world == WorldKnobs::of(Realism::Ideal);
        Self {
            config: config.clone(),
            table,
            realistic: !(sensor.is_ideal() && world_ideal),
            sensor,
            pose_error: PoseError::new(&scenario.pose_error.knobs(), seed, &scenario.name),
            slots: ScanSlots::default(),
        }
    }

    /// The ego's estimate of its state at `t_secs` given its true state then.
    pub(crate) fn estimate(&self, truth: &MotionState, t_secs: f64) -> MotionState {
        self.pose_error.estimate(truth, t_secs)
    }

    /// Share of the beams the ego car's own body stops (never cast), 0 without vehicle shapes.
    pub fn self_occluded_share(&self) -> f64 {
        self.table.occluded_share()
    }

    /// The settings.
    pub fn config(&self) -> &LidarConfig {
        &self.config
    }

    /// Pose of the sensor for an ego state: above the ego centre at the mount height, yawed with it.
    pub fn world_from_sensor(&self, ego: &MotionState) -> Isometry3<f64> {
        Isometry3::from_parts(
            Translation3::new(
                ego.position_m[0],
                ego.position_m[1],
                self.config.mount_height_m,
            ),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), ego.yaw_rad),
        )
    }

    /// Unit ray directions in the sensor frame, column by column (channel fastest).
    pub fn rays_in_sensor(&self) -> Vec<[f32; 3]> {
        self.table
            .rays_in_sensor()
            .iter()
            .map(|d| [d.x, d.y, d.z])
            .collect()
    }

    /// Casts one sweep starting at scenario time `start_secs` (the reference time). With the
    /// rolling shutter on, azimuth block `b` is cast against the scene at the block's middle
    /// instant; otherwise the whole sweep sees the scene at `start_secs`. The movers' poses at
    /// every block instant are taken up front and the ray-cast tree is rebuilt once so that its
    /// leaves span them, so all columns of the sweep are cast in one parallel loop, each against
    /// its own block's instant. Noise is drawn from one stream per column derived from
    /// `noise_key`, so the result does not depend on threads. Takes `&mut self` only to reuse its
    /// scratch slots. The scene is left moved to `start_secs`.
    pub fn scan(&mut self, scene: &mut Scene, start_secs: f64, noise_key: u64) -> Scan {
        let ego_ref = scene.ego().trajectory.state_at(start_secs);
        let ego_ref_estimate = self.pose_error.estimate(&ego_ref, start_secs);
        scene.move_to(start_secs);
        let blocks = self.table.blocks();
        let instants: Vec<SceneInstant> = blocks
            .iter()
            .map(|block| scene.instant(start_secs + block.offset_secs))
            .collect();
        scene.rebuild_ray_tree_spanning(&instants);
        let scene = &*scene;
        let casters: Vec<BlockCaster<'_>> = blocks
            .iter()
            .zip(&instants)
            .map(|(block, instant)| {
                let t = start_secs + block.offset_secs;
                let ego = scene.ego().trajectory.state_at(t);
                let states = EgoStates {
                    block: ego,
                    block_estimate: self.pose_error.estimate(&ego, t),
                    reference_estimate: ego_ref_estimate,
                };
                BlockCaster::new(
                    scene.query_at(instant),
                    (&self.table, &self.sensor, self.realistic),
                    &self.config,
                    block.offset_secs,
                    &states,
                    noise_key,
                )
            })
            .collect();
        let slots = &mut self.slots;
        let columns = self.config.azimuth_steps as usize;
        slots.reset(columns, self.table.channels());
        let table = &self.table;
        slots.fill_columns(0..columns, |j, column| {
            if let Some(caster) = casters.get(table.block_of(j)) {
                caster.cast_column(j, column);
            }
        });
        if self.realistic {
            let origin_of = |j: usize| {
                casters
                    .get(table.block_of(j))
                    .map_or([0.0; 3], |c| c.origin_in_reference.to_array())
            };
            let key = sub_seed(noise_key, 0x313D);
            mix_edges(
                slots.returns_mut(),
                self.sensor.mixed_pixels(),
                &origin_of,
                key,
            );
        }
        slots.gather(scene.actors().len())
    }

    /// The bare Rapier loop over the same rays: `cast_ray` only, from the sensor pose at
    /// `start_secs`, into the scene as it stands through `tree`, one rayon task per azimuth
    /// column like [`Lidar::scan`] (the beams the ego car's own body stops are not cast in
    /// either). Returns the number of hits. The yardstick of SPEC §8.
    pub fn bare_cast_ray_hits(&self, scene: &Scene, start_secs: f64, tree: QueryTree) -> usize {
        let ego = scene.ego().trajectory.state_at(start_secs);
        let origin = Vector::new(
            ego.position_m[0] as f32,
            ego.position_m[1] as f32,
            self.config.mount_height_m as f32,
        );
        let (s, c) = ego.yaw_rad.sin_cos();
        let (c, s) = (c as f32, s as f32);
        let max_range_m = self.config.max_range_m as f32;
        (0..self.config.azimuth_steps as usize)
            .into_par_iter()
            .map(|j| {
                let qp = scene.query_pipeline_on(tree);
                let occluded = self.table.occluded_column(j);
                self.table
                    .column(j)
                    .iter()
                    .enumerate()
                    .filter(|&(k, d)| {
                        if occluded.is_some_and(|o| o[k]) {
                            return false;
                        }
                        let dir = Vector::new(c * d.x - s * d.y, s * d.x + c * d.y, d.z);
                        qp.cast_ray(&Ray::new(origin, dir), max_range_m, true)
                            .is_some()
                    })
                    .count()
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use crate::{QueryTree, Scenario, Simulation};

    const TINY: &str = include_str!("../../../scenarios/tiny.toml");

    fn tiny_with_noise_and_dropout() -> Simulation {
        let text = TINY.replace("blocks = 36", "blocks = 36\ndropout_probability = 0.1");
        let scenario = Scenario::from_toml(&text, "tiny.toml", "tiny").unwrap();
        Simulation::new(&scenario, 3).unwrap()
    }

    #[test]
    fn dropout_probability_takes_effect_on_every_rung() {
        for rung in ["ideal", "urban", "harsh"] {
            let points = |dropout: f64| {
                let text = format!(
                    "realism = \"{rung}\"\n{}",
                    TINY.replace(
                        "blocks = 36",
                        &format!("blocks = 36\ndropout_probability = {dropout}")
                    )
                );
                let scenario = Scenario::from_toml(&text, "tiny.toml", "tiny").unwrap();
                Simulation::new(&scenario, 3).unwrap().sweep(1).len() as f64
            };
            let (kept, dropped) = (points(0.0), points(0.9));
            // 90 % dropped: about a tenth is left; a third is far outside any chance variation.
            assert!(
                dropped < kept / 3.0,
                "{rung}: {dropped} of {kept} points kept"
            );
        }
    }

    #[test]
    fn a_sweep_is_byte_identical_on_one_and_on_three_threads() {
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| tiny_with_noise_and_dropout().sweep(1))
        };
        let (one, three) = (on(1), on(3));
        assert!(one.len() > 1000, "{} points", one.len());
        assert_eq!(one, three);
    }

    #[test]
    fn a_sweep_does_not_depend_on_the_sweeps_made_before_it() {
        let mut walked = tiny_with_noise_and_dropout();
        walked.sweep(0);
        walked.sweep(2);
        assert_eq!(walked.sweep(1), tiny_with_noise_and_dropout().sweep(1));
    }

    #[test]
    fn the_ray_tree_and_rapiers_broad_phase_tree_give_the_same_hits() {
        let mut sim = tiny_with_noise_and_dropout();
        sim.sweep(0);
        sim.sweep(1);
        let t = sim.stamp_secs(2);
        sim.scene_mut().move_to(t);
        let (lidar, scene) = (sim.lidar(), sim.scene());
        let ours = lidar.bare_cast_ray_hits(scene, t, QueryTree::RayCast);
        let rapier = lidar.bare_cast_ray_hits(scene, t, QueryTree::RapierBroadPhase);
        assert!(ours > 1000, "{ours} hits");
        assert_eq!(ours, rapier);
    }

    /// A car 6 m ahead drives across the view at 15 m/s in the direction the beam sweeps.
    fn crossing(rolling: bool) -> patchflow_dataset::Sweep {
        let text = format!(
            "realism = \"ideal\"\nsweeps = 1\n[lidar]\nchannels = 8\nupper_deg = -4.0\nlower_deg = -12.0\nspacing = \"uniform\"\nazimuth_steps = 3600\nblocks = 3600\nrange_noise_std_m = 0.0\nrolling_shutter = {rolling}\n[ego]\npath_m = [[0.0, 0.0], [1.0, 0.0]]\nspeed_mps = 0.0\n[[actors]]\nname = \"car\"\ntarget = true\npath_m = [[6.0, 30.0], [6.0, -30.0]]\nspeed_mps = 15.0\nstart_secs = -1.95\n"
        );
        let scenario = Scenario::from_toml(&text, "smear.toml", "smear").unwrap();
        Simulation::new(&scenario, 0).unwrap().sweep(0)
    }

    fn car_extent_y(sweep: &patchflow_dataset::Sweep) -> (f64, f64) {
        let on_car: Vec<usize> = (0..sweep.len())
            .filter(|&i| sweep.labels[i].instance() == 1)
            .collect();
        let ys: Vec<f64> = on_car
            .iter()
            .map(|&i| f64::from(sweep.points_in_sensor[i][1]))
            .collect();
        let ts: Vec<f64> = on_car
            .iter()
            .map(|&i| f64::from(sweep.time_in_sweep_secs[i]))
            .collect();
        let extent = ys.iter().cloned().fold(f64::MIN, f64::max)
            - ys.iter().cloned().fold(f64::MAX, f64::min);
        let duration = ts.iter().cloned().fold(f64::MIN, f64::max)
            - ts.iter().cloned().fold(f64::MAX, f64::min);
        (extent, duration)
    }

    #[test]
    fn the_rolling_shutter_smears_a_crossing_car_by_its_speed_times_its_scan_time() {
        let (static_extent, static_duration) = car_extent_y(&crossing(false));
        let (rolling_extent, rolling_duration) = car_extent_y(&crossing(true));
        assert_eq!(static_duration, 0.0);
        let expected = 15.0 * rolling_duration;
        assert!(
            expected > 0.1,
            "the car's azimuth span takes only {rolling_duration} s"
        );
        let smear = rolling_extent - static_extent;
        // Tolerance: one azimuth column at 6 m (1 cm) on each end plus f32 rounding.
        assert!(
            (smear - expected).abs() < 0.03,
            "smear {smear} m, expected v·Δt = {expected} m"
        );
    }
}
