//! Importance sampling without replacement (thesis 3.1.2): most draws have a high weight, but low
//! weights are still drawn now and then, which the GP needs to learn its noise.
//!
//! Efraimidis and Spirakis (2006): give every item the key `ln(u) / w` with `u` uniform in
//! (0, 1] and keep the `n` largest keys. The keys are independent per item, so the draw can run
//! as one streaming pass (`TopN`) with `u` hashed from the item's identity ([`hashed_uniform`]):
//! the kept set is then the same however the items were split among threads.

use std::cmp::Ordering;

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use patchflow_dataset::splitmix64;

/// Draws `n` distinct indices of `weights`, each draw picking among the remaining items with
/// probability proportional to its weight (Efraimidis and Spirakis 2006: key `ln(u) / w` per
/// item, keep the `n` largest keys). Items of weight 0 (or a non-finite or negative weight) come
/// after every positive one, in random order. Returns the indices in ascending order; all of
/// them if `n` is at least the number of items. Deterministic in `seed`.
///
/// ```
/// let picked = patchflow_learn::importance_sample(&[0.1, 5.0, 0.0, 2.0], 2, 7);
/// assert_eq!(picked.len(), 2);
/// assert!(picked.windows(2).all(|w| w[0] < w[1]));
/// ```
pub fn importance_sample(weights: &[f64], n: usize, seed: u64) -> Vec<usize> {
    if n >= weights.len() {
        return (0..weights.len()).collect();
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut keyed: Vec<(DrawKey, usize)> = weights
        .iter()
        .enumerate()
        .map(|(i, &w)| (DrawKey::new(w, 1.0 - rng.random::<f64>()), i))
        .collect();
    // Larger keys first, then smaller index: a total, seed-fixed order.
    keyed.sort_unstable_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut picked: Vec<usize> = keyed[..n].iter().map(|k| k.1).collect();
    picked.sort_unstable();
    picked
}

/// The Efraimidis–Spirakis key of an item: larger keys are drawn first. Items with a positive
/// weight order by `ln(u) / w`, after them the rest by `u`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DrawKey {
    positive: bool,
    key: f64,
}

impl DrawKey {
    /// The key of an item of weight `weight` with its uniform `u` in (0, 1].
    pub(crate) fn new(weight: f64, u: f64) -> Self {
        if weight.is_finite() && weight > 0.0 {
            Self {
                positive: true,
                key: u.ln() / weight,
            }
        } else {
            Self {
                positive: false,
                key: u,
            }
        }
    }
}

impl Ord for DrawKey {
    fn cmp(&self, other: &Self) -> Ordering {
        self.positive
            .cmp(&other.positive)
            .then(self.key.total_cmp(&other.key))
    }
}

