//! Building façades with depth instead of flat boxes: each building of the scenario becomes one
//! [`FacadeShape`] (piers every bay, floor bands, plinth and parapet standing out to the outline,
//! the windows recessed glass), with a seeded layout per building, and on some buildings
//! balconies in front of the bays.

use patchflow_dataset::SemanticClass;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::Material;
use super::facade_shape::FacadeGrid;
use super::piece::{Piece, PieceShape};

/// Depth of the window recess, metres.
const RECESS_M: f64 = 0.25;
/// Storey height, metres.
const FLOOR_M: f64 = 3.2;

/// The pieces of a building with outline `size_m` (length, width, height) centred at `centre_m`
/// on the ground at `base_z_m`, yawed by `yaw_rad`, with wall `reflectivity`.
pub(crate) fn facade_pieces(
    centre_m: [f64; 2],
    base_z_m: f64,
    size_m: [f64; 3],
    yaw_rad: f64,
    reflectivity: f64,
    seed: u64,
) -> Vec<Piece> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let [length, width, height] = size_m;
    let wall = reflectivity * rng.random_range(0.7..1.3);
    if length < 3.0 || width < 3.0 || height < 2.0 {
        return vec![Piece::block(
            centre_m,
            base_z_m,
            size_m,
            yaw_rad,
            SemanticClass::Building,
            reflectivity,
        )];
    }
    let grid = FacadeGrid {
        bay_m: rng.random_range(2.6f32..3.8),
        pier_m: rng.random_range(0.4f32..0.9),
        floor_m: FLOOR_M as f32,
        sill_m: 0.9,
        lintel_m: 0.35,
        plinth_m: 0.7 + 0.3,
        parapet_m: 0.8,
        recess_m: RECESS_M as f32,
    };
    let half = [length as f32 / 2.0, width as f32 / 2.0, height as f32 / 2.0];
    let mut out = vec![Piece {
        shape: PieceShape::Facade(half, grid),
        centre_m: [
            centre_m[0] as f32,
            centre_m[1] as f32,
            (base_z_m + height / 2.0) as f32,
        ],
        yaw_rad: yaw_rad as f32,
        semantic: SemanticClass::Building,
        reflectivity: wall as f32,
        material: Material::WINDOWS,
    }];
    if rng.random::<f64>() < 0.4 {
        let (sin, cos) = yaw_rad.sin_cos();
        let at = |u: f64, v: f64| {
            [
                centre_m[0] + cos * u - sin * v,
                centre_m[1] + sin * u + cos * v,
            ]
        };
        let floors = (height / FLOOR_M).floor() as usize;
        for (along_u, sign, face) in [
            (false, 1.0, length),
            (false, -1.0, length),
            (true, 1.0, width),
            (true, -1.0, width),
        ] {
            let half_depth = if along_u { length / 2.0 } else { width / 2.0 };
            let face_yaw = if along_u {
                yaw_rad + std::f64::consts::FRAC_PI_2
            } else {
                yaw_rad
            };
            let bays = (face / f64::from(grid.bay_m)).round().max(1.0) as usize;
            let span = face / bays as f64 - f64::from(grid.pier_m);
            for f in 1..floors {
                for k in 0..bays {
                    if rng.random::<f64>() > 0.15 {
                        continue;
                    }
                    let s = -face / 2.0 + face * (k as f64 + 0.5) / bays as f64;
                    let out_m = half_depth + 0.55;
                    let p = if along_u {
                        at(sign * out_m, s)
                    } else {
                        at(s, sign * out_m)
                    };
                    let z = base_z_m + f as f64 * FLOOR_M - 0.15;
                    out.push(Piece::block(
                        p,
                        z,
                        [span, 1.1, 1.1],
                        face_yaw,
                        SemanticClass::Building,
                        0.35,
                    ));
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_building_is_one_facade_shape_with_windows_and_maybe_balconies_outside_it() {
        let pieces = facade_pieces([10.0, 20.0], 0.0, [20.0, 12.0, 10.0], 0.0, 0.45, 3);
        assert!(matches!(pieces[0].shape, PieceShape::Facade(..)));
        assert_eq!(pieces[0].material, Material::WINDOWS);
        for p in &pieces[1..] {
            let (dx, dy) = (
                (f64::from(p.centre_m[0]) - 10.0).abs(),
                (f64::from(p.centre_m[1]) - 20.0).abs(),
            );
            assert!(
                dx > 10.0 || dy > 6.0,
                "a balcony inside the outline at {:?}",
                p.centre_m
            );
        }
    }
}
