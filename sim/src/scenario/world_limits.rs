//! The size of a scenario's street world (`urban` and `harsh` rungs), estimated from its fields
//! before anything is built: the street segments the ground is laid along (every ground vertex
//! looks for its nearest street), the area the ego's lidar can reach (the ground and the
//! vegetation scattered over it), and the pieces (colliders) the clutter, parked cars, sidewalk
//! slabs and structures become. Each is checked against a limit of [`super::bounds`] style, so a
//! scenario that would build a world of millions of colliders is refused with the estimate.

use patchflow_dataset::ActorClass;

use super::bounds::gigabytes;
use super::bounds::show;
use super::problem::{Problem, Seg};
use super::{Realism, Scenario, StructureKind, WorldKnobs};

/// Most street segments a world is laid along (each ground vertex is tested against every one).
pub(crate) const MAX_STREETS: u64 = 2000;

/// Most static pieces (colliders) of a street world: each costs about [`BYTES_PER_PIECE`].
pub(crate) const MAX_WORLD_PIECES: u64 = 250_000;

/// Memory one static piece costs: its Rapier collider, parry shape, surface and tree node, bytes.
pub(crate) const BYTES_PER_PIECE: u64 = 1000;

/// Ground cell side, metres, and most cells a ground may have (it coarsens beyond).
pub(crate) const GROUND_CELL_M: f64 = 0.5;
pub(crate) const MAX_GROUND_CELLS: f64 = 16.0e6;

/// Memory of one ground cell (vertex height, material, block bounds), bytes.
const BYTES_PER_CELL: f64 = 7.0;

/// Pieces per metre of one street side at clutter 1: hedges, trees (two pieces), bushes, lights,
/// signs (two), bollards and bins per 100 m, as `street_furniture.rs` places them.
const CLUTTER_PIECES_PER_M: f64 = (6.0 + 2.0 * 4.0 + 4.0 + 2.5 + 2.0 * 1.5 + 3.0 + 1.5) / 100.0;
/// Traffic lights (two pieces) per metre of one street side, at any clutter above 0.
const TRAFFIC_LIGHT_PIECES_PER_M: f64 = 2.0 * 2.0 / 100.0;
/// Sidewalk slabs per metre of one street side.
const SLABS_PER_M: f64 = 1.0 / 8.0;
/// Most pieces of one vehicle shape (wheels, body, cabin, cargo box).
pub(crate) const PIECES_PER_VEHICLE: f64 = 12.0;
/// Pieces per square metre of terrain at clutter 1: trees (two pieces) and bushes.
const TERRAIN_PIECES_PER_M2: f64 = 2.0 / 250.0 + 1.0 / 90.0;
/// How far a street derived from a path runs on beyond its ends, metres.
const RUN_ON_M: f64 = 150.0;

/// What the street world of a scenario will hold, estimated from its fields.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct WorldSize {
    /// Street segments before parallel ones are merged.
    pub streets: u64,
    /// Area the ego's lidar can reach, square metres.
    pub area_m2: f64,
    /// Ground cells (at most [`MAX_GROUND_CELLS`]: the cells grow beyond).
    pub ground_cells: f64,
    /// Static pieces, an upper estimate.
    pub pieces: f64,
}

impl WorldSize {
    /// The estimate for `s`, or `None` on the `ideal` world (no street world is built).
    pub(crate) fn of(s: &Scenario) -> Option<Self> {
        let k = s.world.knobs();
        if k == WorldKnobs::of(Realism::Ideal) {
            return None;
        }
        let (min, max) = lidar_reach(s);
        let area_m2 = (max[0] - min[0]) * (max[1] - min[1]);
        let segments = street_segments(s);
        let street_m: f64 = segments
            .iter()
            .map(|&(a, b)| clipped_length(a, b, min, max))
            .sum();
        let per_side_m = k.clutter * CLUTTER_PIECES_PER_M
            + if k.clutter > 0.0 {
                TRAFFIC_LIGHT_PIECES_PER_M
            } else {
                0.0
            }
            + k.parked_cars_per_100m / 100.0 * PIECES_PER_VEHICLE
            + SLABS_PER_M;
        let structures: f64 = s
            .structures
            .iter()
            .map(|st| {
                let parts = match st.kind {
                    StructureKind::ParkedCar if k.shapes => PIECES_PER_VEHICLE,
                    _ => 1.0,
                };
                st.box_count() as f64 * parts
            })
            .sum();
        let pieces =
            2.0 * street_m * per_side_m + area_m2 * k.clutter * TERRAIN_PIECES_PER_M2 + structures;
        Some(Self {
            streets: segments.len() as u64,
            area_m2,
            ground_cells: (area_m2 / (GROUND_CELL_M * GROUND_CELL_M)).min(MAX_GROUND_CELLS),
            pieces,
        })
    }

    /// Memory the world holds while the run lasts, bytes.
    pub(crate) fn memory_bytes(&self) -> u64 {
        (self.ground_cells * BYTES_PER_CELL + self.pieces * BYTES_PER_PIECE as f64) as u64
    }
}

