//! Importance sampling without replacement (thesis 3.1.2): most draws have a high weight, but low
//! weights are still drawn now and then, which the GP needs to learn its noise.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

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
    let mut keyed: Vec<(bool, f64, usize)> = weights
        .iter()
        .enumerate()
        .map(|(i, &w)| {
            // u in (0, 1], so ln(u) is finite.
            let u = 1.0 - rng.random::<f64>();
            if w.is_finite() && w > 0.0 {
                (true, u.ln() / w, i)
            } else {
                (false, u, i)
            }
        })
        .collect();
    // Positive weights first, then larger keys, then smaller index: a total, seed-fixed order.
    keyed.sort_unstable_by(|a, b| b.0.cmp(&a.0).then(b.1.total_cmp(&a.1)).then(a.2.cmp(&b.2)));
    let mut picked: Vec<usize> = keyed[..n].iter().map(|k| k.2).collect();
    picked.sort_unstable();
    picked
}

#[cfg(test)]
mod tests {
    use super::*;

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
