//! The street layout of a scenario: straight street segments (centre line and carriageway half
//! width) taken from its `[[roads]]`, or derived from what it already says: every vehicle path
//! (ego, cars, trucks) drives the right-hand lane, so its street's centre line lies one lane
//! offset to its left, and the random-traffic grid has a street on every grid line. Parallel
//! copies of one street (two cars on the same road) are merged into one segment.

use patchflow_dataset::ActorClass;

use crate::scenario::{ActorConfig, Scenario};

/// Offset of a right-hand lane's centre from its street's centre line, metres.
pub(crate) const LANE_OFFSET_M: f64 = 1.75;
/// How far a street runs on beyond the first and last waypoint of the path it was derived from.
const RUN_ON_M: f64 = 150.0;

/// One straight street.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Street {
    /// Start of the centre line, metres.
    pub a: [f64; 2],
    /// End of the centre line, metres.
    pub b: [f64; 2],
    /// Half width of the carriageway, metres.
    pub half_width_m: f64,
}

impl Street {
    /// Unit direction from `a` to `b`.
    pub(crate) fn direction(&self) -> [f64; 2] {
        let (dx, dy) = (self.b[0] - self.a[0], self.b[1] - self.a[1]);
        let n = dx.hypot(dy).max(1e-12);
        [dx / n, dy / n]
    }

    /// Length of the centre line, metres.
    pub(crate) fn length_m(&self) -> f64 {
        (self.b[0] - self.a[0]).hypot(self.b[1] - self.a[1])
    }

    /// Distance from `p` to the centre line segment, metres.
    pub(crate) fn distance_m(&self, p: [f64; 2]) -> f64 {
        let d = self.direction();
        let along =
            ((p[0] - self.a[0]) * d[0] + (p[1] - self.a[1]) * d[1]).clamp(0.0, self.length_m());
        (p[0] - self.a[0] - along * d[0]).hypot(p[1] - self.a[1] - along * d[1])
    }

    /// The point `along` metres from `a` and `across` metres to the left of the centre line.
    pub(crate) fn point_at(&self, along: f64, across: f64) -> [f64; 2] {
        let d = self.direction();
        [
            self.a[0] + along * d[0] - across * d[1],
            self.a[1] + along * d[1] + across * d[0],
        ]
    }

    /// Yaw of the centre line, radians.
    pub(crate) fn yaw_rad(&self) -> f64 {
        let d = self.direction();
        d[1].atan2(d[0])
    }
}

/// Every street of a scenario.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct StreetMap {
    pub streets: Vec<Street>,
}

impl StreetMap {
    /// The streets of `scenario` with its actors `actors` (listed and random), carriageways
    /// `half_width_m` wide unless a `[[roads]]` entry says otherwise.
    pub(crate) fn of(scenario: &Scenario, actors: &[ActorConfig], half_width_m: f64) -> Self {
        let mut map = Self::default();
        for road in &scenario.roads {
            let w = road.half_width_m.unwrap_or(half_width_m);
            for pair in road.path_m.windows(2) {
                map.add(Street {
                    a: pair[0],
                    b: pair[1],
                    half_width_m: w,
                });
            }
        }
        if scenario.roads.is_empty() {
            let vehicles = std::iter::once(&scenario.ego).chain(
                actors
                    .iter()
                    .filter(|a| matches!(a.class, ActorClass::Car | ActorClass::Truck)),
            );
            for actor in vehicles {
                for street in streets_of_path(&actor.path_m, half_width_m) {
                    map.add(street);
                }
            }
            let traffic = &scenario.traffic;
            if traffic.random_cars + traffic.random_pedestrians > 0 {
                let g = traffic.grid_spacing_m;
                let e = traffic.extent_m + g;
                let n = (traffic.extent_m / g).floor() as i64;
                let c = traffic.centre_m;
                for k in -n..=n {
                    let o = k as f64 * g;
                    map.add(Street {
                        a: [c[0] - e, c[1] + o],
                        b: [c[0] + e, c[1] + o],
                        half_width_m,
                    });
                    map.add(Street {
                        a: [c[0] + o, c[1] - e],
                        b: [c[0] + o, c[1] + e],
                        half_width_m,
                    });
                }
            }
        }
        map
    }

