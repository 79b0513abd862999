//! Probabilistic least-squares classification on toy data: separable classes are ranked perfectly,
//! the squashing sharpens as labels become reliable, and bad input is an error.

use nalgebra::DMatrix;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::*;

/// Tie-aware ROC AUC: the probability that a random positive outscores a random negative.
fn auc(scores: &[f64], labels: &[bool]) -> f64 {
    let (mut wins, mut pairs) = (0.0, 0.0);
    for (s, _) in scores.iter().zip(labels).filter(|(_, l)| **l) {
        for (t, _) in scores.iter().zip(labels).filter(|(_, l)| !**l) {
            pairs += 1.0;
            wins += if s > t {
                1.0
            } else if s == t {
                0.5
            } else {
                0.0
            };
        }
    }
    wins / pairs
}

/// Points uniform in [−3, 3]², labelled by the side of the line x₀ + ½x₁ = 0.
fn separable(n: usize, seed: u64) -> (DMatrix<f64>, Vec<bool>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let x: DMatrix<f64> = DMatrix::from_fn(n, 2, |_, _| rng.random_range(-3.0..3.0));
    let labels = (0..n).map(|i| x[(i, 0)] + 0.5 * x[(i, 1)] > 0.0).collect();
    (x, labels)
}

#[test]
fn separable_classes_get_an_auc_near_one_with_full_and_sparse_gps() {
    let (x, labels) = separable(160, 1);
    let (test_x, test_labels) = separable(300, 2);
    for gp in [
        GpParams::new(GpKind::Full).max_iters(60),
        // Sparse kinds with their pseudo-inputs held at a random subset (PlsParams docs: moving
        // pseudo-inputs let FITC's diagonal correction swallow σ² on ±1 labels).
        GpParams::new(GpKind::Spgp)
            .pseudo_inputs(20)
            .optimise_pseudo_inputs(false),
        GpParams::new(GpKind::SpgpHet)
            .pseudo_inputs(40)
            .optimise_pseudo_inputs(false),
    ] {
        let kind = gp.check().expect("valid").kind();
        let classifier = PlsParams::new(gp).fit(&x, &labels).expect("fits");
        let p = classifier.predict(&test_x).expect("predicts");
        let score = auc(p.probability.as_slice(), &test_labels);
        assert!(score > 0.99, "{kind}: AUC {score}");
        assert!(p.probability.iter().all(|v| (0.0..=1.0).contains(v)));
        assert!(classifier.squashing().alpha > 0.0, "{kind}");
    }
}

/// 1-D labels sign(x) on [−3, 3] with the sample's label flipped where its uniform draw is below
/// `flip`; the draws are shared, so a smaller `flip` flips a subset of the labels.
fn noisy_labels(flip: f64) -> (DMatrix<f64>, Vec<bool>) {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let n = 200;
    let x: DMatrix<f64> = DMatrix::from_fn(n, 1, |_, _| rng.random_range(-3.0..3.0));
    let labels = (0..n)
        .map(|i| (x[(i, 0)] > 0.0) != (rng.random_range(0.0..1.0) < flip))
        .collect();
    (x, labels)
}

#[test]
fn alpha_grows_as_the_labels_become_less_noisy() {
    let alphas: Vec<f64> = [0.3, 0.15, 0.05]
        .iter()
        .map(|&flip| {
            let (x, labels) = noisy_labels(flip);
            let gp = GpParams::new(GpKind::Full).max_iters(80);
            let c = PlsParams::new(gp).fit(&x, &labels).expect("fits");
            c.squashing().alpha
        })
        .collect();
    assert!(
        alphas[0] < alphas[1] && alphas[1] < alphas[2],
        "α for 30 %, 15 %, 5 % flipped labels: {alphas:?}"
    );
}

#[test]
fn the_loo_moments_of_a_fit_are_in_label_units() {
    let (x, labels) = separable(60, 3);
    let gp = GpParams::new(GpKind::Full).max_iters(40);
    let c = PlsParams::new(gp).fit(&x, &labels).expect("fits");
    let loo = c.loo();
    assert_eq!(loo.mean.len(), 60);
    // On separable data almost every left-out label is predicted with the right sign.
    let right = (0..60)
        .filter(|&i| (loo.mean[i] > 0.0) == labels[i])
        .count();
    assert!(right >= 55, "{right} of 60");
    assert!(c.loo_log_probability() < 0.0 && c.loo_log_probability() > -60.0 * 2f64.ln());
}

#[test]
fn one_class_or_mismatched_labels_are_errors() {
    let (x, labels) = separable(20, 4);
    let params = PlsParams::default();
    let all = vec![true; 20];
    assert!(matches!(
        params.fit(&x, &all),
        Err(GpError::DegenerateData(_))
    ));
    assert!(matches!(
        params.fit(&x, &labels[..19]),
        Err(GpError::DegenerateData(_))
    ));
}
