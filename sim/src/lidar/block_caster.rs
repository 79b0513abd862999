//! Casting one azimuth block into the scene at the block's instant: everything the rays of the
//! block share is computed once (sensor origin and yaw, the rotation into the reference sensor
//! frame, the movers' poses and each actor's label), so the work per ray is one `cast_ray` plus a
//! few flops. The casters of all blocks of a sweep exist at once, so every column of the sweep
//! can be cast in one parallel loop.

use patchflow_dataset::PointLabel;
use rand::rngs::Xoshiro256PlusPlus;
use rand::{RngExt, SeedableRng};
use rand_distr::StandardNormal;
use rapier3d::prelude::{Ray, Vector};

use super::firing_table::FiringTable;
use super::intensity::intensity;
use super::scan::{ColumnSlots, Return};
use crate::motion::MotionState;
use crate::scenario::LidarConfig;
use crate::scene::InstantQuery;
use crate::seed::sub_seed;
use crate::simulation::MOVING_SPEED_MPS;

/// Rays shorter than this (the origin inside a shape) are not returns, metres.
const MIN_RANGE_M: f32 = 0.05;

/// World rays written ahead of casting (a whole HDL-64E column).
const RAY_BATCH: usize = 64;

/// What every ray of one azimuth block shares.
pub(super) struct BlockCaster<'a> {
    /// Ray queries against the scene at the block's instant.
    query: InstantQuery<'a>,
    table: &'a FiringTable,
    time_in_sweep_secs: f32,
    /// Sensor origin at the block's instant, world frame.
    origin: Vector,
    /// Sensor yaw at the block's instant, (cos, sin): sensor frame → world directions.
    yaw_cos_sin: (f32, f32),
    /// The same origin in the reference sensor frame (the sweep start).
    origin_in_reference: Vector,
    /// Yaw change since the reference, (cos, sin): sensor frame → reference sensor frame.
    yaw_since_reference_cos_sin: (f32, f32),
    /// Label of every actor at the block's instant (moving class once it moves).
    actor_labels: Vec<PointLabel>,
    max_range_m: f32,
    noise_std_m: f32,
    dropout: f32,
    attenuation_per_m: f32,
    noise_key: u64,
}

impl<'a> BlockCaster<'a> {
    /// The shared facts of a block cast at `time_in_sweep_secs` through `query`, the scene at
    /// that instant; `ego` is the ego state then and `ego_ref` the ego state at the sweep start
    /// (the reference sensor frame: above the ego centre at the mount height, yawed with it).
    pub(super) fn new(
        query: InstantQuery<'a>,
        table: &'a FiringTable,
        config: &LidarConfig,
        time_in_sweep_secs: f64,
        ego: &MotionState,
        ego_ref: &MotionState,
        noise_key: u64,
    ) -> Self {
        let (s, c) = ego.yaw_rad.sin_cos();
        let (s_ref, c_ref) = ego_ref.yaw_rad.sin_cos();
        let (sd, cd) = (ego.yaw_rad - ego_ref.yaw_rad).sin_cos();
        let dx = ego.position_m[0] - ego_ref.position_m[0];
        let dy = ego.position_m[1] - ego_ref.position_m[1];
        let mount_m = config.mount_height_m as f32;
        let states = query.actor_states();
        let actor_labels = query
            .scene()
            .actors()
            .iter()
            .zip(states)
            .map(|(a, s)| PointLabel::new(a.class.semantic(s.speed_mps >= MOVING_SPEED_MPS), a.id))
            .collect();
        Self {
            query,
            table,
            time_in_sweep_secs: time_in_sweep_secs as f32,
            origin: Vector::new(ego.position_m[0] as f32, ego.position_m[1] as f32, mount_m),
            yaw_cos_sin: (c as f32, s as f32),
            origin_in_reference: Vector::new(
                (c_ref * dx + s_ref * dy) as f32,
                (c_ref * dy - s_ref * dx) as f32,
                0.0,
            ),
            yaw_since_reference_cos_sin: (cd as f32, sd as f32),
            actor_labels,
            max_range_m: config.max_range_m as f32,
            noise_std_m: config.range_noise_std_m as f32,
            dropout: config.dropout_probability as f32,
            attenuation_per_m: config.attenuation_per_m as f32,
            noise_key,
        }
    }

    /// Casts the rays of azimuth column `j` and writes its labelled returns. Dropout and range
    /// noise come from one stream per column (seeded from the sweep key and `j`), so the result
    /// does not depend on which thread casts the column.
    ///
    /// The world rays are written in batches before any is cast: parry reads each ray back
    /// from memory, and a ray stored just before (as one per loop turn would be) cannot be
    /// forwarded from the store buffer to that wider load, which then waits for the store.
    pub(super) fn cast_column(&self, j: usize, out: &mut ColumnSlots<'_>) {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(sub_seed(self.noise_key, j as u64));
        let mut rays = [Ray::new(self.origin, Vector::ZERO); RAY_BATCH];
        for batch in self.table.column(j).chunks(RAY_BATCH) {
            for (ray, &in_sensor) in rays.iter_mut().zip(batch) {
                ray.dir = rotate_z(self.yaw_cos_sin, in_sensor);
            }
            out.extend(
                batch
                    .iter()
                    .zip(&rays)
                    .filter_map(|(&in_sensor, ray)| self.cast_ray(in_sensor, ray, &mut rng)),
            );
        }
    }

    /// The labelled return of one ray (`ray`, whose direction in the sensor frame is
    /// `in_sensor`), if it hits something.
    #[inline]
    fn cast_ray(
        &self,
        in_sensor: Vector,
        ray: &Ray,
        rng: &mut Xoshiro256PlusPlus,
    ) -> Option<Return> {
        let dir = ray.dir;
        let (surface, toi) = self
            .query
            .cast_ray_to_surface(ray, self.max_range_m, true)?;
        if toi < MIN_RANGE_M {
            return None;
        }
        if self.dropout > 0.0 && rng.random::<f32>() < self.dropout {
            return None;
        }
        let noise_m = if self.noise_std_m > 0.0 {
            self.noise_std_m * rng.sample::<f32, _>(StandardNormal)
        } else {
            0.0
        };
        let hit = self.origin + dir * toi;
        let range_m = (toi + noise_m).max(0.0);
        let point = self.origin_in_reference
            + rotate_z(self.yaw_since_reference_cos_sin, in_sensor) * range_m;
        let states = self.query.actor_states();
        let (label, flow_mps) = match surface
            .actor
            .and_then(|a| Some((*self.actor_labels.get(a)?, states.get(a)?)))
        {
            Some((label, state)) => {
                let v = state.velocity_at_mps([f64::from(hit.x), f64::from(hit.y)]);
                (label, [v[0] as f32, v[1] as f32, 0.0])
            }
            None => (PointLabel::new(surface.semantic, 0), [0.0; 3]),
        };
        Some(Return {
            point_in_sensor: [point.x, point.y, point.z],
            intensity: intensity(
                surface.reflectivity,
                surface.cos_incidence(hit, dir),
                toi,
                self.attenuation_per_m,
            ),
            label,
            flow_mps,
            time_in_sweep_secs: self.time_in_sweep_secs,
        })
    }
}

/// Rotates `v` about z by the angle with the given (cos, sin).
#[inline]
fn rotate_z((c, s): (f32, f32), v: Vector) -> Vector {
    Vector::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z)
}
