//! Values and analytic gradients of the stationary kernels against direct formulas and central
//! differences.

use nalgebra::{DMatrix, DVector};

use super::*;

fn points(p: usize, d: usize, seed: usize) -> DMatrix<f64> {
    DMatrix::from_fn(d, p, |i, j| {
        (((j * 7 + i * 3 + seed) % 11) as f64 * 0.37).sin() * 1.5
    })
}

fn kernels() -> Vec<(&'static str, Stationary)> {
    let with = |k: Stationary| {
        Stationary::with_values(k.factors, DVector::from_vec(vec![0.7, 1.3, 0.9]), 1.7)
            .expect("valid")
    };
    vec![
        ("se-ard", with(Stationary::se_ard())),
        ("matern32-ard", with(Stationary::matern32_ard())),
        (
            "space-time",
            with(Stationary::space_time(
                2,
                Shape::Matern32,
                Shape::SquaredExponential,
            )),
        ),
        (
            "space-time, ℓt held in 0.5-4",
            with(Stationary::space_time(
                2,
                Shape::SquaredExponential,
                Shape::SquaredExponential,
            ))
            .bounded(2, 0.5, 4.0)
            .expect("valid range"),
        ),
    ]
}

/// k(a, b) from the definition, one pair at a time.
fn direct(k: &Stationary, a: &[f64], b: &[f64]) -> f64 {
    let mut v = k.signal_variance;
    for g in &k.groups {
        let r2: f64 = (g.start..g.start + g.len)
            .map(|d| ((a[d] - b[d]) / k.lengthscales[d]).powi(2))
            .sum();
        v *= match g.shape {
            Shape::SquaredExponential => (-0.5 * r2).exp(),
            Shape::Matern32 => {
                let r = (3.0 * r2).sqrt();
                (1.0 + r) * (-r).exp()
            }
        };
    }
    v
}

#[test]
fn the_gemm_covariance_matches_the_direct_formula() {
    let (a, b) = (points(7, 3, 1), points(9, 3, 4));
    for (name, k) in kernels() {
        let got = k.cross(Points::new(&a, None), Points::new(&b, None));
        for p in 0..7 {
            for q in 0..9 {
                let want = direct(&k, a.column(p).as_slice(), b.column(q).as_slice());
                assert!((got[(p, q)] - want).abs() < 1e-13, "{name} {p},{q}");
            }
        }
    }
}

/// Σ G ∘ k(a, b) for the scalarised central differences.
fn weighted(k: &Stationary, a: &DMatrix<f64>, b: &DMatrix<f64>, g: &DMatrix<f64>) -> f64 {
    k.cross(Points::new(a, None), Points::new(b, None))
        .component_mul(g)
        .sum()
}

#[test]
fn hyperparameter_and_input_gradients_match_central_differences() {
    let (a, b) = (points(5, 3, 2), points(6, 3, 5));
    let g = DMatrix::from_fn(5, 6, |i, j| ((i * 3 + j * 5) % 7) as f64 * 0.3 - 0.8);
    let h = 1e-6;
    for (name, k) in kernels() {
        let kab = k.cross(Points::new(&a, None), Points::new(&b, None));
        let mut d_a = DMatrix::zeros(5, 3);
        let grad = k.cross_gradient(
            Points::new(&a, None),
            Points::new(&b, None),
            &kab,
            &g,
            Some(&mut d_a),
        );
        let theta = k.params();
        for i in 0..theta.len() {
            let at = |delta: f64| {
                let mut t = theta.clone();
                t[i] += delta;
                let mut kk = k.clone();
                kk.set_params(&t);
                weighted(&kk, &a, &b, &g)
            };
            let fd = (at(h) - at(-h)) / (2.0 * h);
            // Relative tolerance 1e-7 on max(|gradient|, 1).
            assert!(
                (fd - grad[i]).abs() < 1e-7 * grad[i].abs().max(1.0),
                "{name} θ{i}: fd {fd} vs {}",
                grad[i]
            );
        }
        for p in 0..5 {
            for d in 0..3 {
                let at = |delta: f64| {
                    let mut moved = a.clone();
                    moved[(d, p)] += delta;
                    weighted(&k, &moved, &b, &g)
                };
                let fd = (at(h) - at(-h)) / (2.0 * h);
                assert!(
                    (fd - d_a[(p, d)]).abs() < 1e-7 * d_a[(p, d)].abs().max(1.0),
                    "{name} ∂a[{d},{p}]: fd {fd} vs {}",
                    d_a[(p, d)]
                );
            }
        }
    }
}

