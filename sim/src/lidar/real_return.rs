//! The realistic return of one beam: the first surface it meets, what that surface is made of
//! (box faces, the ground's triangles and materials, parry's normal for other shapes), foliage it
//! may enter and scatter inside or pass through, glass it may pass or be lost on, whether the
//! sensor detects what comes back ([`SensorModel::detection_probability`]), range noise growing
//! with range, and the channel's intensity gain. Labels and flow are those of the surface hit.

use rand::RngExt;
use rand::rngs::Xoshiro256PlusPlus;
use rand_distr::StandardNormal;
use rapier3d::prelude::{Ray, Vector};

use super::block_caster::{BlockCaster, MIN_RANGE_M, rotate_z};
use super::intensity::intensity;
use super::scan::Return;
use rapier3d::parry::shape::FeatureId;

use crate::scene::{Glass, HitPart, SurfaceKind};
use crate::world::GLASS_FEATURE;

/// Most surfaces a beam passes (foliage) before it is given up.
const MAX_PASSES: usize = 3;
/// Share of glass hits that return nothing.
const GLASS_LOST: f32 = 0.45;
/// Share of glass hits that return from behind the pane (the interior).
const GLASS_PASSED: f32 = 0.25;

/// The share of a ground footprint hit at `cos_incidence` that its grit, aggregate and tufts do
/// not shadow from the sensor. Rough ground is not Lambertian at grazing incidence: beyond about
/// 70° from the normal the backscatter of asphalt, gravel and grass falls faster than the cosine
/// (the grains hide each other's lit faces), which is why real HDL-64E sweeps lose the road's far
/// rings first. Modelled as one more cosine factor (Smith-like masking at small grazing angles),
/// saturating at 1 above 45°; the intensity keeps the plain Lambertian cosine.
#[inline]
fn ground_visible_share(cos_incidence: f32) -> f32 {
    (cos_incidence.abs() * std::f32::consts::SQRT_2).min(1.0)
}

impl BlockCaster<'_> {
    /// The labelled return of the beam of channel `channel` (ring `ring`), cast along `ray`
    /// (its true direction) and written along `in_sensor` (its nominal direction).
    pub(super) fn cast_ray_real(
        &self,
        channel: usize,
        ring: u16,
        in_sensor: Vector,
        ray: &Ray,
        rng: &mut Xoshiro256PlusPlus,
    ) -> Option<Return> {
        let dir = ray.dir;
        let mut segment = *ray;
        let mut travelled = 0.0f32;
        for _ in 0..MAX_PASSES {
            let (surface, toi, part, normal) = self
                .query
                .cast_ray_to_hit(&segment, self.max_range_m - travelled)?;
            let mut range = travelled + toi;
            if range < MIN_RANGE_M {
                return None;
            }
            let hit = segment.origin + dir * toi;
            let mut semantic = surface.semantic;
            let (mut reflectivity, mut cos) = (surface.reflectivity, 1.0f32);
            let mut glass = surface.material.glass == Glass::All;
            // Share of the lit footprint that the surface's own relief leaves visible to the
            // sensor (1 for smooth faces); see GROUND_SHADOWING below.
            let mut visible = 1.0f32;
            match surface.kind {
                SurfaceKind::Box => cos = surface.cos_incidence(hit, dir),
                SurfaceKind::Ground => {
                    if let Some(ground) = self.query.scene().ground() {
                        let (n, material, r) = ground.surface_at(hit.x, hit.y);
                        cos = (n[0] * dir.x + n[1] * dir.y + n[2] * dir.z).abs();
                        semantic = material.semantic();
                        reflectivity = r;
                        visible = ground_visible_share(cos);
                    }
                }
                SurfaceKind::Shape => {
                    let (n, feature) = normal
                        .or_else(|| self.query.normal(part, &segment, toi))
                        .unwrap_or((-dir, FeatureId::Unknown));
                    cos = n.dot(dir).abs();
                    glass |= match surface.material.glass {
                        Glass::Sides => n.z.abs() < 0.7,
                        Glass::Windows => feature == GLASS_FEATURE,
                        Glass::All | Glass::None => false,
                    };
                }
            }
            if surface.material.porous_m > 0.0 {
                // Leaves at exponential depths: the beam scatters inside or passes through.
                let depth = -surface.material.porous_m * (1.0 - rng.random::<f32>()).ln();
                let inside = Ray::new(hit + dir * 1e-3, dir);
                let exit = self.query.exit_toi(part, &inside, 20.0).unwrap_or(0.0);
                if depth >= exit {
                    travelled = range + exit + 2e-3;
                    segment = Ray::new(inside.origin + dir * (exit + 1e-3), dir);
                    continue;
                }
                range += depth;
                cos = rng.random_range(0.2..1.0);
            }
            if glass {
                let u = rng.random::<f32>();
                if u < GLASS_LOST {
                    return None;
                }
                if u < GLASS_LOST + GLASS_PASSED {
                    range += self.behind_pane_m(part, hit, dir, rng.random_range(1.0..5.0));
                    reflectivity = 0.3;
                    cos = 0.7;
                }
            }
            let u = rng.random::<f32>();
            if !self.sensor.detects(reflectivity * visible, cos, range, u) {
                return None;
            }
            // `[lidar] dropout_probability` on top of the rung's physical ray drop (drawn only
            // when set, so a rung's sweeps without it are unchanged).
            if self.dropout > 0.0 && rng.random::<f32>() < self.dropout {
                return None;
            }
            let std = self.noise_std_m + self.sensor.extra_noise_std_m(range);
            let noisy = (range + std * rng.sample::<f32, _>(StandardNormal)).max(0.0);
            let point = self.origin_in_reference
                + rotate_z(self.yaw_since_reference_cos_sin, in_sensor) * noisy;
            let (label, flow_mps) = self.label_and_flow(surface.actor, semantic, hit);
            let gain = self.sensor.gain(channel);
            return Some(Return {
                point_in_sensor: [point.x, point.y, point.z],
                intensity: (gain * intensity(reflectivity, cos, range, self.attenuation_per_m))
                    .min(1.0),
                label,
                flow_mps,
                time_in_sweep_secs: self.time_in_sweep_secs,
                ring,
                range_m: noisy,
            });
        }
        None
    }

    /// How far behind a glass pane hit at `hit` a passing beam returns from the interior:
    /// `depth_m`, but never past the far side of what it hit (a car's cabin) nor below the
    /// ground (a descending beam through a low window would otherwise return from under the
    /// road, as it once did: 0.5-1.3 m down).
    fn behind_pane_m(&self, part: HitPart, hit: Vector, dir: Vector, depth_m: f32) -> f32 {
        let inside = Ray::new(hit + dir * 1e-3, dir);
        let mut depth = depth_m;
        if let Some(exit) = self.query.exit_toi(part, &inside, depth) {
            depth = depth.min(exit);
        }
        if let Some(ground) = self.query.scene().ground() {
            let o = inside.origin;
            if let Some((t, _)) = ground.cast([o.x, o.y, o.z], [dir.x, dir.y, dir.z], depth) {
                depth = depth.min(t);
            }
        }
        depth + 1e-3
    }
}
