//! Tests of `instant_query.rs`.

use rapier3d::prelude::{Ray, Vector};

use crate::Scenario;
use crate::scene::Scene;

const TINY: &str = include_str!("../../../scenarios/tiny.toml");

#[test]
fn a_cast_at_an_instant_hits_what_a_cast_into_the_scene_moved_there_hits() {
    let scenario = Scenario::from_toml(TINY, "tiny.toml", "tiny").unwrap();
    let mut swept = Scene::build(&scenario, &scenario.actors).unwrap();
    let mut moved = Scene::build(&scenario, &scenario.actors).unwrap();
    // Four block instants 25 ms apart: the crossing car moves 20 cm between them.
    let start = scenario.start_secs + 1.0;
    let times: Vec<f64> = (0..4).map(|b| start + 0.025 * f64::from(b)).collect();
    swept.move_to(start);
    let instants: Vec<_> = times.iter().map(|&t| swept.instant(t)).collect();
    swept.rebuild_ray_tree_spanning(&instants);
    let mut actor_hits = 0;
    for (&t, instant) in times.iter().zip(&instants) {
        moved.move_to(t);
        moved.rebuild_ray_tree();
        let ego = moved.ego().trajectory.state_at(t);
        let origin = Vector::new(ego.position_m[0] as f32, ego.position_m[1] as f32, 1.73);
        for k in 0..2880 {
            let azimuth = std::f32::consts::TAU * (k / 4) as f32 / 720.0;
            let elevation = -0.02 - 0.06 * (k % 4) as f32;
            let dir = Vector::new(
                elevation.cos() * azimuth.cos(),
                elevation.cos() * azimuth.sin(),
                elevation.sin(),
            );
            let ray = Ray::new(origin, dir);
            let expected = moved.query_pipeline().cast_ray(&ray, 120.0, true);
            let query = swept.query_at(instant);
            assert_eq!(query.cast_ray(&ray, 120.0, true), expected, "t {t} ray {k}");
            let surface = expected.and_then(|(handle, _)| query.surface(handle));
            if let Some(surface) = surface.filter(|s| s.actor.is_some()) {
                actor_hits += 1;
                // The instant's surface is placed where the moved scene's surface is.
                assert_eq!(Some(surface), expected.and_then(|(h, _)| moved.surface(h)));
            }
        }
    }
    assert!(actor_hits > 40, "{actor_hits} hits on the moving car");
}
