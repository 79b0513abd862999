//! The spinning lidar: casts one sweep into a scene, azimuth block by azimuth block, each block
//! with the scene moved to its own instant (rolling shutter), rays of a block in parallel.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use patchflow_dataset::PointLabel;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use rapier3d::prelude::{QueryPipeline, Ray, Vector};
use rayon::prelude::*;

use super::beams::{azimuth_rad, elevations_deg};
use super::intensity::intensity;
use crate::motion::MotionState;
use crate::scenario::LidarConfig;
use crate::scene::Scene;
use crate::seed::sub_seed;

/// Rays shorter than this (the origin inside a shape) are not returns, metres.
const MIN_RANGE_M: f32 = 0.05;

/// The per-point output of one sweep, parallel arrays in firing order (column by column).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Scan {
    /// Points in the sensor frame at the sweep's reference time, ego motion removed.
    pub points_in_sensor: Vec<[f32; 3]>,
    /// Intensity in [0, 1].
    pub intensities: Vec<f32>,
    /// SemanticKITTI labels.
    pub labels: Vec<PointLabel>,
    /// True velocity of the hit surface point, world frame, m/s.
    pub flow_in_world_mps: Vec<[f32; 3]>,
    /// Seconds since the sweep started at which the point's block was cast.
    pub time_in_sweep_secs: Vec<f32>,
    /// Points per actor (index = actor index, i.e. instance id − 1).
    pub actor_point_counts: Vec<u32>,
}

/// One return before it is appended to the scan.
#[derive(Debug, Clone, Copy)]
struct Return {
    point_in_sensor: [f32; 3],
    intensity: f32,
    label: PointLabel,
    flow_mps: [f32; 3],
    actor: Option<usize>,
}

/// What every ray of one azimuth block shares.
struct Block<'a> {
    time_in_sweep_secs: f32,
    origin: Vector,
    yaw_cos_sin: (f32, f32),
    states: &'a [MotionState],
    sensor_from_world_ref: &'a Isometry3<f64>,
    noise_key: u64,
}

/// A spinning multi-beam lidar with precomputed beam directions.
#[derive(Debug, Clone)]
pub struct Lidar {
    config: LidarConfig,
    elevation_sin_cos: Vec<(f32, f32)>,
    azimuth_sin_cos: Vec<(f32, f32)>,
}

impl Lidar {
    /// A lidar with the given settings.
    pub fn new(config: &LidarConfig) -> Self {
        let elevation_sin_cos = elevations_deg(config)
            .into_iter()
            .map(|e| {
                let (s, c) = e.to_radians().sin_cos();
                (s as f32, c as f32)
            })
            .collect();
        let azimuth_sin_cos = (0..config.azimuth_steps)
            .map(|j| {
                let (s, c) = azimuth_rad(j, config.azimuth_steps).sin_cos();
                (s as f32, c as f32)
            })
            .collect();
        Self {
            config: config.clone(),
            elevation_sin_cos,
            azimuth_sin_cos,
        }
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
        self.azimuth_sin_cos
            .iter()
            .flat_map(|&(sa, ca)| {
                self.elevation_sin_cos
                    .iter()
                    .map(move |&(se, ce)| [ce * ca, ce * sa, se])
            })
            .collect()
    }

    /// Casts one sweep starting at scenario time `start_secs` (the reference time). With the
    /// rolling shutter on, azimuth block `b` is cast with the scene moved to the block's middle
    /// instant; otherwise the whole sweep sees the scene at `start_secs`. Noise is drawn from one
    /// stream per column derived from `noise_key`, so the result does not depend on threads.
    pub fn scan(&self, scene: &mut Scene, start_secs: f64, noise_key: u64) -> Scan {
        let period = self.config.period_secs();
        let steps = self.config.azimuth_steps;
        let blocks = if self.config.rolling_shutter {
            self.config.blocks.max(1)
        } else {
            1
        };
        let ego_ref = scene.ego().trajectory.state_at(start_secs);
        let sensor_from_world_ref = self.world_from_sensor(&ego_ref).inverse();
        let rays = self.azimuth_sin_cos.len() * self.elevation_sin_cos.len();
        let mut scan = Scan {
            points_in_sensor: Vec::with_capacity(rays),
            intensities: Vec::with_capacity(rays),
            labels: Vec::with_capacity(rays),
            flow_in_world_mps: Vec::with_capacity(rays),
            time_in_sweep_secs: Vec::with_capacity(rays),
            actor_point_counts: vec![0; scene.actors().len()],
        };
        for b in 0..blocks {
            let (first, end) = (b * steps / blocks, (b + 1) * steps / blocks);
            let offset_secs = if self.config.rolling_shutter {
                period * (f64::from(first) + f64::from(end)) / 2.0 / f64::from(steps)
            } else {
                0.0
            };
            let t = start_secs + offset_secs;
            scene.move_to(t);
            let states: Vec<MotionState> = scene
                .actors()
                .iter()
                .map(|a| a.trajectory.state_at(t))
                .collect();
            let ego = scene.ego().trajectory.state_at(t);
            let block = Block {
                time_in_sweep_secs: offset_secs as f32,
                origin: Vector::new(
                    ego.position_m[0] as f32,
                    ego.position_m[1] as f32,
                    self.config.mount_height_m as f32,
                ),
                yaw_cos_sin: (ego.yaw_rad.cos() as f32, ego.yaw_rad.sin() as f32),
                states: &states,
                sensor_from_world_ref: &sensor_from_world_ref,
                noise_key,
            };
            let scene_ref: &Scene = scene;
            let block_returns: Vec<Vec<Return>> = (first..end)
                .into_par_iter()
                .map(|j| self.cast_column(scene_ref, &scene_ref.query_pipeline(), &block, j))
                .collect();
            let time = block.time_in_sweep_secs;
            for r in block_returns.iter().flatten() {
                scan.points_in_sensor.push(r.point_in_sensor);
                scan.intensities.push(r.intensity);
                scan.labels.push(r.label);
                scan.flow_in_world_mps.push(r.flow_mps);
                scan.time_in_sweep_secs.push(time);
                if let Some(count) = r.actor.and_then(|a| scan.actor_point_counts.get_mut(a)) {
                    *count += 1;
                }
            }
        }
        scan
    }

