//! Tests of the motion-adapted kernel: the printed eq. 2 for a uniform velocity, the stationary
//! space × time kernel without motion, symmetry and positive semidefiniteness on a sheared field,
//! and every θ-gradient (a and b included) against central differences, alone and through the
//! marginal likelihood of a full GP and of an SPGP.

use std::sync::Arc;

use nalgebra::{DMatrix, DVector};

use super::*;
use crate::shape::{Factor, Shape};
use crate::{GpKind, GpObjective, GpParams, Kernel, Stationary};

/// A uniform velocity with a constant error.
#[derive(Debug)]
struct Uniform([f64; 2], f64);

impl MotionField for Uniform {
    fn velocity_mps(&self, _: [f64; 2]) -> [f64; 2] {
        self.0
    }
    fn error_mps(&self, _: [f64; 2]) -> f64 {
        self.1
    }
}

/// Two lanes in opposite directions sheared into each other, with an error that grows with x.
#[derive(Debug)]
struct Lanes;

impl MotionField for Lanes {
    fn velocity_mps(&self, xy: [f64; 2]) -> [f64; 2] {
        [2.0 * (0.8 * xy[1]).tanh(), 0.1 * (0.3 * xy[0]).sin()]
    }
    fn error_mps(&self, xy: [f64; 2]) -> f64 {
        0.05 + 0.3 * (1.0 + (0.4 * xy[0]).sin()) + 0.02 * xy[1].abs()
    }
}

/// P points (x, y, t) as columns, spread over 8 × 6 m and t = 0 … 3 s.
fn points(p: usize, salt: usize) -> DMatrix<f64> {
    DMatrix::from_fn(3, p, |d, i| {
        let v = ((i * (7 + 2 * d) + salt * 13 + d * 5) % 17) as f64 / 16.0;
        match d {
            0 => 8.0 * v - 4.0,
            1 => 6.0 * v - 3.0,
            _ => (3.0 * v).round(),
        }
    })
}

fn kernel<F: MotionField>(field: F) -> MotionAdapted<F> {
    MotionAdapted::new(Arc::new(field), 3.0)
        .with_values([1.3, 0.8], 1.7, 0.9, 1.4)
        .expect("valid values")
}

fn cross<K: Kernel>(k: &K, a: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    let (ea, eb) = (k.point_data(a), k.point_data(b));
    k.cross(Points::new(a, ea.as_ref()), Points::new(b, eb.as_ref()))
}

#[test]
fn with_a_uniform_velocity_the_kernel_is_eq_2_as_printed() {
    let v = [2.0, -1.0];
    let k = kernel(Uniform(v, 0.4));
    let (a, b) = (points(9, 0), points(7, 1));
    let got = cross(&k, &a, &b);
    let lt = k.temporal_lengthscale_secs(0.4);
    for i in 0..a.ncols() {
        for j in 0..b.ncols() {
            // |x − A x'|: x' carried from t' to t by v.
            let dt = a[(2, i)] - b[(2, j)];
            let dx = (a[(0, i)] - b[(0, j)] - v[0] * dt) / 1.3;
            let dy = (a[(1, i)] - b[(1, j)] - v[1] * dt) / 0.8;
            let u = 3f64.sqrt() * dt.abs() / lt;
            let want = 1.7 * (-0.5 * (dx * dx + dy * dy)).exp() * (1.0 + u) * (-u).exp();
            assert!(
                (got[(i, j)] - want).abs() < 1e-12,
                "({i}, {j}): {} vs {want}",
                got[(i, j)]
            );
        }
    }
}

#[test]
fn without_motion_and_with_a_constant_error_it_is_the_stationary_space_time_kernel() {
    let k = kernel(Uniform([0.0, 0.0], 0.25));
    let lt = 0.9 * 0.25f64.powf(-1.0 / 1.4);
    assert!((k.temporal_lengthscale_secs(0.25) - lt).abs() < 1e-12);
    let factors = vec![
        Factor {
            shape: Shape::SquaredExponential,
            dims: Some(2),
        },
        Factor {
            shape: Shape::Matern32,
            dims: None,
        },
    ];
    let stationary = Stationary::with_values(factors, DVector::from_vec(vec![1.3, 0.8, lt]), 1.7)
        .expect("valid");
    let (a, b) = (points(8, 2), points(6, 3));
    let diff = (cross(&k, &a, &b) - cross(&stationary, &a, &b)).amax();
    assert!(diff < 1e-13, "largest difference {diff}");
}

