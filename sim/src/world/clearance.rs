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

/// How far apart two bounding boxes must be, beyond the clearance asked for, before their
/// contents count as clear without their exact distance, metres: far above the distances'
/// rounding (1e-13 m at a kilometre), so the shortcut decides as the exact test would.
const SURELY_APART_M: f64 = 1e-6;

/// An axis-aligned bounding box: min x, min y, max x, max y.
type Bounds = [f64; 4];

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
    /// `radius_m`) and its `body` from the actors' corridors. The body counts with its shape, a
    /// stadium of its length and width: a parked car lying along a street is 1 m wide to a
    /// driver on that street but half a car long to a cyclist or pedestrian crossing past its
    /// end.
    pub(crate) fn is_free(
        &self,
        p: [f64; 2],
        radius_m: f64,
        body: ItemExtent,
        margin_m: f64,
    ) -> bool {
        let (axis_a, axis_b) = body.axis(p);
        let axis_bounds = bounds(axis_a, axis_b);
        // A corridor segment far from the item by its bounding box needs no exact distance
        // (clutter placement tests thousands of spots against every segment of a long route).
        let corridor_free = self.corridors.iter().all(|&(a, b, w)| {
            let clearance = w + body.half_across_m + margin_m;
            gap(&axis_bounds, &bounds(a, b)) > clearance + SURELY_APART_M
                || segments_distance((axis_a, axis_b), (a, b)) > clearance
        });
        let structure_free = self.footprints.iter().all(|f| {
            let (c, h, (cos, sin)) = (f.centre, f.half, f.yaw_cos_sin);
            let (dx, dy) = (p[0] - c[0], p[1] - c[1]);
            let (u, v) = (cos * dx + sin * dy, -sin * dx + cos * dy);
            u.abs() > h[0] + radius_m + margin_m || v.abs() > h[1] + radius_m + margin_m
        });
        corridor_free
            && structure_free
            && self.placed.iter().all(|&(q, r)| {
                let (dx, dy, clearance) = (p[0] - q[0], p[1] - q[1], r + radius_m + margin_m);
                dx.abs().max(dy.abs()) > clearance + SURELY_APART_M || dx.hypot(dy) > clearance
            })
    }

    /// Records an item placed at `p`.
    pub(crate) fn occupy(&mut self, p: [f64; 2], radius_m: f64) {
        self.placed.push((p, radius_m));
    }
}

/// What an item occupies around its centre: half its length along `yaw_rad` and half its width
/// across.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ItemExtent {
    /// Half the length along `yaw_rad`, metres.
    pub half_along_m: f64,
    /// Half the width across `yaw_rad`, metres.
    pub half_across_m: f64,
    /// The direction of its length, radians.
    pub yaw_rad: f64,
}

impl ItemExtent {
    /// A round item of radius `radius_m`.
    pub(crate) fn disc(radius_m: f64) -> Self {
        Self {
            half_along_m: radius_m,
            half_across_m: radius_m,
            yaw_rad: 0.0,
        }
    }

    /// The ends of the item's axis when it stands at `p`: the segment whose points within its
    /// half width make up the item (a stadium; one point for a disc).
    fn axis(&self, p: [f64; 2]) -> ([f64; 2], [f64; 2]) {
        let half = (self.half_along_m - self.half_across_m).max(0.0);
        let (sin, cos) = self.yaw_rad.sin_cos();
        let d = [half * cos, half * sin];
        ([p[0] - d[0], p[1] - d[1]], [p[0] + d[0], p[1] + d[1]])
    }
}

/// The bounding box of the segment `a`–`b`.
fn bounds(a: [f64; 2], b: [f64; 2]) -> Bounds {
    [
        a[0].min(b[0]),
        a[1].min(b[1]),
        a[0].max(b[0]),
        a[1].max(b[1]),
    ]
}

