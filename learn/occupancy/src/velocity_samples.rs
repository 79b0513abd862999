//! The cells the motion map's regressors learn from (DGPOM paper, Section 2.3: Υ from 500 cells of
//! the motion clusters, ε from how far Υ misses clusters held out from it), and why they are drawn
//! as they are:
//! - **Held out by scan pair.** Every ⌈1/share⌉-th pair of scans is held out whole, so ε measures
//!   Υ on pairs it never saw; a random draw of clusters put one pair's clusters, the same cars at
//!   the same moment, on both sides, and moved the T-junction's lane RMSE by up to 0.5 m/s
//!   between draws.
//! - **Half moving, half still.** Stationary cells far outnumber moving ones; a plain draw would
//!   leave Υ a few moving cells among hundreds of zeros. Half the draw comes from each kind (all
//!   of a kind if it has fewer).
//!
//! Taking each still cell once (a fixed scanner sees the same static cells at every pair) was
//! tried and dropped: it lowered DGPOM on the 3-D slice of the busy intersection (seed 7 0.871 →
//! 0.861, seed 9 0.855 → 0.836; docs/occupancy.md).

use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use crate::{ClusterKind, MotionCluster};

/// One regression sample: a cell centre (metres) and its velocity (m/s).
pub(crate) type Sample = ([f64; 2], [f64; 2]);

/// The samples of Υ and of ε.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct VelocitySamples {
    /// Cells Υ is fitted to.
    pub fitted: Vec<Sample>,
    /// Cells of the held-out pairs, where ε measures Υ's miss.
    pub held_out: Vec<Sample>,
}

impl VelocitySamples {
    /// Up to `fitted_n` and `held_out_n` cells of `clusters`, a `held_out_share` of the scan pairs
    /// held out; `rng` draws the subsets where a kind has more cells than its half.
    pub fn draw(
        clusters: &[MotionCluster],
        (fitted_n, held_out_n): (usize, usize),
        held_out_share: f64,
        rng: &mut ChaCha8Rng,
    ) -> Self {
        let period = held_out_period(held_out_share);
        let samples = |held: bool, moving: bool| -> Vec<Sample> {
            clusters
                .iter()
                .filter(|c| {
                    period.is_some_and(|p| c.scan % p == 0) == held
                        && (c.kind != ClusterKind::Stationary) == moving
                })
                .flat_map(|c| c.cells_m.iter().map(|&p| (p, c.velocity_mps)))
                .collect()
        };
        let mut balanced = |held: bool, n: usize| -> Vec<Sample> {
            let moving = samples(held, true);
            let take_moving = moving.len().min(n / 2);
            let still = samples(held, false);
            let mut out = subset(moving, take_moving, rng);
            out.extend(subset(still, n - take_moving, rng));
            out
        };
        let fitted = balanced(false, fitted_n);
        let held_out = balanced(true, held_out_n);
        Self { fitted, held_out }
    }
}

/// Every how many scan pairs one is held out for a `share` (at least every second; none for a
/// share of 0).
fn held_out_period(share: f64) -> Option<usize> {
    (share > 0.0 && share.is_finite()).then(|| ((1.0 / share).round() as usize).max(2))
}

/// `n` of `samples` drawn without replacement (all if there are fewer), in their original order.
fn subset(samples: Vec<Sample>, n: usize, rng: &mut ChaCha8Rng) -> Vec<Sample> {
    if samples.len() <= n {
        return samples;
    }
    let mut idx: Vec<usize> = (0..samples.len()).collect();
    for i in 0..n {
        let j = rng.random_range(i..idx.len());
        idx.swap(i, j);
    }
    let mut chosen = idx[..n].to_vec();
    chosen.sort_unstable();
    chosen.into_iter().map(|i| samples[i]).collect()
}

#[cfg(test)]
mod tests {
    use rand::SeedableRng;

    use super::*;
    use crate::Association;

    fn cluster(scan: usize, kind: ClusterKind, cells_m: Vec<[f64; 2]>, v: f64) -> MotionCluster {
        MotionCluster {
            scan,
            kind,
            association: Association::AdjacentObject,
            centroid_m: cells_m[0],
            cells_m,
            velocity_mps: [v, 0.0],
        }
    }

    /// A wall of three cells stationary at every pair 1 … 9, a car moving at pairs 1 … 9.
    fn run() -> Vec<MotionCluster> {
        (1..10)
            .flat_map(|k| {
                let x = k as f64;
                [
                    cluster(
                        k,
                        ClusterKind::Stationary,
                        vec![[0.25, 10.25], [0.75, 10.25], [1.25, 10.25]],
                        0.0,
                    ),
                    cluster(k, ClusterKind::Arrived, vec![[x + 0.25, 4.25]], 2.0),
                ]
            })
            .collect()
    }

    #[test]
    fn every_third_pair_is_held_out_whole_and_the_others_are_fitted() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let s = VelocitySamples::draw(&run(), (500, 500), 0.3, &mut rng);
        // Pairs 3, 6 and 9 held out: their car cells at x = 3, 6, 9 and nowhere else.
        let xs = |v: &[Sample]| -> Vec<f64> {
            v.iter()
                .filter(|(_, v)| v[0] > 0.0)
                .map(|(p, _)| p[0] - 0.25)
                .collect()
        };
        assert_eq!(xs(&s.held_out), vec![3.0, 6.0, 9.0]);
        assert_eq!(xs(&s.fitted), vec![1.0, 2.0, 4.0, 5.0, 7.0, 8.0]);
    }

    #[test]
    fn half_the_draw_is_still_when_still_cells_outnumber_moving_ones() {
        // 6 fitted car cells, 18 fitted wall cells; a draw of 10 takes 5 of each.
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let s = VelocitySamples::draw(&run(), (10, 10), 0.3, &mut rng);
        let still = s.fitted.iter().filter(|(_, v)| v[0] == 0.0).count();
        assert_eq!((s.fitted.len(), still), (10, 5));
    }

    #[test]
    fn no_draw_depends_on_the_seed_when_each_kind_fits_in_its_half() {
        let draw = |seed| {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            VelocitySamples::draw(&run(), (40, 40), 0.3, &mut rng)
        };
        assert_eq!(draw(1), draw(2));
    }

    #[test]
    fn a_share_of_zero_holds_nothing_out() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let s = VelocitySamples::draw(&run(), (500, 500), 0.0, &mut rng);
        assert!(s.held_out.is_empty());
        assert_eq!(s.fitted.len(), 9 + 27);
    }
}
