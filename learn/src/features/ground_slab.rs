//! Where a beam runs through the height slice above an uneven ground (thesis 2.1.1, measured
//! from the local ground instead of z = 0).
//!
//! A beam is a straight line in 3-D; its height above the ground, `h(t) = z(t) − g(x(t), y(t))`,
//! is linear only where the ground under it is. The beam is cut into pieces on which `h` is
//! linear to within [`TOLERANCE_M`] (checked at each piece's midpoint, halving up to
//! [`MAX_DEPTH`] times), and each piece is clipped to the slab. Pieces that stay clear of the slab
//! by more than the ground can bend under them are skipped without looking at the ground.

use crate::features::ground_grid::GroundGrid;

/// How far `h` may bend away from a straight line on one piece, metres: a fraction of the 0.5 m
/// slice, and about the ground estimate's own accuracy.
const TOLERANCE_M: f64 = 0.03;
/// Halvings of a beam at most: pieces of 1/16 of the beam.
const MAX_DEPTH: u32 = 4;
/// The most the ground is assumed to bend away from a straight line under one piece, metres.
const MAX_BEND_M: f64 = 0.15;

/// The slab `[min_m, max_m]` above a ground, seen from one sensor origin.
pub(crate) struct SlabAboveGround<'a> {
    ground: &'a GroundGrid,
    origin: [f64; 3],
    origin_height_m: f64,
    min_m: f64,
    max_m: f64,
}

impl<'a> SlabAboveGround<'a> {
    /// The slab between `min_m` and `max_m` above `ground`, for beams from `origin` (world).
    pub(crate) fn new(ground: &'a GroundGrid, origin: [f64; 3], min_m: f64, max_m: f64) -> Self {
        Self {
            ground,
            origin,
            origin_height_m: origin[2] - ground.ground_z_m(origin[0], origin[1]),
            min_m,
            max_m,
        }
    }

    /// Appends the parameter intervals `[t0, t1]` (0 at the origin, 1 at `end`) where the beam
    /// to `end` lies in the slab, in order and merged where they touch; true if `end` itself lies
    /// in the slab (the last interval then ends at 1).
    pub(crate) fn clip(&self, end: [f64; 3], out: &mut Vec<(f64, f64)>) -> bool {
        let end_height = end[2] - self.ground.ground_z_m(end[0], end[1]);
        let beam = Beam {
            slab: self,
            end,
            length_xy_m: ((end[0] - self.origin[0]).powi(2) + (end[1] - self.origin[1]).powi(2))
                .sqrt(),
        };
        beam.piece(0.0, 1.0, self.origin_height_m, end_height, 0, out);
        (self.min_m..=self.max_m).contains(&end_height)
    }
}

/// One beam being clipped.
struct Beam<'s, 'a> {
    slab: &'s SlabAboveGround<'a>,
    end: [f64; 3],
    length_xy_m: f64,
}

impl Beam<'_, '_> {
    /// Height above the ground at parameter `t`.
    fn height_m(&self, t: f64) -> f64 {
        let o = &self.slab.origin;
        let at = |k: usize| o[k] + t * (self.end[k] - o[k]);
        at(2) - self.slab.ground.ground_z_m(at(0), at(1))
    }

    /// Clips the piece `[ta, tb]` with heights `ha`, `hb` at its ends.
    fn piece(&self, ta: f64, tb: f64, ha: f64, hb: f64, depth: u32, out: &mut Vec<(f64, f64)>) {
        let (lo, hi) = (ha.min(hb), ha.max(hb));
        let bend = (self.slab.ground.max_gradient() * self.length_xy_m * (tb - ta)).min(MAX_BEND_M);
        let slab = self.slab;
        if lo - bend > slab.max_m || hi + bend < slab.min_m {
            return;
        }
        if lo - bend >= slab.min_m && hi + bend <= slab.max_m {
            push(out, ta, tb);
            return;
        }
        let tm = 0.5 * (ta + tb);
        let hm = self.height_m(tm);
        if depth >= MAX_DEPTH || (hm - 0.5 * (ha + hb)).abs() <= TOLERANCE_M {
            self.linear(ta, tm, ha, hm, out);
            self.linear(tm, tb, hm, hb, out);
        } else {
            self.piece(ta, tm, ha, hm, depth + 1, out);
            self.piece(tm, tb, hm, hb, depth + 1, out);
        }
    }

    /// Clips a piece on which the height is taken as linear.
    fn linear(&self, ta: f64, tb: f64, ha: f64, hb: f64, out: &mut Vec<(f64, f64)>) {
        if let Some((s0, s1)) = clip_to_slab(ha, hb, self.slab.min_m, self.slab.max_m) {
            push(out, ta + s0 * (tb - ta), ta + s1 * (tb - ta));
        }
    }
}