impl PartialOrd for DrawKey {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl PartialEq for DrawKey {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for DrawKey {}

/// The draw key of a training candidate (thesis 3.1.2): its Eq. 3.1 weight and a uniform hashed
/// from the draw's seed and the candidate's identity (its sequence's [`name_hash`], sweep and
/// point), so a kept sample's key can be recomputed from the sample alone.
pub(crate) fn candidate_key(
    seed: u64,
    name_key: u64,
    scan: u32,
    point: usize,
    weight: f64,
) -> DrawKey {
    DrawKey::new(
        weight,
        hashed_uniform(seed, &[name_key, u64::from(scan), point as u64]),
    )
}

/// A uniform number in (0, 1] fixed by a seed and an item's identity (splitmix64 over the
/// parts), so an item's draw does not depend on which thread meets it or when.
pub(crate) fn hashed_uniform(seed: u64, parts: &[u64]) -> f64 {
    let h = parts
        .iter()
        .fold(splitmix64(seed), |h, &p| splitmix64(h ^ p));
    // The top 53 bits, shifted off zero.
    ((h >> 11) + 1) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// A standard normal number fixed by a seed and an item's identity (Box–Muller over two
/// [`hashed_uniform`]s keyed by the parts plus 1 and 2).
pub(crate) fn hashed_normal(seed: u64, parts: &[u64]) -> f64 {
    let mut keyed = parts.to_vec();
    keyed.push(1);
    let u1 = hashed_uniform(seed, &keyed);
    if let Some(last) = keyed.last_mut() {
        *last = 2;
    }
    let u2 = hashed_uniform(seed, &keyed);
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// FNV-1a hash of a name, to key draws by sequence name (the workspace's one copy).
pub(crate) use patchflow_dataset::fnv1a as name_hash;

#[cfg(test)]
mod tests {
    use super::*;

    use crate::features::top_n::TopN;
    use std::cmp::Reverse;

    #[test]
    fn hashed_normals_have_zero_mean_and_unit_variance() {
        let z: Vec<f64> = (0..20_000u64).map(|i| hashed_normal(3, &[i])).collect();
        let mean = z.iter().sum::<f64>() / z.len() as f64;
        let var = z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / z.len() as f64;
        assert!(mean.abs() < 0.03, "mean {mean}");
        assert!((var - 1.0).abs() < 0.05, "variance {var}");
        assert_eq!(hashed_normal(3, &[7]), hashed_normal(3, &[7]));
    }

    #[test]
    fn high_weights_dominate_but_low_weights_are_still_drawn() {
        // 500 items of weight 1 and 500 of weight 0.1; 100 draws per seed. The first draw is
        // heavy with probability 500 / 550 = 0.909 and later ones barely less, so about 90.6 %
        // of the draws should be heavy; 20 seeds give 2,000 draws (standard error 0.65 %), and
        // we allow ±3 %.
        let weights: Vec<f64> = (0..1000)
            .map(|i| if i % 2 == 0 { 1.0 } else { 0.1 })
            .collect();
        let (mut heavy, mut light) = (0, 0);
        for seed in 0..20 {
            let picked = importance_sample(&weights, 100, seed);
            assert_eq!(picked.len(), 100);
            assert!(
                picked.windows(2).all(|w| w[0] < w[1]),
                "distinct and sorted"
            );
            heavy += picked.iter().filter(|&&i| i % 2 == 0).count();
            light += picked.iter().filter(|&&i| i % 2 == 1).count();
        }
        assert_heavy_items_dominate(heavy, light);
    }

    /// 20 draws of 100 from 500 items of weight 1 and 500 of weight 0.1: the heavy share of
    /// draws without replacement is about 0.906, and the light items are still drawn.
    fn assert_heavy_items_dominate(heavy: usize, light: usize) {
        let share = heavy as f64 / 2000.0;
        assert!((share - 0.906).abs() < 0.03, "heavy share {share}");
        assert!(light >= 100, "light items drawn {light} times");
    }

    #[test]
    fn equal_weights_draw_every_item_equally_often() {
        let weights = [2.0; 10];
        let mut counts = [0usize; 10];
        for seed in 0..2000 {
            for i in importance_sample(&weights, 5, seed) {
                counts[i] += 1;
            }
        }
        // Each item is in half of the draws: 1,000 ± 22 (one standard error); allow ±100.
        assert!(counts.iter().all(|&c| c.abs_diff(1000) < 100), "{counts:?}");
    }

    #[test]
    fn zero_weights_are_drawn_only_when_the_positive_ones_run_out() {
        let weights = [0.0, 1.0, 0.0, 3.0, 0.0];
        assert_eq!(importance_sample(&weights, 2, 1), vec![1, 3]);
        assert_eq!(importance_sample(&weights, 3, 1).len(), 3);
        assert_eq!(importance_sample(&weights, 9, 1), vec![0, 1, 2, 3, 4]);
    }

    #[test]
    fn a_streamed_draw_with_hashed_uniforms_favours_high_weights_but_keeps_low_ones() {
        // As above, but through TopN in two halves merged, u hashed from (seed, item).
        let (mut heavy, mut light) = (0, 0);
        for seed in 0..20 {
            let mut halves = [TopN::new(100), TopN::new(100)];
            for i in 0..1000usize {
                let w = if i % 2 == 0 { 1.0 } else { 0.1 };
                let key = DrawKey::new(w, hashed_uniform(seed, &[i as u64]));
                halves[i % 3 / 2].push((key, Reverse(i)), i);
            }
            let [a, b] = halves;
            let picked: Vec<usize> = a.merge(b).into_items().map(|(_, i)| i).collect();
            assert_eq!(picked.len(), 100);
            heavy += picked.iter().filter(|&&i| i % 2 == 0).count();
            light += picked.iter().filter(|&&i| i % 2 == 1).count();
        }
        assert_heavy_items_dominate(heavy, light);
    }

    #[test]
    fn hashed_uniforms_lie_in_the_unit_interval_and_average_one_half() {
        let us: Vec<f64> = (0..10_000u64)
            .map(|i| hashed_uniform(3, &[name_hash("seq"), i]))
            .collect();
        assert!(us.iter().all(|&u| u > 0.0 && u <= 1.0));
        let mean = us.iter().sum::<f64>() / us.len() as f64;
        // Standard error 0.0029; allow 4 of them.
        assert!((mean - 0.5).abs() < 0.012, "mean {mean}");
        assert_ne!(hashed_uniform(3, &[1, 2]), hashed_uniform(3, &[2, 1]));
        assert_ne!(hashed_uniform(3, &[1]), hashed_uniform(4, &[1]));
    }

    #[test]
    fn the_same_seed_gives_the_same_draw() {
        let weights: Vec<f64> = (0..300).map(|i| f64::from(i % 7) + 0.5).collect();
        assert_eq!(
            importance_sample(&weights, 40, 9),
            importance_sample(&weights, 40, 9)
        );
        assert_ne!(
            importance_sample(&weights, 40, 9),
            importance_sample(&weights, 40, 10)
        );
    }
}
