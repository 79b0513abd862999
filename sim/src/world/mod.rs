//! The procedural street world of the `urban` and `harsh` rungs (SPEC §3a), built from what a
//! scenario already says: its streets (from `[[roads]]` or the vehicle paths and the traffic
//! grid), a height-field ground with cambered roads and uneven terrain, sidewalk slabs with
//! curbs, seeded street clutter, façades with depth, and recognisable actor shapes. Everything is
//! drawn from the run seed and the scenario name, and only where the ego's lidar can reach.

mod body_shapes;
mod clearance;
mod custom_shape;
mod facade;
mod facade_shape;
mod frontage;
mod grid_piece;
mod grid_walk;
mod ground_field;
mod ground_recipe;
mod noise;
mod piece;
mod piece_grid;
mod plane_hull;
mod street_furniture;
mod street_item;
mod street_map;
mod street_shape;
mod surface;
mod terrain_scatter;

use std::sync::Arc;

pub(crate) use body_shapes::body_parts;
pub use facade_shape::GLASS_FEATURE;
pub(crate) use grid_piece::GridPiece;
pub use ground_field::GroundField;
pub(crate) use piece::{Piece, PieceShape};
pub use piece_grid::{HitNormal, PieceGrid};
pub use street_shape::{StreetPart, StreetShape};
pub use surface::{Glass, Material, Surface, SurfaceKind};

// Ground cells are GROUND_CELL_M a side, at most MAX_GROUND_CELLS of them (about 100 MB of
// heights and materials); a larger reach gets larger cells.
use crate::scenario::{
    ActorConfig, GROUND_CELL_M, MAX_GROUND_CELLS, Scenario, StructureKind, VehicleBody, fleet_key,
    lidar_reach,
};
use crate::seed::{hash_name, mix, sub_seed};
use clearance::Clearance;
use ground_field::GroundRecipe;
use patchflow_dataset::ActorClass;
use street_furniture::SideBuilder;
use street_map::{Street, StreetMap};

/// The static part of a street world.
pub(crate) struct StreetWorld {
    /// The ground, or `None` for the flat plane of the first release.
    pub ground: Option<Arc<GroundField>>,
    /// Every static piece: sidewalks, clutter, façades, structures.
    pub pieces: Vec<Piece>,
}

impl StreetWorld {
    /// The world of `scenario` with all its actors `actors` (listed and random), seeded by `seed`.
    pub(crate) fn build(scenario: &Scenario, actors: &[ActorConfig], seed: u64) -> Self {
        let knobs = scenario.world.knobs();
        let world_seed = sub_seed(mix(seed ^ hash_name(&scenario.name)), 0x3011D);
        let streets = StreetMap::of(scenario, actors, knobs.road_half_width_m);
        let recipe = GroundRecipe {
            streets: &streets,
            knobs,
            road_reflectivity: scenario.ground_reflectivity,
            seed: world_seed,
        };
        let (min, max) = lidar_reach(scenario);
        let area = (max[0] - min[0]) * (max[1] - min[1]);
        let cell_m = GROUND_CELL_M.max((area / MAX_GROUND_CELLS).sqrt());
        let field = GroundField::build(&recipe, min, max, cell_m);
        let t0 = scenario.start_secs - 1.0;
        let t1 = scenario.sweep_start_secs(scenario.sweeps) + 1.0;
        let movers: Vec<&ActorConfig> = std::iter::once(&scenario.ego).chain(actors).collect();
        let mut clearance = Clearance::new(&movers, &scenario.structures, t0, t1);
        let mut pieces = structure_pieces(scenario, &field, (seed, world_seed));
        let (lo, hi) = field.bounds();
        let off_streets = |p: [f64; 2]| {
            let on_field =
                (0..2).all(|i| p[i] > f64::from(lo[i]) + 1.0 && p[i] < f64::from(hi[i]) - 1.0);
            on_field
                && streets
                    .nearest(p)
                    .is_none_or(|(d, w)| d > w + knobs.sidewalk_width_m + 0.2)
        };
        for (index, street) in streets.streets.iter().enumerate() {
            for (end_index, end) in street_ends(street, knobs.sidewalk_width_m)
                .iter()
                .enumerate()
            {
                let builder = SideBuilder {
                    recipe: &recipe,
                    field: &field,
                    street: end,
                    side: 1.0,
                    seed: sub_seed(world_seed, 0xE4D0 + 2 * index as u64 + end_index as u64),
                };
                let across = (0.0, end.length_m());
                pieces.extend(builder.frontage(
                    across,
                    knobs.clutter,
                    &off_streets,
                    &mut clearance,
                ));
            }
        }
        for (index, street) in streets.streets.iter().enumerate() {
            for (side_index, side) in [1.0, -1.0].into_iter().enumerate() {
                let builder = SideBuilder {
                    recipe: &recipe,
                    field: &field,
                    street,
                    side,
                    seed: sub_seed(world_seed, 16 + 2 * index as u64 + side_index as u64),
                };
                for interval in builder.free_intervals(&|p| streets.on_carriageway(p)) {
                    if knobs.curb_height_m > 0.0 && knobs.sidewalk_width_m > 0.0 {
                        pieces.extend(builder.slabs(interval));
                    }
                    pieces.extend(builder.frontage(
                        interval,
                        knobs.clutter,
                        &off_streets,
                        &mut clearance,
                    ));
                    pieces.extend(builder.clutter(interval, &mut clearance));
                }
            }
        }
        if knobs.clutter > 0.0 {
            let scatter_seed = sub_seed(world_seed, 0x5CA7);
            pieces.extend(terrain_scatter::scatter(
                &field,
                knobs.clutter,
                scatter_seed,
                &mut clearance,
            ));
        }
        let ground = (!knobs.flat_ground()).then(|| Arc::new(field));
        Self { ground, pieces }
    }
}