/// Every limit the street world of `s` exceeds.
pub(crate) fn world_problems(s: &Scenario) -> Vec<Problem> {
    let Some(size) = WorldSize::of(s) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    if size.streets > MAX_STREETS {
        let at = match s.roads.is_empty() {
            true => vec![Seg::Key("actors")],
            false => vec![Seg::Key("roads")],
        };
        out.push((
            at,
            format!(
                "the street world would be laid along {} street segments (road and vehicle path segments, random-traffic grid lines); at most {MAX_STREETS}",
                size.streets
            ),
        ));
    }
    if size.pieces > MAX_WORLD_PIECES as f64 {
        out.push((
            vec![Seg::Key("world")],
            format!(
                "the street world within the lidar's reach ({} km² of ground) would hold about {} pieces of clutter, vegetation and structures (about {}); at most {MAX_WORLD_PIECES} (less [world] clutter or parked_cars_per_100m, or a shorter ego path)",
                show((size.area_m2 / 1e6 * 100.0).round() / 100.0),
                show(size.pieces.round()),
                gigabytes(size.memory_bytes())
            ),
        ));
    }
    out
}

/// The rectangle the ego's lidar can reach over the scenario's sweeps (ego positions at every
/// sweep, grown by the lidar's range): where the street world is built.
pub(crate) fn lidar_reach(s: &Scenario) -> ([f64; 2], [f64; 2]) {
    let reach = s.lidar.max_range_m + 10.0;
    let mut min = [f64::MAX; 2];
    let mut max = [f64::MIN; 2];
    if let Ok(ego) = s.ego.trajectory() {
        for i in 0..=s.sweeps {
            let p = ego.state_at(s.sweep_start_secs(i)).position_m;
            for a in 0..2 {
                min[a] = min[a].min(p[a] - reach);
                max[a] = max[a].max(p[a] + reach);
            }
        }
    }
    if min[0] > max[0] {
        return ([-reach; 2], [reach; 2]);
    }
    (min, max)
}

/// The street segments the world is laid along (before merging): the `[[roads]]`, or every
/// vehicle path run on at its ends plus the random-traffic grid lines.
fn street_segments(s: &Scenario) -> Vec<([f64; 2], [f64; 2])> {
    let pairs = |path: &[[f64; 2]]| -> Vec<([f64; 2], [f64; 2])> {
        path.windows(2).map(|w| (w[0], w[1])).collect()
    };
    if !s.roads.is_empty() {
        return s.roads.iter().flat_map(|r| pairs(&r.path_m)).collect();
    }
    let vehicles = std::iter::once(&s.ego).chain(
        s.actors
            .iter()
            .filter(|a| matches!(a.class, ActorClass::Car | ActorClass::Truck)),
    );
    let mut out: Vec<_> = vehicles
        .flat_map(|a| {
            let mut segments = pairs(&a.path_m);
            if let Some(first) = segments.first_mut() {
                first.0 = run_on(first.1, first.0);
            }
            if let Some(last) = segments.last_mut() {
                last.1 = run_on(last.0, last.1);
            }
            segments
        })
        .collect();
    let t = &s.traffic;
    if t.random_cars + t.random_pedestrians > 0 {
        let n = (t.extent_m / t.grid_spacing_m).floor();
        let (g, e, c) = (t.grid_spacing_m, t.extent_m + t.grid_spacing_m, t.centre_m);
        for k in (-n as i64)..=(n as i64) {
            let o = k as f64 * g;
            out.push(([c[0] - e, c[1] + o], [c[0] + e, c[1] + o]));
            out.push(([c[0] + o, c[1] - e], [c[0] + o, c[1] + e]));
        }
    }
    out
}

/// `to` moved [`RUN_ON_M`] further away from `from`.
fn run_on(from: [f64; 2], to: [f64; 2]) -> [f64; 2] {
    let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
    let n = dx.hypot(dy);
    if n < 1e-9 {
        return to;
    }
    [to[0] + RUN_ON_M * dx / n, to[1] + RUN_ON_M * dy / n]
}

/// Length of the segment `a`-`b` inside the rectangle `[min, max]` (Liang-Barsky clipping).
fn clipped_length(a: [f64; 2], b: [f64; 2], min: [f64; 2], max: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for axis in 0..2 {
        if d[axis].abs() < 1e-12 {
            if a[axis] < min[axis] || a[axis] > max[axis] {
                return 0.0;
            }
            continue;
        }
        let (ta, tb) = (
            (min[axis] - a[axis]) / d[axis],
            (max[axis] - a[axis]) / d[axis],
        );
        t0 = t0.max(ta.min(tb));
        t1 = t1.min(ta.max(tb));
    }
    (t1 - t0).max(0.0) * d[0].hypot(d[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    const BASE: &str = "sweeps = 10\n[ego]\npath_m = [[0.0, 0.0], [80.0, 0.0]]\nspeed_mps = 5.0\n";

    fn scenario(text: &str) -> Scenario {
        Scenario::from_toml(text, "w.toml", "w").unwrap()
    }

    #[test]
    fn the_ideal_world_has_no_street_world_to_bound() {
        let s = scenario(&format!("realism = \"ideal\"\n{BASE}"));
        assert_eq!(WorldSize::of(&s), None);
    }

    #[test]
    fn an_urban_street_holds_a_few_thousand_pieces_at_most() {
        let size = WorldSize::of(&scenario(BASE)).unwrap();
        assert_eq!(size.streets, 1);
        // 5 m of ego path, reach 130 m each way: 265 m × 260 m.
        assert!((size.area_m2 - 265.0 * 260.0).abs() < 1.0, "{size:?}");
        assert!((1000.0..10_000.0).contains(&size.pieces), "{size:?}");
    }

    #[test]
    fn a_segment_is_clipped_to_the_rectangle() {
        let l = clipped_length([-10.0, 1.0], [30.0, 1.0], [0.0, 0.0], [10.0, 10.0]);
        assert!((l - 10.0).abs() < 1e-12);
        assert_eq!(
            clipped_length([-10.0, 20.0], [30.0, 20.0], [0.0, 0.0], [10.0, 10.0]),
            0.0
        );
    }
}
