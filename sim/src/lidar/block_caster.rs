//! Casting one azimuth block into the scene at the block's instant: everything the rays of the
//! block share is computed once (sensor origin and yaw, the rotation into the reference sensor
//! frame, the movers' poses and each actor's label), so the work per ray is one `cast_ray` plus a
//! few flops. The casters of all blocks of a sweep exist at once, so every column of the sweep
//! can be cast in one parallel loop. The `ideal` world with the ideal sensor takes the path of
//! the first release ([`BlockCaster::cast_ray`], byte for byte); any other world or sensor the
//! realistic one ([`BlockCaster::cast_ray_real`], in `real_return.rs`).

use patchflow_dataset::{PointLabel, SemanticClass};
use rand::rngs::Xoshiro256PlusPlus;
use rand::{RngExt, SeedableRng};
use rand_distr::StandardNormal;
use rapier3d::prelude::{Ray, Vector};

use super::firing_table::FiringTable;
use super::intensity::intensity;
use super::scan::{ColumnSlots, Return};
use super::sensor_model::SensorModel;
use crate::motion::{MOVING_SPEED_MPS, MotionState};
use crate::scenario::LidarConfig;
use crate::scene::InstantQuery;
use crate::seed::sub_seed;

/// Rays shorter than this (the origin inside a shape) are not returns, metres.
pub(super) const MIN_RANGE_M: f32 = 0.05;

/// The ego's true and estimated states at a block's instant and at the sweep's reference time:
/// the beams leave from the true pose, the points are compensated with the estimated ones.
#[derive(Debug, Clone, Copy)]
pub(super) struct EgoStates {
    pub block: MotionState,
    pub block_estimate: MotionState,
    pub reference_estimate: MotionState,
}

/// World rays written ahead of casting (a whole HDL-64E column).
const RAY_BATCH: usize = 64;

/// What every ray of one azimuth block shares.
pub(super) struct BlockCaster<'a> {
    /// Ray queries against the scene at the block's instant.
    pub(super) query: InstantQuery<'a>,
    pub(super) table: &'a FiringTable,
    pub(super) sensor: &'a SensorModel,
    /// Take the realistic path (any world or sensor but the ideal ones).
    realistic: bool,
    pub(super) time_in_sweep_secs: f32,
    /// Sensor origin at the block's instant, world frame.
    pub(super) origin: Vector,
    /// Sensor yaw at the block's instant, (cos, sin): sensor frame → world directions.
    yaw_cos_sin: (f32, f32),
    /// The same origin in the reference sensor frame (the sweep start), as the ego estimates it.
    pub(super) origin_in_reference: Vector,
    /// Yaw change since the reference as the ego estimates it, (cos, sin): sensor frame →
    /// reference sensor frame.
    pub(super) yaw_since_reference_cos_sin: (f32, f32),
    /// Label of every actor at the block's instant (moving class once it moves).
    pub(super) actor_labels: Vec<PointLabel>,
    pub(super) max_range_m: f32,
    pub(super) noise_std_m: f32,
    pub(super) dropout: f32,
    pub(super) attenuation_per_m: f32,
    noise_key: u64,
}

impl<'a> BlockCaster<'a> {
    /// The shared facts of a block cast at `time_in_sweep_secs` through `query`, the scene at
    /// that instant; `ego` holds the ego's true and estimated states then and at the sweep start
    /// (the reference sensor frame: above the ego centre at the mount height, yawed with it).
    pub(super) fn new(
        query: InstantQuery<'a>,
        (table, sensor, realistic): (&'a FiringTable, &'a SensorModel, bool),
        config: &LidarConfig,
        time_in_sweep_secs: f64,
        ego: &EgoStates,
        noise_key: u64,
    ) -> Self {
        let (s, c) = ego.block.yaw_rad.sin_cos();
        let (estimate, reference) = (&ego.block_estimate, &ego.reference_estimate);
        let (s_ref, c_ref) = reference.yaw_rad.sin_cos();
        let (sd, cd) = (estimate.yaw_rad - reference.yaw_rad).sin_cos();
        let dx = estimate.position_m[0] - reference.position_m[0];
        let dy = estimate.position_m[1] - reference.position_m[1];
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
            sensor,
            realistic,
            time_in_sweep_secs: time_in_sweep_secs as f32,
            origin: Vector::new(
                ego.block.position_m[0] as f32,
                ego.block.position_m[1] as f32,
                mount_m,
            ),
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
        let channels = self.table.channels();
        let cast = self.table.cast_column(j);
        for (b, batch) in self.table.column(j).chunks(RAY_BATCH).enumerate() {
            let first = b * RAY_BATCH;
            for (ray, &dir) in rays.iter_mut().zip(&cast[first..]) {
                ray.dir = rotate_z(self.yaw_cos_sin, dir);
            }
            let ring = |k: usize| (channels - 1 - (first + k)) as u16;
            if self.realistic {
                let occluded = self.table.occluded_column(j);
                out.extend(batch.iter().zip(&rays).enumerate().filter_map(
                    |(k, (&in_sensor, ray))| {
                        if occluded.is_some_and(|o| o[first + k]) {
                            return None;
                        }
                        self.cast_ray_real(first + k, ring(k), in_sensor, ray, &mut rng)
                    },
                ));
            } else {
                out.extend(batch.iter().zip(&rays).enumerate().filter_map(
                    |(k, (&in_sensor, ray))| self.cast_ray(ring(k), in_sensor, ray, &mut rng),
                ));
            }
        }
    }

    /// The labelled return of one ray (`ray`, whose direction in the sensor frame is
    /// `in_sensor`), if it hits something.
    #[inline]
    fn cast_ray(
        &self,
        ring: u16,
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
        let (label, flow_mps) = self.label_and_flow(surface.actor, surface.semantic, hit);
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
            ring,
            range_m,
        })
    }

    /// The label and true flow of a hit at world point `hit`: an actor's label and its rigid
    /// velocity there, or the static class `semantic` and no flow.
    #[inline]
    pub(super) fn label_and_flow(
        &self,
        actor: Option<usize>,
        semantic: SemanticClass,
        hit: Vector,
    ) -> (PointLabel, [f32; 3]) {
        let states = self.query.actor_states();
        match actor.and_then(|a| Some((*self.actor_labels.get(a)?, states.get(a)?))) {
            Some((label, state)) => {
                let v = state.velocity_at_mps([f64::from(hit.x), f64::from(hit.y)]);
                (label, [v[0] as f32, v[1] as f32, 0.0])
            }
            None => (PointLabel::new(semantic, 0), [0.0; 3]),
        }
    }
}

/// Rotates `v` about z by the angle with the given (cos, sin).
#[inline]
pub(super) fn rotate_z((c, s): (f32, f32), v: Vector) -> Vector {
    Vector::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z)
}
