//! Building façades with depth instead of flat boxes: a glass core set back from the building's
//! outline, piers every bay and floor bands (spandrels, plinth, parapet) standing out to the
//! outline, so the windows are recessed glass, and on some buildings balconies in front of the
//! bays. Seeded per building.

use patchflow_dataset::SemanticClass;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::piece::Piece;
use crate::scene::Material;

/// Depth of the window recess, metres.
const RECESS_M: f64 = 0.25;
/// Storey height, metres.
const FLOOR_M: f64 = 3.2;
/// Reflectivity of window glass.
const GLASS_REFLECTIVITY: f64 = 0.08;

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
    let (sin, cos) = yaw_rad.sin_cos();
    let at = |u: f64, v: f64| {
        [
            centre_m[0] + cos * u - sin * v,
            centre_m[1] + sin * u + cos * v,
        ]
    };
    let wall = reflectivity * rng.random_range(0.7..1.3);
    let mut out = vec![
        Piece::block(
            centre_m,
            base_z_m,
            [length - 2.0 * RECESS_M, width - 2.0 * RECESS_M, height],
            yaw_rad,
            SemanticClass::Building,
            GLASS_REFLECTIVITY,
        )
        .with_material(Material::GLASS),
    ];
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
    let bay_m = rng.random_range(2.6..3.8);
    let pier_m = rng.random_range(0.4..0.9);
    let balconies = rng.random::<f64>() < 0.4;
    // The four faces: (outward axis is local u or v, sign, face length).
    for (along_u, sign, face) in [
        (false, 1.0, length),
        (false, -1.0, length),
        (true, 1.0, width),
        (true, -1.0, width),
    ] {
        let half_depth = if along_u { length / 2.0 } else { width / 2.0 };
        let offset = sign * (half_depth - RECESS_M / 2.0);
        let place = |s: f64, out_m: f64| {
            if along_u {
                at(offset + sign * out_m, s)
            } else {
                at(s, offset + sign * out_m)
            }
        };
        let face_yaw = if along_u {
            yaw_rad + std::f64::consts::FRAC_PI_2
        } else {
            yaw_rad
        };
        let bays = (face / bay_m).round().max(1.0) as usize;
        for k in 0..=bays {
            let s = -face / 2.0 + face * k as f64 / bays as f64;
            let s = s.clamp(-face / 2.0 + pier_m / 2.0, face / 2.0 - pier_m / 2.0);
            out.push(Piece::block(
                place(s, 0.0),
                base_z_m,
                [pier_m, RECESS_M, height],
                face_yaw,
                SemanticClass::Building,
                wall,
            ));
        }
        let floors = (height / FLOOR_M).floor().max(1.0) as usize;
        let mut bands = vec![(0.0, 0.7)];
        bands.extend((1..floors).map(|f| (f as f64 * FLOOR_M - 0.35, f as f64 * FLOOR_M + 0.9)));
        bands.push(((height - 0.8).max(0.0), height));
        for (z0, z1) in bands {
            if z1 <= z0 {
                continue;
            }
            out.push(Piece::block(
                place(0.0, 0.0),
                base_z_m + z0,
                [face, RECESS_M, z1 - z0],
                face_yaw,
                SemanticClass::Building,
                wall,
            ));
        }
        if balconies {
            for f in 1..floors {
                for k in 0..bays {
                    if rng.random::<f64>() > 0.3 {
                        continue;
                    }
                    let s = -face / 2.0 + face * (k as f64 + 0.5) / bays as f64;
                    let span = face / bays as f64 - pier_m;
                    let z = base_z_m + f as f64 * FLOOR_M - 0.15;
                    out.push(Piece::block(
                        place(s, 0.6),
                        z,
                        [span, 1.0, 0.15],
                        face_yaw,
                        SemanticClass::Building,
                        wall,
                    ));
                    out.push(Piece::block(
                        place(s, 1.05),
                        z + 0.15,
                        [span, 0.06, 0.95],
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
    fn a_facade_has_a_recessed_glass_core_piers_and_bands_within_the_outline() {
        let pieces = facade_pieces([10.0, 20.0], 0.0, [20.0, 12.0, 10.0], 0.0, 0.45, 3);
        let glass = pieces
            .iter()
            .filter(|p| p.material == Material::GLASS)
            .count();
        assert_eq!(glass, 1);
        assert!(pieces.len() > 20, "{} pieces", pieces.len());
        for p in pieces.iter().filter(|p| p.material != Material::GLASS) {
            // Piers and bands reach the outline (balconies stand out up to 1.1 m beyond it).
            let (dx, dy) = (
                (f64::from(p.centre_m[0]) - 10.0).abs(),
                (f64::from(p.centre_m[1]) - 20.0).abs(),
            );
            assert!(dx <= 10.0 + 1.1 && dy <= 6.0 + 1.1, "{:?}", p.centre_m);
        }
    }
}
