//! Tests of the FITC / SPGP-HET objective, gradient and predictions (gp.md §6.4 and §6 checklist).

use nalgebra::{DMatrix, DVector};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::super::hyper::{Hyper, Layout};
use super::super::kernel::{Kernel, OwnedPoints};
use super::super::sparse_posterior::SparsePosterior;
use super::super::stationary::Stationary;
use super::super::train_data::TrainData;
use super::objective;

/// The N = 8, D = 2, M = 3 problem of gp.md §6.4.
fn reference_problem(het: bool) -> (TrainData, Hyper<Stationary>) {
    let x = DMatrix::from_fn(8, 2, |n, d| {
        if d == 0 {
            2.0 * n as f64 / 7.0 - 1.0
        } else {
            (n as f64).sin()
        }
    });
    let y = DVector::from_fn(8, |n, _| (3.0 * x[(n, 0)]).cos() + 0.1 * x[(n, 1)]);
    let h = Hyper {
        kernel: Stationary::se(&[0.6, 1.5], 1.3),
        noise_variance: 0.02,
        pseudo_inputs: DMatrix::from_row_slice(3, 2, &[-0.8, 0.1, 0.0, -0.5, 0.7, 0.6]),
        pseudo_noise: het.then(|| DVector::from_vec(vec![0.05, 0.2, 0.01])),
    };
    (TrainData::new(&x, &y), h)
}

fn close(got: f64, want: f64, rel: f64) -> bool {
    (got - want).abs() <= rel * want.abs().max(1e-12)
}

fn assert_all_close(got: &[f64], want: &[f64], rel: f64, what: &str) {
    for (g, w) in got.iter().zip(want) {
        assert!(close(*g, *w, rel), "{what}: got {g:.15}, want {w:.15}");
    }
}

fn test_points() -> DMatrix<f64> {
    DMatrix::from_row_slice(2, 2, &[0.25, 0.3, -1.2, -0.4])
}

#[test]
fn fitc_objective_and_gradient_match_the_gp_md_reference_vectors() {
    let (data, h) = reference_problem(false);
    let e = objective(&data, &h, 1e-6).expect("reference problem factors");
    let rel = 1e-8;
    assert!(close(e.nlml, 8.196028616783465, rel), "nlml {}", e.nlml);
    assert_all_close(
        &e.grad.kernel.as_slice()[..2],
        &[3.604387926454, -3.477760952753],
        rel,
        "dℓ",
    );
    assert!(close(e.grad.kernel[2], 1.521041978253, rel));
    assert!(close(e.grad.log_noise_variance, 0.083979925757, rel));
    let dz = e.grad.pseudo_inputs.transpose(); // row-major order below
    let want = [
        0.390743584068,
        -0.401165770616,
        0.600952929246,
        -1.016703748027,
        -2.190255802733,
        1.324508204459,
    ];
    assert_all_close(dz.as_slice(), &want, rel, "dZ");
}

#[test]
fn fitc_predictions_match_the_gp_md_reference_vectors() {
    let (data, h) = reference_problem(false);
    let (post, _) = SparsePosterior::new(&data, &h, 1e-6).expect("factors");
    let (mean, var) = post.predict(&h, &test_points());
    assert_all_close(
        mean.as_slice(),
        &[0.191910136857, -0.633577239843],
        1e-8,
        "mean",
    );
    assert_all_close(
        var.as_slice(),
        &[0.254655089316, 0.574999892186],
        1e-8,
        "var",
    );
}

#[test]
fn het_objective_gradient_and_predictions_match_the_gp_md_reference_vectors() {
    let (data, h) = reference_problem(true);
    let e = objective(&data, &h, 0.0).expect("reference problem factors");
    let rel = 1e-8;
    assert!(close(e.nlml, 8.573182153511636, rel), "nlml {}", e.nlml);
    assert_all_close(
        &e.grad.kernel.as_slice()[..2],
        &[3.055207396048, -2.689013980586],
        rel,
        "dℓ",
    );
    assert!(close(e.grad.kernel[2], 1.335131496405, rel));
    assert!(close(e.grad.log_noise_variance, 0.074762013190, rel));
    let dh = e.grad.log_pseudo_noise.clone().expect("het gradient");
    assert_all_close(
        dh.as_slice(),
        &[0.011346182701, 0.269439332820, 0.011590296570],
        rel,
        "dh",
    );
    let dz = e.grad.pseudo_inputs.transpose();
    let want = [
        0.461983451017,
        -0.388970192645,
        0.593690951300,
        -0.801465784796,
        -1.990366954661,
        1.068983522654,
    ];
    assert_all_close(dz.as_slice(), &want, rel, "dZ");
    let (post, _) = SparsePosterior::new(&data, &h, 0.0).expect("factors");
    let (mean, var) = post.predict(&h, &test_points());
    assert_all_close(
        mean.as_slice(),
        &[0.153050981003, -0.579852842191],
        rel,
        "mean",
    );
    assert_all_close(
        var.as_slice(),
        &[0.346153203210, 0.628926722720],
        rel,
        "var",
    );
}

/// A random problem with `n` samples, 3 inputs and `m` pseudo-inputs.
fn random_problem(n: usize, m: usize, het: bool, seed: u64) -> (TrainData, Hyper<Stationary>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let x: DMatrix<f64> = DMatrix::from_fn(n, 3, |_, _| rng.random_range(-2.0..2.0));
    let y = DVector::from_fn(n, |i, _| {
        x[(i, 0)].sin() + 0.3 * x[(i, 1)] + rng.random_range(-0.2..0.2)
    });
    let h = Hyper {
        kernel: Stationary::se(
            &[
                rng.random_range(0.5..2.0),
                rng.random_range(0.5..2.0),
                rng.random_range(0.5..2.0),
            ],
            rng.random_range(0.5..1.5),
        ),
        noise_variance: rng.random_range(0.01..0.1),
        pseudo_inputs: DMatrix::from_fn(m, 3, |_, _| rng.random_range(-2.0..2.0)),
        pseudo_noise: het.then(|| DVector::from_fn(m, |_, _| rng.random_range(0.01..0.3))),
    };
    (TrainData::new(&x, &y), h)
}

