//! Tests of the street world as a whole: where the curbs and sidewalks go, and that clutter
//! keeps off the drivers' corridors.

use patchflow_dataset::SemanticClass;

use super::*;
use crate::scenario::{Realism, WorldKnobs};

/// A straight east-west street (centre line y = 0) crossed by a north-south one at x = 60.
const CROSSING: &str = "sweeps = 5\n[ego]\npath_m = [[0.0, -1.75], [200.0, -1.75]]\nspeed_mps = 5.0\n[[actors]]\nname = \"north\"\npath_m = [[61.75, -100.0], [61.75, 100.0]]\nspeed_mps = 5.0\n";

fn world() -> (Scenario, StreetWorld) {
    let scenario = Scenario::from_toml(CROSSING, "c.toml", "c").unwrap();
    let world = StreetWorld::build(&scenario, &scenario.actors, 4);
    (scenario, world)
}

#[test]
fn curbs_run_along_both_sides_of_the_street_a_curb_height_above_the_gutter_and_stop_at_the_crossing()
 {
    let (scenario, world) = world();
    let knobs = scenario.world.knobs();
    assert_eq!(knobs, WorldKnobs::of(Realism::Urban));
    let ground = world.ground.as_ref().unwrap();
    let slabs: Vec<&Piece> = world
        .pieces
        .iter()
        .filter(|p| p.semantic == SemanticClass::Sidewalk)
        .collect();
    assert!(slabs.len() > 20, "{} slabs", slabs.len());
    let mut along_east_west = 0;
    for slab in slabs {
        let PieceShape::Cuboid(half) = slab.shape else {
            panic!("a slab is a box")
        };
        let [x, y, z] = slab.centre_m;
        let top = z + half[2];
        if slab.yaw_rad.abs() < 1e-3 && y.abs() < 20.0 {
            along_east_west += 1;
            // Its road-facing face (the curb) stands at the carriageway's edge, |y| = 6.
            let curb = y.abs() - half[1];
            assert!((curb - 6.0).abs() < 1e-3, "curb at |y| = {curb}");
            // No slab reaches onto the crossing street's carriageway (|x − 60| < 6).
            assert!(
                (x - 60.0).abs() > 6.0 + half[0] - 0.51,
                "slab at x = {x} on the crossing"
            );
            let gutter = ground.height_at(x, y.signum() * 5.9);
            let curb_height = top - gutter;
            assert!(
                (curb_height - 0.13).abs() < 0.03,
                "curb height {curb_height} at x = {x}"
            );
        }
    }
    assert!(along_east_west > 10);
}

#[test]
fn clutter_stands_clear_of_the_lanes() {
    let (_, world) = world();
    for piece in world
        .pieces
        .iter()
        .filter(|p| p.semantic != SemanticClass::Sidewalk)
    {
        let [x, y, _] = piece.centre_m;
        // The ego's lane (y = −1.75) and the crossing car's lane (x = 61.75) stay free.
        assert!(
            (y + 1.75).abs() > 1.0 || (x - 61.75).abs() < 1.0,
            "{:?} at ({x}, {y}) in the ego's lane",
            piece.semantic
        );
    }
}