#[test]
fn on_a_sheared_field_the_kernel_is_symmetric_and_positive_semidefinite_with_its_diagonal() {
    let k = kernel(Lanes);
    let x = points(40, 4);
    let gram = cross(&k, &x, &x);
    assert!((&gram - gram.transpose()).amax() < 1e-14);
    let diag = k.diag(Points::new(&x, None));
    for i in 0..x.ncols() {
        assert!((gram[(i, i)] - diag[i]).abs() < 1e-14);
    }
    let min = gram.symmetric_eigenvalues().min();
    assert!(min > -1e-10, "smallest eigenvalue {min}");
}

#[test]
fn points_without_point_data_are_carried_on_the_fly_to_the_same_values() {
    let k = kernel(Lanes);
    let (a, b) = (points(5, 5), points(4, 6));
    let direct = k.cross(Points::new(&a, None), Points::new(&b, None));
    assert_eq!(direct, cross(&k, &a, &b));
}

#[test]
fn every_theta_gradient_including_a_and_b_matches_central_differences() {
    check_cross_gradient(kernel(Lanes));
}

#[test]
fn with_a_temporal_range_the_theta_gradient_still_matches_central_differences() {
    check_cross_gradient(kernel(Lanes).temporal_range_secs(0.5, 4.0).unwrap());
}

fn check_cross_gradient(mut k: MotionAdapted<Lanes>) {
    let (a, b) = (points(11, 7), points(9, 8));
    let (ea, eb) = (k.point_data(&a), k.point_data(&b));
    let (pa, pb) = (Points::new(&a, ea.as_ref()), Points::new(&b, eb.as_ref()));
    let adjoint = DMatrix::from_fn(11, 9, |i, j| ((i * 3 + j * 5) % 7) as f64 / 3.0 - 1.0);
    let kab = k.cross(pa, pb);
    let analytic = k.cross_gradient(pa, pb, &kab, &adjoint, None);
    let theta = k.params();
    for i in 0..5 {
        let value = |k: &mut MotionAdapted<Lanes>, shift: f64| {
            let mut t = theta.clone();
            t[i] += shift;
            k.set_params(&t);
            k.cross(pa, pb).component_mul(&adjoint).sum()
        };
        let numeric = (value(&mut k, 1e-6) - value(&mut k, -1e-6)) / 2e-6;
        assert!(
            (numeric - analytic[i]).abs() < 1e-7 * analytic[i].abs().max(1.0),
            "θ{i}: analytic {} vs numeric {numeric}",
            analytic[i]
        );
    }
    k.set_params(&theta);
    let g = DVector::from_fn(11, |i, _| i as f64 - 5.0);
    let d = k.diag_gradient(pa, &g);
    assert!((d[2] - 1.7 * g.sum()).abs() < 1e-12 && d.rows(0, 2).amax() == 0.0);
}

/// Occupancy-like ±1 targets over the points: a blob moving with the field.
fn labels(x: &DMatrix<f64>) -> DVector<f64> {
    DVector::from_fn(x.ncols(), |i, _| {
        let (px, py, t) = (x[(0, i)], x[(1, i)], x[(2, i)]);
        if (px - 2.0 * t + 2.0).hypot(py - 1.0) < 1.5 {
            1.0
        } else {
            -1.0
        }
    })
}

