//! Sizes that follow from several scenario fields (rays in a sweep, the length of the run, boxes
//! in a row, random traffic's paths, how far the movers get, the street world's streets and
//! pieces, see [`super::world_limits`]), computed from the fields alone and
//! checked against the limits of [`super::bounds`] before anything is allocated or built. They
//! run once every field is within its own bounds, so the arithmetic cannot overflow.

use super::bounds::{
    BYTES_PER_RAY, COORD_M, MAX_BOXES, MAX_RAYS_PER_SWEEP, MAX_ROW_BOXES, MAX_TRAFFIC_PATH_M,
    TIME_SECS, gigabytes, show,
};
use super::problem::{Problem, Seg};
use super::world_limits::{WorldSize, world_problems};
use super::{ActorConfig, Scenario};
use crate::motion::Trajectory;

/// Half side of the square ground the ego must stay on, metres (the scene's ground slab).
pub(crate) const GROUND_HALF_M: f64 = 2000.0;

/// Every derived size of a scenario whose fields are each within bounds that exceeds its limit.
pub(crate) fn derived_problems(s: &Scenario) -> Vec<Problem> {
    let mut out = Vec::new();
    let rays = u64::from(s.lidar.channels) * u64::from(s.lidar.azimuth_steps);
    if rays > MAX_RAYS_PER_SWEEP {
        out.push((
            vec![Seg::Key("lidar"), Seg::Key("azimuth_steps")],
            format!(
                "channels × azimuth_steps = {rays} rays per sweep (about {} of memory); at most {MAX_RAYS_PER_SWEEP} ({})",
                gigabytes(rays * BYTES_PER_RAY),
                gigabytes(MAX_RAYS_PER_SWEEP * BYTES_PER_RAY)
            ),
        ));
    }
    let end_secs = s.start_secs + f64::from(s.sweeps) * s.lidar.period_secs();
    if let Some(reason) = TIME_SECS.problem("the end of the last sweep", end_secs) {
        out.push((vec![Seg::Key("sweeps")], reason));
    }
    out.extend(structure_problems(s));
    out.extend(traffic_problems(s, end_secs));
    if out.is_empty() {
        out.extend(mover_problems(s, end_secs));
    }
    if out.is_empty() {
        out.extend(world_problems(s));
    }
    out
}

/// Boxes per row and in all, counted from the row's length and spacing without building it.
fn structure_problems(s: &Scenario) -> Vec<Problem> {
    let mut out = Vec::new();
    let mut total = 0u64;
    for (i, structure) in s.structures.iter().enumerate() {
        let count = structure.box_count();
        total = total.saturating_add(count);
        if count > MAX_ROW_BOXES {
            out.push((
                vec![Seg::Key("structures"), Seg::Index(i), Seg::Key("repeat_to_m")],
                format!(
                    "this row would hold {count} boxes (its length over spacing_m); at most {MAX_ROW_BOXES}"
                ),
            ));
        }
    }
    if total > MAX_BOXES {
        out.push((
            vec![Seg::Key("structures")],
            format!("the structures hold {total} boxes in all; at most {MAX_BOXES}"),
        ));
    }
    out
}

/// Random cars hold waypoints for their whole drive: their total path length is bounded.
fn traffic_problems(s: &Scenario, end_secs: f64) -> Vec<Problem> {
    let horizon_secs = end_secs + 1.0;
    let per_car_m = s.traffic.car_speed_mps[1] * horizon_secs.max(0.0) + 60.0;
    let total_m = f64::from(s.traffic.random_cars) * per_car_m;
    if s.traffic.random_cars == 0 || total_m <= MAX_TRAFFIC_PATH_M {
        return Vec::new();
    }
    vec![(
        vec![Seg::Key("traffic"), Seg::Key("random_cars")],
        format!(
            "{} random cars driving up to {} m/s until {} s need {} km of path; at most {} km (fewer cars or a shorter run)",
            s.traffic.random_cars,
            show(s.traffic.car_speed_mps[1]),
            show(horizon_secs),
            show((total_m / 1000.0).round()),
            show(MAX_TRAFFIC_PATH_M / 1000.0)
        ),
    )]
}

/// The ego stays on the ground (off it, the lidar sees nothing); every actor stays within the
/// coordinate bound, from the first sweep to the last.
fn mover_problems(s: &Scenario, end_secs: f64) -> Vec<Problem> {
    let movers = std::iter::once((
        vec![Seg::Key("ego")],
        &s.ego,
        GROUND_HALF_M,
        "the ground square",
    ))
    .chain(s.actors.iter().enumerate().map(|(i, a)| {
        let at = vec![Seg::Key("actors"), Seg::Index(i)];
        (at, a, COORD_M.max, "the world")
    }));
    let mut out = Vec::new();
    for (mut at, actor, limit_m, region) in movers {
        let Ok(trajectory) = actor.trajectory() else {
            continue;
        };
        let reach_m = farthest_m(actor, &trajectory, s.start_secs, end_secs);
        if reach_m > limit_m {
            at.push(Seg::Key("path_m"));
            out.push((
                at,
                format!(
                    "{} gets {} m from the origin during the run; it must stay within {region} (±{} m)",
                    actor.name,
                    show(reach_m.round()),
                    show(limit_m)
                ),
            ));
        }
    }
    out
}

/// The largest |x| or |y| a mover reaches between `t0` and `t1`: its path (straight segments and
/// arcs) lies within the hull of its waypoints and of its positions at both ends of the run.
fn farthest_m(actor: &ActorConfig, trajectory: &Trajectory, t0: f64, t1: f64) -> f64 {
    let ends = [t0, t1].map(|t| trajectory.state_at(t).position_m);
    actor
        .path_m
        .iter()
        .chain(&ends)
        .flatten()
        .fold(0.0, |m: f64, v| m.max(v.abs()))
}

/// Memory a run of the scenario needs while a sweep is cast and written, bytes: the sweep's
/// buffers and the street world (ground and pieces) it is cast into.
pub(crate) fn sweep_memory_bytes(s: &Scenario) -> u64 {
    let world = WorldSize::of(s).map_or(0, |w| w.memory_bytes());
    u64::from(s.lidar.channels) * u64::from(s.lidar.azimuth_steps) * BYTES_PER_RAY + world
}