    /// Adds a street, or widens the span of an existing parallel one whose carriageway holds its
    /// centre line.
    fn add(&mut self, street: Street) {
        if street.length_m() < 1e-6 {
            return;
        }
        let d = street.direction();
        for existing in &mut self.streets {
            let e = existing.direction();
            let parallel = (d[0] * e[1] - d[1] * e[0]).abs() < 0.02;
            let offset =
                (street.a[0] - existing.a[0]) * -e[1] + (street.a[1] - existing.a[1]) * e[0];
            if !parallel || offset.abs() > existing.half_width_m {
                continue;
            }
            let along = |p: [f64; 2]| (p[0] - existing.a[0]) * e[0] + (p[1] - existing.a[1]) * e[1];
            let (s0, s1) = (along(street.a), along(street.b));
            let (lo, hi) = (s0.min(s1), s0.max(s1));
            let length = existing.length_m();
            if hi < -1.0 || lo > length + 1.0 {
                continue;
            }
            let (new_lo, new_hi) = (lo.min(0.0), hi.max(length));
            let a = existing.point_at(new_lo, 0.0);
            let b = existing.point_at(new_hi, 0.0);
            existing.a = a;
            existing.b = b;
            return;
        }
        self.streets.push(street);
    }

    /// Distance from `p` to the nearest centre line and that street's half width.
    pub(crate) fn nearest(&self, p: [f64; 2]) -> Option<(f64, f64)> {
        self.streets
            .iter()
            .map(|s| (s.distance_m(p), s.half_width_m))
            .min_by(|x, y| x.0.total_cmp(&y.0))
    }

    /// True if `p` lies on some street's carriageway.
    pub(crate) fn on_carriageway(&self, p: [f64; 2]) -> bool {
        self.streets
            .iter()
            .any(|s| s.distance_m(p) < s.half_width_m)
    }
}

/// The street segments of a vehicle path: each straight piece shifted one lane offset to its
/// left, run on at both ends of the path and by a lane offset at the corners (so it meets the
/// crossing street's centre line).
fn streets_of_path(path: &[[f64; 2]], half_width_m: f64) -> Vec<Street> {
    let count = path.len().saturating_sub(1);
    (0..count)
        .filter_map(|k| {
            let (p, q) = (path[k], path[k + 1]);
            let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
            let n = dx.hypot(dy);
            if n < 1e-6 {
                return None;
            }
            let d = [dx / n, dy / n];
            let left = [-d[1] * LANE_OFFSET_M, d[0] * LANE_OFFSET_M];
            let before = if k == 0 { RUN_ON_M } else { LANE_OFFSET_M };
            let after = if k + 1 == count {
                RUN_ON_M
            } else {
                LANE_OFFSET_M
            };
            Some(Street {
                a: [
                    p[0] + left[0] - before * d[0],
                    p[1] + left[1] - before * d[1],
                ],
                b: [q[0] + left[0] + after * d[0], q[1] + left[1] + after * d[1]],
                half_width_m,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = "sweeps = 1\n[ego]\npath_m = [[-40.0, -61.75], [-1.75, -61.75], [-1.75, -121.75]]\nspeed_mps = 5.0\n[[actors]]\nname = \"oncoming\"\npath_m = [[60.0, -58.25], [-100.0, -58.25]]\nspeed_mps = 5.0\n";

    #[test]
    fn a_right_turn_in_the_right_hand_lane_gives_two_streets_meeting_at_the_crossing() {
        let scenario = Scenario::from_toml(SCENE, "s.toml", "s").unwrap();
        let map = StreetMap::of(&scenario, &scenario.actors, 6.0);
        // The oncoming car drives the same street (y = −60) the other way: merged, not doubled.
        assert_eq!(map.streets.len(), 2, "{:?}", map.streets);
        assert!(map.streets[0].distance_m([-20.0, -60.0]) < 1e-9);
        assert!(map.streets[1].distance_m([0.0, -100.0]) < 1e-9);
        assert!(
            map.streets[1].distance_m([0.0, -60.0]) < 1e-9,
            "meets the crossing"
        );
        // The merged street spans both paths' run-ons.
        assert!(map.streets[0].distance_m([-240.0, -60.0]) < 1e-9);
        assert!(map.on_carriageway([-10.0, -55.0]) && !map.on_carriageway([-10.0, -50.0]));
    }
}
