//! Tests of `piece_grid.rs`.

use super::*;
use crate::world::Material;
use crate::world::{Piece, PieceShape};
use patchflow_dataset::SemanticClass;

fn pieces() -> Vec<Piece> {
    let mut out = Vec::new();
    for k in 0..60 {
        let a = k as f32 * 0.37;
        let r = 5.0 + (k % 7) as f32 * 6.0;
        out.push(Piece {
            shape: match k % 3 {
                0 => PieceShape::Cuboid([1.0 + 0.1 * (k % 5) as f32, 0.4, 1.2]),
                1 => PieceShape::Ball(0.8),
                _ => PieceShape::Column(1.5, 0.2),
            },
            centre_m: [r * a.cos(), r * a.sin(), 0.5 + (k % 4) as f32 * 0.3],
            yaw_rad: a,
            semantic: SemanticClass::Pole,
            reflectivity: 0.5,
            material: Material::SOLID,
        });
    }
    // A long wall across many cells.
    out.push(Piece::block(
        [0.0, -30.0],
        0.0,
        [80.0, 0.5, 3.0],
        0.1,
        SemanticClass::Building,
        0.5,
    ));
    out
}

#[test]
fn the_walk_finds_the_nearest_piece_a_test_of_every_piece_finds() {
    let placed: Vec<GridPiece> = pieces().iter().filter_map(GridPiece::new).collect();
    let grid = PieceGrid::new(placed.clone());
    let mut hits = 0;
    for k in 0..3000 {
        let a = k as f32 * 0.0021;
        let e = -0.3 + 0.35 * ((k * 7) % 100) as f32 / 100.0;
        let dir = Vector::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin());
        let ray = Ray::new(Vector::new(1.0, -2.0, 1.7), dir);
        let inverse = Vector::ONE / dir;
        let expected = placed
            .iter()
            .enumerate()
            .filter(|(_, p)| {
                let (t1, t2) = (
                    (p.aabb().mins - ray.origin) * inverse,
                    (p.aabb().maxs - ray.origin) * inverse,
                );
                t1.min(t2).max_element().max(0.0) <= t1.max(t2).min_element().min(100.0)
            })
            .filter_map(|(i, p)| Some((p.cast_solid(&ray, 100.0)?, i as u32)))
            .min_by(|x, y| x.0.total_cmp(&y.0));
        let got = grid.cast(&ray, 100.0);
        assert_eq!(got.map(|g| g.1), expected.map(|e| e.1), "ray {k}");
        if let (Some(g), Some(e)) = (got, expected) {
            assert_eq!(g.0, e.0, "ray {k}");
            hits += 1;
        }
    }
    assert!(hits > 500, "{hits} hits");
}