/// Appends `[t0, t1]`, merged into the last interval if they touch.
fn push(out: &mut Vec<(f64, f64)>, t0: f64, t1: f64) {
    match out.last_mut() {
        Some(last) if t0 <= last.1 + 1e-12 => last.1 = last.1.max(t1),
        _ => out.push((t0, t1)),
    }
}

/// The parameter interval `[t0, t1] ⊆ [0, 1]` where `z0 + t·(z1 − z0)` lies in `[zmin, zmax]`.
pub(crate) fn clip_to_slab(z0: f64, z1: f64, zmin: f64, zmax: f64) -> Option<(f64, f64)> {
    let dz = z1 - z0;
    if dz.abs() < 1e-12 {
        return (zmin..=zmax).contains(&z0).then_some((0.0, 1.0));
    }
    let (ta, tb) = ((zmin - z0) / dz, (zmax - z0) / dz);
    let (lo, hi) = (ta.min(tb).max(0.0), ta.max(tb).min(1.0));
    (lo <= hi).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ground grid fitted to a dense, exact sampling of `height` around the origin.
    fn grid(height: impl Fn(f64, f64) -> f64) -> GroundGrid {
        let mut points = Vec::new();
        for i in -120..120 {
            for j in -120..120 {
                let (x, y) = (0.25 * f64::from(i) + 0.125, 0.25 * f64::from(j) + 0.125);
                points.push([x, y, height(x, y)]);
            }
        }
        GroundGrid::from_points_in_world(&points, [0.0, 0.0], 24.0)
    }

    #[test]
    fn a_beam_to_a_sloped_ground_passes_the_slab_where_it_is_half_to_one_metre_above_it() {
        // Ground rising 5 % along +x, 1 m up at x = 0; sensor 1.73 m above it.
        let g = grid(|x, _| 1.0 + 0.05 * x);
        let slab = SlabAboveGround::new(&g, [0.0, 0.0, 2.73], 0.5, 1.0);
        // End on the ground at x = 12: height above ground falls from 1.73 to 0 over 12 m.
        let mut out = Vec::new();
        let hit = slab.clip([12.0, 0.0, 1.6], &mut out);
        assert!(!hit);
        assert_eq!(out.len(), 1);
        let (t0, t1) = out[0];
        assert!(
            (t0 - 0.73 / 1.73).abs() < 1e-3 && (t1 - 1.23 / 1.73).abs() < 1e-3,
            "{out:?}"
        );
    }

    #[test]
    fn a_level_beam_over_rising_ground_enters_the_slab_where_the_ground_comes_up() {
        // Flat to x = 8, then rising 10 %: a level beam 1.73 m up is 1.0 m above the ground at
        // x = 15.3 and 0.5 m at x = 20.3.
        let g = grid(|x, _| 0.1 * (x - 8.0).max(0.0));
        let slab = SlabAboveGround::new(&g, [0.0, 0.0, 1.73], 0.5, 1.0);
        let mut out = Vec::new();
        let hit = slab.clip([22.0, 0.0, 1.73], &mut out);
        assert!(!hit && out.len() == 1, "{out:?}");
        let (x0, x1) = (22.0 * out[0].0, 22.0 * out[0].1);
        assert!(
            (x0 - 15.3).abs() < 0.3 && (x1 - 20.3).abs() < 0.3,
            "{x0} {x1}"
        );
    }

    #[test]
    fn a_beam_ending_in_the_slab_is_a_hit_whose_interval_ends_at_the_end_point() {
        let g = grid(|x, y| 0.3 + 0.02 * x - 0.01 * y);
        let slab = SlabAboveGround::new(&g, [0.0, 0.0, 2.03], 0.5, 1.0);
        let end = [10.0, 4.0, 0.3 + 0.2 - 0.04 + 0.7];
        let mut out = Vec::new();
        assert!(slab.clip(end, &mut out));
        assert_eq!(out.last().unwrap().1, 1.0);
    }

    #[test]
    fn on_flat_ground_the_interval_is_the_flat_slab_clip() {
        let g = grid(|_, _| 0.0);
        let slab = SlabAboveGround::new(&g, [0.0, 0.0, 1.73], 0.5, 1.0);
        for end in [[17.3, 0.0, 0.0], [9.0, -3.0, 0.8], [30.0, 2.0, 3.0]] {
            let mut out = Vec::new();
            slab.clip(end, &mut out);
            let flat: Vec<_> = clip_to_slab(1.73, end[2], 0.5, 1.0).into_iter().collect();
            assert_eq!(out.len(), flat.len(), "{end:?}");
            for (a, b) in out.iter().zip(&flat) {
                assert!(
                    (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9,
                    "{a:?} {b:?}"
                );
            }
        }
    }
}
