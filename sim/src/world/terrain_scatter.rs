//! Vegetation scattered over the open ground between the streets (the park strips, verges and
//! yards a city has): trees with porous crowns and bushes at a density per area, on the terrain
//! only (not on carriageways or sidewalks), clear of corridors, structures and other clutter.

use patchflow_dataset::SemanticClass;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::Material;
use super::clearance::{Clearance, ItemExtent};
use super::ground_field::{GroundField, GroundMaterial};
use super::piece::{Piece, PieceShape};

/// Trees per square metre of terrain at clutter 1.
const TREES_PER_M2: f64 = 1.0 / 250.0;
/// Bushes per square metre of terrain at clutter 1.
const BUSHES_PER_M2: f64 = 1.0 / 90.0;

/// Trees and bushes over the terrain of `field`, `clutter` times the typical density.
pub(crate) fn scatter(
    field: &GroundField,
    clutter: f64,
    seed: u64,
    clearance: &mut Clearance,
) -> Vec<Piece> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (lo, hi) = field.bounds();
    let area = f64::from(hi[0] - lo[0]) * f64::from(hi[1] - lo[1]);
    let mut out = Vec::new();
    for (tree, per_m2) in [(true, TREES_PER_M2), (false, BUSHES_PER_M2)] {
        let tries = (area * per_m2 * clutter).round() as usize;
        for _ in 0..tries {
            let x = rng.random_range(lo[0]..hi[0]);
            let y = rng.random_range(lo[1]..hi[1]);
            if !matches!(
                field.material_at(x, y).0,
                GroundMaterial::Grass | GroundMaterial::Gravel
            ) {
                continue;
            }
            let p = [f64::from(x), f64::from(y)];
            let radius = if tree { 0.8 } else { 1.0 };
            if !clearance.is_free(p, radius, ItemExtent::disc(radius), 0.5) {
                continue;
            }
            clearance.occupy(p, radius);
            let base = field.height_at(x, y);
            if tree {
                let trunk_h = rng.random_range(2.0f32..4.0);
                let crown = rng.random_range(1.5f32..3.5);
                out.push(Piece {
                    shape: PieceShape::Column(trunk_h / 2.0 + 0.2, rng.random_range(0.12..0.3)),
                    centre_m: [x, y, base + trunk_h / 2.0 - 0.2],
                    yaw_rad: 0.0,
                    semantic: SemanticClass::Trunk,
                    reflectivity: 0.35,
                    material: Material::SOLID,
                });
                out.push(Piece {
                    shape: PieceShape::Ball(crown),
                    centre_m: [x, y, base + trunk_h + 0.7 * crown],
                    yaw_rad: 0.0,
                    semantic: SemanticClass::Vegetation,
                    reflectivity: 0.5,
                    material: Material::foliage(0.6),
                });
            } else {
                let r = rng.random_range(0.5f32..1.3);
                out.push(Piece {
                    shape: PieceShape::Ball(r),
                    centre_m: [x, y, base + 0.5 * r],
                    yaw_rad: 0.0,
                    semantic: SemanticClass::Vegetation,
                    reflectivity: 0.45,
                    material: Material::foliage(0.3),
                });
            }
        }
    }
    out
}