/// The two ends of `street` as short streets across it, each running so that its left side
/// faces out of the street's end: the frontage of the houses that face a dead end or close the
/// top of a T-junction stands on that side.
fn street_ends(street: &Street, sidewalk_width_m: f64) -> [Street; 2] {
    let reach = street.half_width_m + sidewalk_width_m;
    let d = street.direction();
    [(street.b, d), (street.a, [-d[0], -d[1]])].map(|(end, out)| {
        let v = [out[1], -out[0]];
        Street {
            a: [end[0] - v[0] * reach, end[1] - v[1] * reach],
            b: [end[0] + v[0] * reach, end[1] + v[1] * reach],
            half_width_m: street.half_width_m,
        }
    })
}

/// The scenario's own structures as pieces standing on the ground: buildings with façades
/// (if asked for), parked cars with car shapes (if asked for; their bodies drawn from the fleet
/// under the run seed `run_seed` where it is on), the rest as boxes.
fn structure_pieces(
    scenario: &Scenario,
    field: &GroundField,
    (run_seed, seed): (u64, u64),
) -> Vec<Piece> {
    let knobs = scenario.world.knobs();
    let mut out = Vec::new();
    for (i, structure) in scenario.structures.iter().enumerate() {
        let size = structure.size_m.unwrap_or(structure.kind.default_size());
        let reflectivity = structure.reflectivity.unwrap_or(0.5);
        let yaw = structure.yaw_deg.to_radians();
        for (j, c) in structure.centres_m().into_iter().enumerate() {
            let ground = f64::from(field.height_at(c[0] as f32, c[1] as f32));
            let key = sub_seed(seed, (i as u64) << 20 | j as u64);
            match structure.kind {
                StructureKind::Building if knobs.facade_detail => {
                    out.extend(facade::facade_pieces(
                        c,
                        ground - 0.3,
                        [size[0], size[1], size[2] + 0.3],
                        yaw,
                        reflectivity,
                        key,
                    ));
                }
                StructureKind::ParkedCar if knobs.shapes => {
                    let drawn = (knobs.fleet && structure.size_m.is_none())
                        .then(|| {
                            let place = format!("structures[{i}][{j}]");
                            let key = fleet_key(run_seed, &scenario.name, &place);
                            VehicleBody::draw(ActorClass::Car, None, key)
                        })
                        .flatten();
                    let body = drawn.map_or((size, None), |b| (b.size_m, Some(b.belt_m)));
                    out.extend(body_shapes::parked_car_parts(
                        body,
                        reflectivity as f32,
                        [c[0], c[1]],
                        yaw,
                        ground,
                    ));
                }
                kind => {
                    // Sunk 0.3 m into uneven ground, so no gap opens under it.
                    let sunk = if knobs.flat_ground() { 0.0 } else { 0.3 };
                    let base = if knobs.flat_ground() { 0.0 } else { ground } - sunk;
                    out.push(Piece::block(
                        c,
                        base,
                        [size[0], size[1], size[2] + sunk],
                        yaw,
                        kind.semantic(),
                        reflectivity,
                    ));
                }
            }
        }
    }
    out
}

#[cfg(test)]
#[path = "world_tests.rs"]
mod tests;
