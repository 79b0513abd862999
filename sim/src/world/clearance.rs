//! Where procedural clutter may stand: off every actor's swept corridor (sampled from the exact
//! trajectories), off the scenario's own structures, and clear of clutter placed before.

use crate::scenario::{ActorConfig, StructureConfig};

/// A structure's footprint: centre, half extents, (cos, sin) of its yaw.
#[derive(Debug, Clone, Copy)]
struct Footprint {
    centre: [f64; 2],
    half: [f64; 2],
    yaw_cos_sin: (f64, f64),
}

/// Free space bookkeeping for clutter placement.
#[derive(Debug, Default)]
pub(crate) struct Clearance {
    /// Segments swept by an actor's centre, with the actor's half width, metres.
    corridors: Vec<([f64; 2], [f64; 2], f64)>,
    /// Footprints of the scenario's structures.
    footprints: Vec<Footprint>,
    /// Clutter placed so far: centre and radius.
    placed: Vec<([f64; 2], f64)>,
}

impl Clearance {
    /// The corridors of `movers` between `t0` and `t1` and the footprints of `structures`.
    pub(crate) fn new(
        movers: &[&ActorConfig],
        structures: &[StructureConfig],
        t0: f64,
        t1: f64,
    ) -> Self {
        let mut out = Self::default();
        for actor in movers {
            let Ok(trajectory) = actor.trajectory() else {
                continue;
            };
            let half_width = actor.size_m.map_or(1.0, |s| s[1] / 2.0);
            let steps = ((t1 - t0) / 0.2).ceil().max(1.0) as usize;
            let mut previous: Option<[f64; 2]> = None;
            for k in 0..=steps {
                let p = trajectory
                    .state_at(t0 + (t1 - t0) * k as f64 / steps as f64)
                    .position_m;
                if let Some(q) = previous {
                    out.corridors.push((q, p, half_width));
                }
                previous = Some(p);
            }
        }
        for s in structures {
            let size = s.size_m.unwrap_or(s.kind.default_size());
            let (sin, cos) = s.yaw_deg.to_radians().sin_cos();
            for c in s.centres_m() {
                out.footprints.push(Footprint {
                    centre: c,
                    half: [size[0] / 2.0, size[1] / 2.0],
                    yaw_cos_sin: (cos, sin),
                });
            }
        }
        out
    }

    /// True if an item at `p` keeps `margin_m` from structures and earlier clutter (as a disc of
    /// `radius_m`) and from the actors' corridors (with its half width `lateral_m` across them).
    pub(crate) fn is_free(
        &self,
        p: [f64; 2],
        radius_m: f64,
        lateral_m: f64,
        margin_m: f64,
    ) -> bool {
        let corridor_free = self
            .corridors
            .iter()
            .all(|&(a, b, w)| segment_distance(p, a, b) > w + lateral_m + margin_m);
        let structure_free = self.footprints.iter().all(|f| {
            let (c, h, (cos, sin)) = (f.centre, f.half, f.yaw_cos_sin);
            let (dx, dy) = (p[0] - c[0], p[1] - c[1]);
            let (u, v) = (cos * dx + sin * dy, -sin * dx + cos * dy);
            u.abs() > h[0] + radius_m + margin_m || v.abs() > h[1] + radius_m + margin_m
        });
        corridor_free
            && structure_free
            && self
                .placed
                .iter()
                .all(|&(q, r)| (p[0] - q[0]).hypot(p[1] - q[1]) > r + radius_m + margin_m)
    }

    /// Records an item placed at `p`.
    pub(crate) fn occupy(&mut self, p: [f64; 2], radius_m: f64) {
        self.placed.push((p, radius_m));
    }
}

/// Distance from `p` to the segment `a`–`b`.
pub(crate) fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length2 = dx * dx + dy * dy;
    let t = if length2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scenario;

    #[test]
    fn clutter_keeps_off_a_drivers_corridor_and_off_earlier_clutter() {
        let text = "sweeps = 1\n[ego]\npath_m = [[0.0, 0.0], [100.0, 0.0]]\nspeed_mps = 5.0\n";
        let scenario = Scenario::from_toml(text, "c.toml", "c").unwrap();
        let mut clearance = Clearance::new(&[&scenario.ego], &[], 0.0, 10.0);
        assert!(
            !clearance.is_free([20.0, 1.0], 0.3, 0.3, 0.3),
            "inside the ego's corridor"
        );
        assert!(clearance.is_free([20.0, 3.0], 0.3, 0.3, 0.3));
        clearance.occupy([20.0, 3.0], 0.3);
        assert!(!clearance.is_free([20.5, 3.0], 0.3, 0.3, 0.3));
    }
}