#[test]
fn the_diagonal_gradient_is_the_signal_variance_derivative() {
    for (name, k) in kernels() {
        let a = points(4, 3, 3);
        let adj = DVector::from_vec(vec![0.5, -1.0, 2.0, 0.25]);
        let grad = k.diag_gradient(Points::new(&a, None), &adj);
        let want = k.signal_variance * adj.sum();
        assert!((grad[3] - want).abs() < 1e-14, "{name}");
        assert!(grad.rows(0, 3).iter().all(|v| *v == 0.0), "{name}");
        assert!(k.diag(Points::new(&a, None)).iter().all(|v| *v == 1.7));
    }
}

#[test]
fn a_space_time_product_of_two_squared_exponentials_is_se_ard() {
    let (a, b) = (points(4, 3, 6), points(5, 3, 7));
    let all = kernels();
    let se = &all[0].1;
    let st = Stationary::with_values(
        Stationary::space_time(2, Shape::SquaredExponential, Shape::SquaredExponential).factors,
        se.lengthscales.clone(),
        se.signal_variance,
    )
    .expect("valid");
    let (pa, pb) = (Points::new(&a, None), Points::new(&b, None));
    assert!((se.cross(pa, pb) - st.cross(pa, pb)).amax() < 1e-14);
}

#[test]
fn factors_that_do_not_cover_the_inputs_are_rejected() {
    let x = points(5, 2, 0);
    let mut st = Stationary::space_time(2, Shape::Matern32, Shape::SquaredExponential);
    let err = st.initialise(&x, 1.0).expect_err("no column left for time");
    assert!(err.to_string().contains("covers no input column"), "{err}");
    let bad = Stationary::with_values(
        vec![Factor {
            shape: Shape::Matern32,
            dims: Some(3),
        }],
        DVector::from_element(2, 1.0),
        1.0,
    );
    assert!(bad.is_err());
}

#[test]
fn the_copy_by_dimension_changes_no_bit_of_the_covariance_or_its_gradients() {
    // D = 11 exercises the four partial sums and their tail; a range exercises the offsets.
    let d = 11;
    let (a, b) = (points(7, d, 1), points(12, d, 4));
    let (a_rows, b_rows) = (a.transpose(), b.transpose());
    let g = DMatrix::from_fn(7, 9, |i, j| ((i * 5 + j * 3) % 7) as f64 * 0.2 - 0.6);
    let ls = DVector::from_fn(d, |i, _| 0.8 + 0.1 * i as f64);
    for k in [Stationary::se_ard(), Stationary::matern32_ard()] {
        let k = Stationary::with_values(k.factors, ls.clone(), 1.3).expect("valid");
        let plain = (Points::new(&a, None), Points::new(&b, None).range(2, 9));
        let kept = (
            Points::new(&a, None).with_by_dim(&a_rows),
            Points::new(&b, None).with_by_dim(&b_rows).range(2, 9),
        );
        let k_plain = k.cross(plain.0, plain.1);
        assert_eq!(k_plain, k.cross(kept.0, kept.1));
        let (mut da_plain, mut da_kept) = (DMatrix::zeros(7, d), DMatrix::zeros(7, d));
        let grad_plain = k.cross_gradient(plain.0, plain.1, &k_plain, &g, Some(&mut da_plain));
        let grad_kept = k.cross_gradient(kept.0, kept.1, &k_plain, &g, Some(&mut da_kept));
        assert_eq!(grad_plain, grad_kept);
        assert_eq!(da_plain, da_kept);
    }
}

#[test]
fn a_held_length_scale_stays_in_its_range_whatever_the_optimiser_asks() {
    let mut k = Stationary::space_time(2, Shape::SquaredExponential, Shape::SquaredExponential)
        .bounded(2, 0.25, 30.0)
        .expect("valid range");
    k.initialise(&points(20, 3, 3), 1.0).expect("three columns");
    for raw in [-1e3, -5.0, 0.0, 2.0, 8.0, 1e3] {
        let mut theta = k.params();
        theta[2] = raw;
        theta[0] = raw; // the free spatial length-scale follows the optimiser (clamped to e^±40)
        k.set_params(&theta);
        let l = k.lengthscales()[2];
        // Inside within a relative 1e-12 (exp(ln 30) rounds to 30 + 4e-15).
        assert!(
            (0.25 * (1.0 - 1e-12)..=30.0 * (1.0 + 1e-12)).contains(&l),
            "raw {raw}: ℓt {l}"
        );
        // params() gives back the raw value the optimiser set (within 1e-6), inside the range.
        if raw.abs() < 10.0 {
            assert!(
                (k.params()[2] - raw).abs() < 1e-6,
                "raw {raw}: {}",
                k.params()[2]
            );
        }
    }
    assert!(k.clone().bounded(2, 3.0, 1.0).is_err());
}