/// Central differences of 𝓛 in the flat log-coordinates against the packed analytic gradient.
fn check_gradient(het: bool, seed: u64) {
    let (data, h) = random_problem(23, 5, het, seed);
    let layout = Layout {
        kernel: h.kernel.clone(),
        dims: 3,
        pseudo: 5,
        het,
        noise_floor: 0.0,
        fixed_pseudo_inputs: None,
    };
    let theta = layout.pack(&h);
    let e = objective(&data, &h, 1e-8).expect("factors");
    let analytic = layout.pack_grad(&h, &e.grad);
    let step = 1e-5;
    for i in 0..theta.len() {
        let (mut up, mut down) = (theta.clone(), theta.clone());
        up[i] += step;
        down[i] -= step;
        let fu = objective(&data, &layout.unpack(&up), 1e-8)
            .expect("factors")
            .nlml;
        let fd = objective(&data, &layout.unpack(&down), 1e-8)
            .expect("factors")
            .nlml;
        let numeric = (fu - fd) / (2.0 * step);
        // Relative tolerance 1e-6 on the larger of |gradient| and 1 (central differences, h = 1e-5).
        let tol = 1e-6 * analytic[i].abs().max(1.0);
        assert!(
            (numeric - analytic[i]).abs() < tol,
            "param {i}: fd {numeric} vs analytic {}",
            analytic[i]
        );
    }
}

#[test]
fn every_fitc_gradient_matches_central_differences() {
    for seed in [1, 2, 3] {
        check_gradient(false, seed);
    }
}

#[test]
fn every_het_gradient_including_h_matches_central_differences() {
    for seed in [4, 5, 6] {
        check_gradient(true, seed);
    }
}

/// 𝓛 from the explicit N×N covariance C = Q + diag(K − Q) + σ²I.
fn dense_nlml(data: &TrainData, h: &Hyper<Stationary>, jitter: f64) -> f64 {
    let x = data.x_rows();
    let m = h.pseudo_inputs.nrows();
    let z = OwnedPoints::of_rows_kept(&h.pseudo_inputs, &h.kernel);
    let mut b_u = h.kernel.cross(z.points(), z.points());
    for i in 0..m {
        b_u[(i, i)] += jitter + h.pseudo_noise.as_ref().map_or(0.0, |p| p[i]);
    }
    let u = h.kernel.cross(z.points(), data.points());
    let q = u.transpose() * b_u.try_inverse().expect("invertible") * &u;
    let mut c = q.clone();
    for i in 0..x.nrows() {
        c[(i, i)] = h.kernel.signal_variance() + h.noise_variance;
    }
    let chol = nalgebra::Cholesky::new(c).expect("C is positive definite");
    let alpha = chol.solve(&data.y);
    let log_det: f64 = chol.l().diagonal().iter().map(|v| 2.0 * v.ln()).sum();
    0.5 * log_det
        + 0.5 * data.y.dot(&alpha)
        + 0.5 * x.nrows() as f64 * (2.0 * std::f64::consts::PI).ln()
}

#[test]
fn the_blocked_stable_objective_equals_the_dense_one_across_several_blocks() {
    for het in [false, true] {
        let (data, h) = random_problem(600, 7, het, 11);
        let stable = objective(&data, &h, 1e-6).expect("factors").nlml;
        let dense = dense_nlml(&data, &h, 1e-6);
        assert!(close(stable, dense, 1e-9), "het {het}: {stable} vs {dense}");
    }
}

#[test]
fn het_with_all_h_zero_equals_fitc() {
    let (data, mut h) = random_problem(40, 6, false, 8);
    let fitc = objective(&data, &h, 1e-6).expect("factors");
    h.pseudo_noise = Some(DVector::zeros(6));
    let het = objective(&data, &h, 1e-6).expect("factors");
    assert_eq!(fitc.nlml, het.nlml);
    assert_eq!(fitc.grad.pseudo_inputs, het.grad.pseudo_inputs);
    assert_eq!(het.grad.log_pseudo_noise, Some(DVector::zeros(6)));
}

#[test]
fn permuting_the_pseudo_inputs_leaves_the_objective_unchanged() {
    let (data, h) = random_problem(30, 5, true, 9);
    let mut p = h.clone();
    let order = [3, 0, 4, 1, 2];
    p.pseudo_inputs = DMatrix::from_fn(5, 3, |i, d| h.pseudo_inputs[(order[i], d)]);
    p.pseudo_noise = h
        .pseudo_noise
        .as_ref()
        .map(|v| DVector::from_fn(5, |i, _| v[order[i]]));
    let a = objective(&data, &h, 1e-6).expect("factors").nlml;
    let b = objective(&data, &p, 1e-6).expect("factors").nlml;
    assert!(close(a, b, 1e-12), "{a} vs {b}");
}

#[test]
fn the_objective_is_bit_identical_on_one_and_two_threads() {
    let (data, h) = random_problem(700, 6, true, 12); // four row blocks
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        pool.install(|| objective(&data, &h, 1e-6).expect("factors"))
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.nlml.to_bits(), two.nlml.to_bits());
    assert_eq!(one.grad.pseudo_inputs, two.grad.pseudo_inputs);
    assert_eq!(one.grad.kernel, two.grad.kernel);
}