    /// Casts the rays of azimuth column `j` and turns hits into labelled returns.
    fn cast_column(
        &self,
        scene: &Scene,
        qp: &QueryPipeline<'_>,
        block: &Block<'_>,
        j: u32,
    ) -> Vec<Return> {
        let mut rng = ChaCha8Rng::seed_from_u64(sub_seed(block.noise_key, u64::from(j)));
        let (sa, ca) = self.azimuth_sin_cos[j as usize];
        let (cy, sy) = block.yaw_cos_sin;
        let max_range = self.config.max_range_m as f32;
        let noise_std = self.config.range_noise_std_m as f32;
        let dropout = self.config.dropout_probability as f32;
        let attenuation = self.config.attenuation_per_m as f32;
        let mut out = Vec::with_capacity(self.elevation_sin_cos.len());
        for &(se, ce) in &self.elevation_sin_cos {
            let (dx, dy) = (ce * ca, ce * sa);
            let dir = Vector::new(cy * dx - sy * dy, sy * dx + cy * dy, se);
            let Some((handle, toi)) = qp.cast_ray(&Ray::new(block.origin, dir), max_range, true)
            else {
                continue;
            };
            if toi < MIN_RANGE_M {
                continue;
            }
            if dropout > 0.0 && rng.random::<f32>() < dropout {
                continue;
            }
            let noise = if noise_std > 0.0 {
                noise_std * rng.sample::<f32, _>(StandardNormal)
            } else {
                0.0
            };
            let Some((surface, pose)) = scene.surface(handle) else {
                continue;
            };
            let hit = block.origin + dir * toi;
            let cos_incidence = dir.dot(surface.normal_at(pose, hit));
            let measured = block.origin + dir * (toi + noise).max(0.0);
            let in_sensor = block.sensor_from_world_ref
                * Point3::new(
                    f64::from(measured.x),
                    f64::from(measured.y),
                    f64::from(measured.z),
                );
            let (label, flow_mps) = match surface
                .actor
                .and_then(|a| block.states.get(a).map(|s| (a, s)))
            {
                Some((a, state)) => {
                    let v = state.velocity_at_mps([f64::from(hit.x), f64::from(hit.y)]);
                    let class = scene.actors()[a].class.semantic(state.speed_mps >= 0.05);
                    (
                        PointLabel::new(class, scene.actors()[a].id),
                        [v[0] as f32, v[1] as f32, 0.0],
                    )
                }
                None => (PointLabel::new(surface.semantic, 0), [0.0; 3]),
            };
            out.push(Return {
                point_in_sensor: [in_sensor.x as f32, in_sensor.y as f32, in_sensor.z as f32],
                intensity: intensity(surface.reflectivity, cos_incidence, toi, attenuation),
                label,
                flow_mps,
                actor: surface.actor,
            });
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use crate::{Scenario, Simulation};

    /// A car 6 m ahead drives across the view at 15 m/s in the direction the beam sweeps.
    fn crossing(rolling: bool) -> patchflow_dataset::Sweep {
        let text = format!(
            "sweeps = 1\n[lidar]\nchannels = 8\nupper_deg = -4.0\nlower_deg = -12.0\nspacing = \"uniform\"\nazimuth_steps = 3600\nblocks = 3600\nrange_noise_std_m = 0.0\nrolling_shutter = {rolling}\n[ego]\npath_m = [[0.0, 0.0], [1.0, 0.0]]\nspeed_mps = 0.0\n[[actors]]\nname = \"car\"\ntarget = true\npath_m = [[6.0, 30.0], [6.0, -30.0]]\nspeed_mps = 15.0\nstart_secs = -1.95\n"
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