fn check_objective_gradient(kind: GpKind) {
    let x = points(60, 9).transpose();
    let y = labels(&x.transpose());
    let params = GpParams::new(kind)
        .pseudo_inputs(15)
        .optimise_pseudo_inputs(false)
        .kernel(kernel(Lanes))
        .check()
        .expect("valid");
    let objective = GpObjective::new(&params, &x, &y).expect("sets up");
    // Away from the start, so no coordinate sits at a stationary point.
    let theta =
        objective.start() + DVector::from_fn(objective.dims(), |i, _| 0.1 * (i as f64 - 2.0));
    let (_, analytic) = objective.value_and_gradient(&theta).expect("evaluates");
    for i in 0..objective.dims() {
        let at = |shift: f64| {
            let mut t = theta.clone();
            t[i] += shift;
            objective.value_and_gradient(&t).expect("evaluates").0
        };
        let numeric = (at(1e-5) - at(-1e-5)) / 2e-5;
        assert!(
            (numeric - analytic[i]).abs() < 1e-5 * analytic[i].abs().max(1.0),
            "{kind}, θ{i}: analytic {} vs numeric {numeric}",
            analytic[i]
        );
    }
}

#[test]
fn the_full_gp_marginal_likelihood_gradient_in_a_and_b_matches_central_differences() {
    check_objective_gradient(GpKind::Full);
}

#[test]
fn the_spgp_marginal_likelihood_gradient_in_a_and_b_matches_central_differences() {
    check_objective_gradient(GpKind::Spgp);
}

#[test]
fn a_kernel_over_two_input_columns_is_refused() {
    let mut k = kernel(Lanes);
    assert!(k.initialise(&DMatrix::zeros(2, 5), 1.0).is_err());
    assert!(k.initialise(&points(5, 0), 1.0).is_ok());
}

#[test]
fn a_temporal_range_holds_every_local_length_scale_inside_it() {
    let k = MotionAdapted::new(Arc::new(Lanes), 3.0)
        .with_values([1.0, 1.0], 1.0, 2.0, 0.2)
        .unwrap()
        .temporal_range_secs(0.5, 30.0)
        .unwrap();
    // l_t = 2 · ε^(−5) unbounded: 2e5 s at ε = 0.1, 2e-5 s at ε = 10; squashed inside.
    for e in [0.01, 0.1, 0.5, 1.0, 2.0, 10.0, 100.0] {
        let l = k.temporal_lengthscale_secs(e);
        assert!(l > 0.5 && l < 30.0, "l_t({e}) = {l}");
    }
    assert!(k.temporal_lengthscale_secs(0.1) > 25.0);
    assert!(k.temporal_lengthscale_secs(10.0) < 0.6);
    // Monotone in ε as the unbounded l_t is.
    assert!(k.temporal_lengthscale_secs(0.5) > k.temporal_lengthscale_secs(1.0));
    assert!(
        MotionAdapted::new(Arc::new(Lanes), 3.0)
            .temporal_range_secs(3.0, 1.0)
            .is_err()
    );
}

#[test]
fn over_one_point_set_the_half_evaluated_covariance_and_gradient_equal_the_full_ones() {
    // The same points as one set (the kernel evaluates i ≤ j and mirrors) and as two copies
    // (every pair evaluated), with an adjoint that is not symmetric.
    let k = kernel(Lanes);
    let a = points(150, 3);
    let copy = a.clone();
    let (ea, ec) = (k.point_data(&a), k.point_data(&copy));
    let (pa, pc) = (
        Points::new(&a, ea.as_ref()),
        Points::new(&copy, ec.as_ref()),
    );
    let (own, full) = (k.cross(pa, pa), k.cross(pa, pc));
    assert!((&own - &full).amax() < 1e-15, "covariance");
    assert_eq!(own, own.transpose());
    let adjoint = DMatrix::from_fn(150, 150, |i, j| ((i * 3 + j * 7) % 13) as f64 / 6.0 - 1.0);
    let g_own = k.cross_gradient(pa, pa, &own, &adjoint, None);
    let g_full = k.cross_gradient(pa, pc, &full, &adjoint, None);
    for (o, f) in g_own.iter().zip(g_full.iter()) {
        // Relative 1e-12 on max(|gradient|, 1): only the order of the sums differs.
        assert!((o - f).abs() < 1e-12 * f.abs().max(1.0), "{o} vs {f}");
    }
}
