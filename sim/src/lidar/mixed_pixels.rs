//! Mixed pixels at depth edges: a real beam has a footprint (divergence of a few mrad), and where
//! it straddles the edge of a nearer object the return mixes the two surfaces, landing between
//! them (the "veil" of points trailing off object outlines in real scans). After a sweep is cast,
//! every return whose azimuth neighbour in the same channel is nearer by more than
//! [`MIN_GAP_M`] may be pulled toward it, with the sensor's `mixed_pixels` probability.

use rand::rngs::Xoshiro256PlusPlus;
use rand::{RngExt, SeedableRng};
use rayon::prelude::*;

use super::scan::ReturnsView;
use crate::seed::sub_seed;

/// Smallest depth step that counts as an edge, metres.
const MIN_GAP_M: f32 = 0.3;
/// Largest depth step over which the two surfaces still fall within one pulse, metres.
const MAX_GAP_M: f32 = 10.0;

/// Moves mixed returns in place; `origin_of(j)` is the sensor origin of column `j` in the frame
/// the points are written in.
pub(super) fn mix_edges(
    view: ReturnsView<'_>,
    probability: f32,
    origin_of: &(dyn Fn(usize) -> [f32; 3] + Sync),
    key: u64,
) {
    let ReturnsView {
        points,
        rings,
        counts,
        ranges,
        channels,
    } = view;
    if probability <= 0.0 || channels == 0 {
        return;
    }
    let columns = counts.len();
    points
        .par_chunks_mut(channels)
        .zip(rings.par_chunks(channels))
        .enumerate()
        .for_each(|(j, (points, rings))| {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(sub_seed(key, j as u64));
            let origin = origin_of(j);
            let (left, right) = ((j + columns - 1) % columns, (j + 1) % columns);
            for (point, &ring) in points.iter_mut().zip(rings).take(counts[j] as usize) {
                let Some(c) = channels.checked_sub(1 + usize::from(ring)) else {
                    continue;
                };
                let range = ranges[j * channels + c];
                let nearer = [ranges[left * channels + c], ranges[right * channels + c]]
                    .into_iter()
                    .filter(|r| (MIN_GAP_M..MAX_GAP_M).contains(&(range - r)))
                    .fold(f32::NAN, f32::min);
                // Half of the beams next to an edge straddle it.
                if nearer.is_nan() || rng.random::<f32>() >= 0.5 * probability {
                    continue;
                }
                let mixed = nearer + rng.random::<f32>() * (range - nearer);
                let scale = mixed / range;
                for a in 0..3 {
                    point[a] = origin[a] + (point[a] - origin[a]) * scale;
                }
            }
        });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_return_behind_an_edge_moves_between_the_two_surfaces_and_others_stay() {
        // Four columns of one channel along x: a post at 15 m in front of a wall at 20 m.
        let points = vec![
            [15.0, 0.0, 0.0],
            [20.0, 0.0, 0.0],
            [20.0, 0.0, 0.0],
            [20.0, 0.0, 0.0],
        ];
        let (rings, counts) = (vec![0u16; 4], vec![1u32; 4]);
        let ranges = vec![15.0, 20.0, 20.0, 20.0];
        let mut moved = 0;
        for key in 0..200 {
            let mut p = points.clone();
            let view = ReturnsView {
                points: &mut p,
                rings: &rings,
                counts: &counts,
                ranges: &ranges,
                channels: 1,
            };
            mix_edges(view, 1.0, &|_| [0.0; 3], key);
            assert_eq!(p[0], points[0], "the nearer surface never moves");
            assert_eq!(p[2], points[2], "no edge next to column 2");
            if p[1] != points[1] {
                moved += 1;
                assert!(p[1][0] >= 15.0 && p[1][0] < 20.0, "{:?}", p[1]);
            }
        }
        assert!((60..140).contains(&moved), "{moved} of 200 moved");
    }
}
