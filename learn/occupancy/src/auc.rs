//! Area under the ROC curve (DGPOM paper, Table 1), computed as the Mann-Whitney U statistic with
//! average ranks for ties: the probability that a random occupied point scores above a random
//! free one, a tie counting one half. Ties matter: an occupancy grid gives every unobserved cell
//! the same 0.5.

/// ROC AUC of `scores` against `labels` (true = positive); `None` if either class is empty, the
/// lengths differ or a score is NaN.
///
/// ```
/// use patchflow_occupancy::roc_auc;
/// assert_eq!(roc_auc(&[0.9, 0.8, 0.3, 0.1], &[true, true, false, false]), Some(1.0));
/// assert_eq!(roc_auc(&[0.5, 0.5, 0.5], &[true, false, false]), Some(0.5));
/// ```
pub fn roc_auc(scores: &[f64], labels: &[bool]) -> Option<f64> {
    if scores.len() != labels.len() || scores.iter().any(|s| s.is_nan()) {
        return None;
    }
    let positives = labels.iter().filter(|&&l| l).count();
    let negatives = labels.len() - positives;
    if positives == 0 || negatives == 0 {
        return None;
    }
    let mut order: Vec<usize> = (0..scores.len()).collect();
    order.sort_by(|&a, &b| scores[a].total_cmp(&scores[b]));
    // Sum of the (1-based, tie-averaged) ranks of the positives.
    let mut rank_sum = 0.0;
    let mut start = 0;
    while start < order.len() {
        let score = scores[order[start]];
        let end = start + order[start..].partition_point(|&i| scores[i] == score);
        let average_rank = (start + 1 + end) as f64 / 2.0;
        let tied_positives = order[start..end].iter().filter(|&&i| labels[i]).count();
        rank_sum += average_rank * tied_positives as f64;
        start = end;
    }
    let (p, n) = (positives as f64, negatives as f64);
    Some((rank_sum - p * (p + 1.0) / 2.0) / (p * n))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The definition: over all (positive, negative) pairs, 1 if the positive scores higher,
    /// ½ on a tie.
    fn brute_force(scores: &[f64], labels: &[bool]) -> f64 {
        let (mut wins, mut pairs) = (0.0, 0.0);
        for (i, &li) in labels.iter().enumerate() {
            for (j, &lj) in labels.iter().enumerate() {
                if li && !lj {
                    pairs += 1.0;
                    wins += match scores[i].partial_cmp(&scores[j]) {
                        Some(std::cmp::Ordering::Greater) => 1.0,
                        Some(std::cmp::Ordering::Equal) => 0.5,
                        _ => 0.0,
                    };
                }
            }
        }
        wins / pairs
    }

    #[test]
    fn separated_constant_and_inverted_scores_give_one_half_and_zero() {
        let labels = [true, true, false, false, false];
        assert_eq!(roc_auc(&[5.0, 4.0, 3.0, 2.0, 1.0], &labels), Some(1.0));
        assert_eq!(roc_auc(&[0.5; 5], &labels), Some(0.5));
        assert_eq!(roc_auc(&[1.0, 2.0, 3.0, 4.0, 5.0], &labels), Some(0.0));
    }

    #[test]
    fn a_small_example_with_ties_matches_the_hand_count() {
        // Pairs (positive, negative): (0.8 vs 0.5) 1, (0.8 vs 0.2) 1, (0.5 vs 0.5) ½, (0.5 vs 0.2) 1.
        let auc = roc_auc(&[0.8, 0.5, 0.5, 0.2], &[true, true, false, false]).unwrap();
        assert!((auc - 3.5 / 4.0).abs() < 1e-15, "{auc}");
    }

    #[test]
    fn one_class_alone_or_a_nan_has_no_auc() {
        assert_eq!(roc_auc(&[0.1, 0.2], &[true, true]), None);
        assert_eq!(roc_auc(&[f64::NAN, 0.2], &[true, false]), None);
        assert_eq!(roc_auc(&[0.1], &[true, false]), None);
    }

    proptest! {
        #[test]
        fn the_rank_auc_equals_the_pair_count_with_ties(
            data in proptest::collection::vec((0u8..6, any::<bool>()), 2..60)
        ) {
            // Scores from six levels, so ties are frequent.
            let scores: Vec<f64> = data.iter().map(|&(s, _)| f64::from(s) / 5.0).collect();
            let labels: Vec<bool> = data.iter().map(|&(_, l)| l).collect();
            match roc_auc(&scores, &labels) {
                Some(auc) => prop_assert!((auc - brute_force(&scores, &labels)).abs() < 1e-12),
                None => prop_assert!(labels.iter().all(|&l| l) || labels.iter().all(|&l| !l)),
            }
        }
    }
}