/// The larger of the gaps between two boxes along x and along y (negative where they overlap
/// on both): no point of one box is nearer to the other than this.
fn gap(a: &Bounds, b: &Bounds) -> f64 {
    (a[0] - b[2])
        .max(b[0] - a[2])
        .max(a[1] - b[3])
        .max(b[1] - a[3])
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

/// Distance between two segments: 0 if they cross, else the nearest of their ends to the
/// other segment.
fn segments_distance((a, b): ([f64; 2], [f64; 2]), (c, d): ([f64; 2], [f64; 2])) -> f64 {
    let side = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    };
    let crosses = side(a, b, c) * side(a, b, d) < 0.0 && side(c, d, a) * side(c, d, b) < 0.0;
    if crosses {
        return 0.0;
    }
    segment_distance(a, c, d)
        .min(segment_distance(b, c, d))
        .min(segment_distance(c, a, b))
        .min(segment_distance(d, a, b))
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
            !clearance.is_free([20.0, 1.0], 0.3, ItemExtent::disc(0.3), 0.3),
            "inside the ego's corridor"
        );
        assert!(clearance.is_free([20.0, 3.0], 0.3, ItemExtent::disc(0.3), 0.3));
        clearance.occupy([20.0, 3.0], 0.3);
        assert!(!clearance.is_free([20.5, 3.0], 0.3, ItemExtent::disc(0.3), 0.3));
    }

    /// A parked car (5.2 m long, 2 m wide) lying along the x axis.
    fn parked_car() -> ItemExtent {
        ItemExtent {
            half_along_m: 2.6,
            half_across_m: 1.0,
            yaw_rad: 0.0,
        }
    }

    #[test]
    fn a_parked_car_keeps_its_length_off_a_cyclists_corridor_that_crosses_past_its_end() {
        // The cyclist rides along x = 22.5; a car centred 2.5 m away along its own length would
        // reach x = 22.6, into the corridor. Its 1 m half width alone would let it stand there.
        let text = "sweeps = 1\n[ego]\npath_m = [[0.0, -30.0], [1.0, -30.0]]\nspeed_mps = 0.0\n\
                    [[actors]]\nname = \"bike\"\nclass = \"cyclist\"\n\
                    path_m = [[22.5, 30.0], [22.5, -30.0]]\nspeed_mps = 5.0\n";
        let scenario = Scenario::from_toml(text, "c.toml", "c").unwrap();
        let clearance = Clearance::new(&[&scenario.actors[0]], &[], 0.0, 12.0);
        assert!(!clearance.is_free([20.0, 3.0], 2.6, parked_car(), 0.3));
        assert!(clearance.is_free([19.0, 3.0], 2.6, parked_car(), 0.3));
    }

    #[test]
    fn a_parked_car_beside_a_drivers_corridor_counts_with_its_width_only() {
        let text = "sweeps = 1\n[ego]\npath_m = [[0.0, 0.0], [100.0, 0.0]]\nspeed_mps = 5.0\n";
        let scenario = Scenario::from_toml(text, "c.toml", "c").unwrap();
        let clearance = Clearance::new(&[&scenario.ego], &[], 0.0, 10.0);
        let w = scenario.ego.size_m.map_or(1.0, |s| s[1] / 2.0); // the corridor's half width
        assert!(clearance.is_free([20.0, w + 1.0 + 0.35], 2.6, parked_car(), 0.3));
        assert!(!clearance.is_free([20.0, w + 1.0 + 0.25], 2.6, parked_car(), 0.3));
    }

    #[test]
    fn the_gap_between_bounding_boxes_never_exceeds_the_segments_distance() {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let mut point = || [rng.random_range(-50.0..50.0), rng.random_range(-50.0..50.0)];
        for _ in 0..20_000 {
            let (a, b, c, d) = (point(), point(), point(), point());
            let exact = segments_distance((a, b), (c, d));
            let lower = gap(&bounds(a, b), &bounds(c, d));
            assert!(
                lower <= exact + 1e-12,
                "{a:?}-{b:?} to {c:?}-{d:?}: {lower} > {exact}"
            );
        }
    }

    #[test]
    fn the_distance_between_segments_is_zero_where_they_cross_and_end_to_segment_otherwise() {
        let cross = segments_distance(([0.0, -1.0], [0.0, 1.0]), ([-1.0, 0.0], [1.0, 0.0]));
        assert_eq!(cross, 0.0);
        let apart = segments_distance(([0.0, 1.0], [0.0, 3.0]), ([-1.0, 0.0], [1.0, 0.0]));
        assert!((apart - 1.0).abs() < 1e-12);
        let parallel = segments_distance(([0.0, 2.0], [4.0, 2.0]), ([1.0, 0.0], [3.0, 0.0]));
        assert!((parallel - 2.0).abs() < 1e-12);
        let disc = ItemExtent::disc(0.7).axis([3.0, 4.0]);
        assert_eq!(disc, ([3.0, 4.0], [3.0, 4.0]));
    }
}
