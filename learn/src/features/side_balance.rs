//! A training draw balanced by side of the line of sight: as many samples crossing it one way
//! (sin φ > 0) as the other, without mirrored streets.
//!
//! Why: right-hand traffic makes one crossing sense the common one (70 % of our nine tracks'
//! samples have sin φ > 0), and a GP trained on that reads the other sense backwards. Mirror
//! images balance the sides by reflecting every street, which also teaches the GPs streets that
//! drive on the left; this keeps the streets as they are and balances what is drawn from them.
//!
//! The importance draw (thesis 3.1.2) keeps the largest Efraimidis–Spirakis keys `ln(u) / w`;
//! the balanced draw keeps the largest `n / 2` keys on each side. From a set drawn with the same
//! seed and at least `n / 2` samples on each side, those are exactly the balanced draw's samples
//! (a side's best keys overall are among the set's best), which [`SampleSet::balanced_by_side`]
//! says with its `exact` flag.

use std::cmp::Reverse;

use crate::features::importance_sampling::{candidate_key, name_hash};
use crate::features::sample_set::SampleSet;
use crate::features::training_sample::TrainingSample;

/// A side-balanced subset of a sample set and whether it is the exact balanced draw.
#[derive(Debug, Clone, PartialEq)]
pub struct SideBalanced {
    /// The kept samples, in the set's (dataset) order.
    pub set: SampleSet,
    /// Whether each side held its quota, so the subset is the balanced draw itself.
    pub exact: bool,
}

impl SampleSet {
    /// The `n` samples with the largest draw keys under `seed` (the seed the set was drawn
    /// with), `n / 2` with sin φ > 0 and the rest with sin φ ≤ 0; a side short of its quota
    /// leaves the rest to the other side (and the result is not exact).
    pub fn balanced_by_side(&self, n: usize, seed: u64) -> SideBalanced {
        let key = |s: &TrainingSample| {
            candidate_key(seed, name_hash(&s.sequence), s.scan, s.point, s.weight)
        };
        // Per side, indices by key, best first (ties to the earlier sample, as the draw).
        let mut sides: [Vec<usize>; 2] = [Vec::new(), Vec::new()];
        for (i, s) in self.samples.iter().enumerate() {
            sides[usize::from(s.sin_rel <= 0.0)].push(i);
        }
        for side in &mut sides {
            side.sort_by_cached_key(|&i| (Reverse(key(&self.samples[i])), i));
        }
        let half = n / 2;
        let quota = [
            half.max(n.saturating_sub(sides[1].len())),
            (n - half).max(n.saturating_sub(sides[0].len())),
        ];
        let exact = sides[0].len() >= half && sides[1].len() >= n - half;
        let mut kept: Vec<usize> = sides
            .iter()
            .zip(quota)
            .flat_map(|(side, q)| side.iter().take(q).copied())
            .collect();
        kept.sort_unstable();
        SideBalanced {
            set: SampleSet {
                kind: self.kind,
                features: self.features.clone(),
                pool_size: self.pool_size,
                samples: kept.into_iter().map(|i| self.samples[i].clone()).collect(),
            },
            exact,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set(signs: &[f64]) -> SampleSet {
        let sample = |i: usize, sin_rel: f64| TrainingSample {
            sequence: "s".into(),
            scan: 1,
            point: i,
            actor: 1,
            weight: 1.0 + (i % 3) as f64,
            bearing_rad: 0.0,
            sin_rel,
            cos_rel: 0.0,
            heading_rad: 0.0,
            speed_mps: 5.0,
            heading_features: vec![0.0; 2],
            speed_features: vec![0.0; 2],
        };
        SampleSet {
            kind: crate::FeatureKind::Patch,
            features: crate::FeatureParams::default(),
            pool_size: signs.len(),
            samples: signs
                .iter()
                .enumerate()
                .map(|(i, &s)| sample(i, s))
                .collect(),
        }
    }

    #[test]
    fn a_lopsided_set_keeps_half_its_samples_on_each_side() {
        let signs: Vec<f64> = (0..100)
            .map(|i| if i % 10 < 7 { 0.5 } else { -0.5 })
            .collect();
        let balanced = set(&signs).balanced_by_side(40, 3);
        assert!(balanced.exact);
        let positive = balanced
            .set
            .samples
            .iter()
            .filter(|s| s.sin_rel > 0.0)
            .count();
        assert_eq!((balanced.set.samples.len(), positive), (40, 20));
        let points: Vec<usize> = balanced.set.samples.iter().map(|s| s.point).collect();
        assert!(points.windows(2).all(|w| w[0] < w[1]), "dataset order");
    }

    #[test]
    fn a_side_short_of_its_quota_leaves_the_rest_to_the_other_and_is_not_exact() {
        let signs: Vec<f64> = (0..50).map(|i| if i < 5 { -0.5 } else { 0.5 }).collect();
        let balanced = set(&signs).balanced_by_side(20, 3);
        assert!(!balanced.exact);
        let negative = balanced
            .set
            .samples
            .iter()
            .filter(|s| s.sin_rel <= 0.0)
            .count();
        assert_eq!((balanced.set.samples.len(), negative), (20, 5));
    }

    #[test]
    fn each_side_keeps_its_largest_draw_keys() {
        let signs: Vec<f64> = (0..60)
            .map(|i| if i % 2 == 0 { 0.5 } else { -0.5 })
            .collect();
        let full = set(&signs);
        let balanced = full.balanced_by_side(10, 9);
        // The draw's own key of each sample (seed 9, sequence "s", sweep 1).
        let key = |s: &TrainingSample| candidate_key(9, name_hash("s"), 1, s.point, s.weight);
        for positive in [true, false] {
            let on_side = |s: &&TrainingSample| (s.sin_rel > 0.0) == positive;
            let worst_kept = balanced.set.samples.iter().filter(on_side).map(key).min();
            let best_left = full
                .samples
                .iter()
                .filter(on_side)
                .filter(|s| !balanced.set.samples.contains(s))
                .map(key)
                .max();
            assert!(worst_kept >= best_left, "side {positive}");
        }
    }
}
