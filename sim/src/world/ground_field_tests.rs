//! Tests of the ground height field: its profile across a street and its ray cast.

use super::*;
use crate::Scenario;
use crate::scenario::{Realism, WorldKnobs};
use crate::world::street_map::StreetMap;

const STREET: &str =
    "sweeps = 1\n[ego]\npath_m = [[0.0, -1.75], [100.0, -1.75]]\nspeed_mps = 5.0\n";

fn field(knobs: WorldKnobs, cell_m: f64) -> GroundField {
    let scenario = Scenario::from_toml(STREET, "s.toml", "s").unwrap();
    let streets = StreetMap::of(&scenario, &[], knobs.road_half_width_m);
    let recipe = GroundRecipe {
        streets: &streets,
        knobs,
        road_reflectivity: 0.15,
        seed: 9,
    };
    GroundField::build(&recipe, [-20.0, -40.0], [120.0, 40.0], cell_m)
}

fn urban_without_noise() -> WorldKnobs {
    WorldKnobs {
        grade_m: 0.0,
        roughness_m: 0.0,
        terrain_relief_m: 0.0,
        ..WorldKnobs::of(Realism::Urban)
    }
}

#[test]
fn the_road_falls_from_its_crown_by_the_camber_and_the_sidewalk_stands_a_curb_higher() {
    let f = field(urban_without_noise(), 0.25);
    let (crown, lane, gutter) = (
        f.height_at(50.0, 0.0),
        f.height_at(50.0, -1.75),
        f.height_at(50.0, -5.9),
    );
    assert!((lane - 0.0).abs() < 1e-4, "lane centre at {lane}");
    assert!((crown - lane - 0.02 * 1.75).abs() < 2e-3, "crown {crown}");
    assert!(
        (lane - gutter - 0.02 * 4.15).abs() < 2e-3,
        "gutter {gutter}"
    );
    // Well behind the curb the field stands at the sidewalk top (minus 2 cm under the slab).
    let sidewalk = f.height_at(50.0, -7.5);
    let expected = 0.02 * (1.75 - 6.0) + 0.13 - 0.02;
    assert!(
        (sidewalk - expected).abs() < 2e-3,
        "sidewalk {sidewalk}, expected {expected}"
    );
    let (m, _) = f.material_at(50.0, -7.5);
    assert_eq!(m, GroundMaterial::Sidewalk);
    assert_eq!(f.material_at(50.0, -3.0).0, GroundMaterial::Road);
    assert!(matches!(
        f.material_at(50.0, -30.0).0,
        GroundMaterial::Grass | GroundMaterial::Gravel
    ));
}

#[test]
fn the_urban_ground_is_not_a_plane() {
    let f = field(WorldKnobs::of(Realism::Urban), 0.5);
    let heights: Vec<f32> = (0..200)
        .map(|k| f.height_at(k as f32 * 0.5 - 10.0, -1.75))
        .collect();
    let mean = heights.iter().sum::<f32>() / heights.len() as f32;
    let spread = heights.iter().map(|h| (h - mean).abs()).fold(0.0, f32::max);
    assert!(spread > 0.02, "the lane varies by only {spread} m");
    assert!(mean.abs() < 0.15, "the lane is at {mean} m on average");
}

#[test]
fn a_cast_finds_the_first_crossing_of_the_surface_a_fine_march_finds() {
    let f = field(WorldKnobs::of(Realism::Harsh), 0.5);
    let origin = [30.0f32, -1.75, 1.73];
    let mut hits = 0;
    for k in 0..400 {
        let azimuth = k as f32 * 0.0157;
        let elevation = -0.02 - 0.0011 * (k % 37) as f32;
        let dir = [
            elevation.cos() * azimuth.cos(),
            elevation.cos() * azimuth.sin(),
            elevation.sin(),
        ];
        let cast = f.cast(origin, dir, 120.0).map(|(t, _)| t);
        // March in 1 cm steps to the first point below the surface.
        let march = (1..12_000).map(|s| s as f32 * 0.01).find(|&t| {
            let p = [
                origin[0] + dir[0] * t,
                origin[1] + dir[1] * t,
                origin[2] + dir[2] * t,
            ];
            let (lo, hi) = f.bounds();
            p[0] > lo[0]
                && p[1] > lo[1]
                && p[0] < hi[0]
                && p[1] < hi[1]
                && p[2] < f.height_at(p[0], p[1])
        });
        match (cast, march) {
            (Some(t), Some(m)) => {
                assert!(
                    (t - m).abs() < 0.02 + 1e-3 * t,
                    "ray {k}: cast {t}, march {m}"
                );
                hits += 1;
            }
            (None, None) => {}
            other => panic!("ray {k}: {other:?}"),
        }
    }
    assert!(hits > 200, "{hits} hits");
}

#[test]
fn a_ray_pointing_up_misses_the_ground() {
    let f = field(WorldKnobs::of(Realism::Urban), 0.5);
    assert!(
        f.cast([30.0, 0.0, 1.73], [0.99, 0.0, 0.141], 120.0)
            .is_none()
    );
}

#[test]
fn the_normal_of_a_cambered_road_leans_towards_the_curb() {
    let f = field(urban_without_noise(), 0.5);
    let n = f.normal_at(50.0, -3.0);
    assert!(n[1] < -0.015 && n[1] > -0.025 && n[2] > 0.999, "{n:?}");
}
