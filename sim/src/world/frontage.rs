//! The frontage of a street side: what stands right behind the back of a sidewalk where the
//! scenario puts no building: garden walls, fences and hedges in runs of a few metres, with gaps
//! for driveways and paths. A real street is lined like this almost everywhere; without it the
//! lidar's level and slightly descending beams cross the sidewalk and run on over open terrain,
//! and the ground outweighs everything else in a sweep (issue 9: under half in open streets).

use patchflow_dataset::SemanticClass;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::Material;
use super::clearance::{Clearance, ItemExtent};
use super::piece::Piece;
use super::street_furniture::SideBuilder;
use crate::seed::sub_seed;

/// Gap between the back of the sidewalk and the frontage's centre line, metres.
const SETBACK_M: f64 = 0.5;
/// Spacing of the clearance samples along a frontage run, metres.
const SAMPLE_M: f64 = 1.0;
/// Shortest run worth placing, metres.
const MIN_RUN_M: f64 = 2.0;

/// What a frontage run is made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    GardenWall,
    Fence,
    Hedge,
}

impl SideBuilder<'_> {
    /// Walls, fences and hedges along `[from, to]` behind the sidewalk; `clutter` (the world knob)
    /// sets how much of the side they cover (about 80 % at 1, 90 % at 2, none at 0). Each run is
    /// cut where it would stand in an actor's corridor, on a structure, on earlier clutter or
    /// where `off_streets` says a street or its sidewalk is.
    pub(crate) fn frontage(
        &self,
        (from, to): (f64, f64),
        clutter: f64,
        off_streets: &dyn Fn([f64; 2]) -> bool,
        clearance: &mut Clearance,
    ) -> Vec<Piece> {
        if clutter <= 0.0 {
            return Vec::new();
        }
        let mut rng = ChaCha8Rng::seed_from_u64(sub_seed(self.seed, 0xF207));
        let (w, band) = (self.street.half_width_m, self.recipe.knobs.sidewalk_width_m);
        let mut out = Vec::new();
        let mut s = from + rng.random_range(0.0..3.0) / clutter;
        while s < to {
            let kind = match rng.random_range(0..10u8) {
                0..=3 => Kind::Hedge,
                4..=6 => Kind::GardenWall,
                _ => Kind::Fence,
            };
            let (thickness, height) = match kind {
                Kind::GardenWall => (0.3, rng.random_range(0.8..1.6)),
                Kind::Fence => (0.06, rng.random_range(1.2..2.0)),
                Kind::Hedge => (0.9, rng.random_range(1.0..2.2)),
            };
            let end = (s + rng.random_range(4.0..12.0)).min(to);
            let across = self.side * (w + band + SETBACK_M + thickness / 2.0);
            let wall_sample = ItemExtent {
                half_along_m: SAMPLE_M / 2.0,
                half_across_m: thickness / 2.0,
                yaw_rad: self.street.yaw_rad(),
            };
            let shade = rng.random_range(0.0..1.0);
            // Maximal runs of free samples between s and end (checked before any is occupied,
            // so a run does not block itself).
            let samples: Vec<(f64, [f64; 2], bool)> = (0..=((end - s) / SAMPLE_M) as usize)
                .map(|k| {
                    let t = s + k as f64 * SAMPLE_M;
                    let p = self.street.point_at(t, across);
                    let free =
                        off_streets(p) && clearance.is_free(p, SAMPLE_M / 2.0, wall_sample, 0.3);
                    (t, p, free)
                })
                .collect();
            for run in samples
                .split(|sample| !sample.2)
                .filter(|run| !run.is_empty())
            {
                let (a, b) = (run[0].0, run[run.len() - 1].0);
                if let Some(piece) = self.run(kind, a, b, across, thickness, height, shade) {
                    out.push(piece);
                    for sample in run {
                        clearance.occupy(sample.1, SAMPLE_M / 2.0);
                    }
                }
            }
            // A gap for a driveway or a path, shorter where the street is more built up.
            s = end + rng.random_range(0.8..3.5) / clutter;
        }
        out
    }

    /// One run of `kind` from `a` to `b` metres along the street, or nothing if it is too short.
    #[allow(clippy::too_many_arguments)]
    fn run(
        &self,
        kind: Kind,
        a: f64,
        b: f64,
        across: f64,
        thickness: f64,
        height: f64,
        shade: f64,
    ) -> Option<Piece> {
        let length = b - a + SAMPLE_M;
        if length < MIN_RUN_M {
            return None;
        }
        let centre = self.street.point_at((a + b) / 2.0, across);
        let base = f64::from(self.field.height_at(centre[0] as f32, centre[1] as f32)) - 0.3;
        let size = [length, thickness, height + 0.3];
        let yaw = self.street.yaw_rad();
        Some(match kind {
            Kind::GardenWall => Piece::block(
                centre,
                base,
                size,
                yaw,
                SemanticClass::OtherStructure,
                0.3 + 0.25 * shade,
            ),
            Kind::Fence => Piece::block(
                centre,
                base,
                size,
                yaw,
                SemanticClass::Fence,
                0.25 + 0.3 * shade,
            ),
            Kind::Hedge => Piece::block(
                centre,
                base,
                size,
                yaw,
                SemanticClass::Vegetation,
                0.4 + 0.1 * shade,
            )
            .with_material(Material::foliage(0.25)),
        })
    }
}
