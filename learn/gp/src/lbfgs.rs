//! A small L-BFGS minimiser (Nocedal & Wright 2006, Alg. 7.4 two-loop recursion) with a strong-Wolfe
//! line search (Alg. 3.5/3.6, cubic interpolation with safeguards). A failed or non-finite
//! evaluation during the line search counts as "too far" and shrinks the step.

use std::collections::VecDeque;

use nalgebra::DVector;

use crate::{GpError, Result};

/// Sufficient-decrease and curvature constants of the strong Wolfe conditions.
const C1: f64 = 1e-4;
const C2: f64 = 0.9;
/// Trial steps per line search before giving up.
const LINE_SEARCH_STEPS: usize = 25;

/// Limits and tolerances of [`minimize`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct LbfgsOptions {
    /// Iteration limit.
    pub max_iters: usize,
    /// Objective-evaluation limit.
    pub max_evals: usize,
    /// Number of correction pairs kept.
    pub memory: usize,
    /// Stop when the largest gradient component falls below this.
    pub grad_tol: f64,
    /// Stop when (f_k − f_{k+1}) / max(|f_k|, |f_{k+1}|, 1) falls below this.
    pub rel_tol: f64,
}

/// Why the optimiser stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum StopReason {
    /// The gradient norm test passed.
    GradientNorm,
    /// The relative objective change test passed.
    ObjectiveChange,
    /// The iteration limit was reached.
    MaxIterations,
    /// The evaluation limit was reached.
    MaxEvaluations,
    /// No step along a steepest-descent direction decreased the objective.
    LineSearchFailed,
}

/// The result of [`minimize`].
#[derive(Debug, Clone)]
pub(crate) struct LbfgsOutcome {
    /// Best point found.
    pub x: DVector<f64>,
    /// Objective at `x`.
    pub f: f64,
    /// Iterations done.
    pub iterations: usize,
    /// Objective evaluations done (including failed ones).
    pub evals: usize,
    /// Why it stopped.
    pub stop: StopReason,
}

#[derive(Clone)]
struct Point {
    a: f64,
    f: f64,
    /// Directional derivative; `None` for a failed evaluation.
    d: Option<f64>,
    x: DVector<f64>,
    g: DVector<f64>,
}

struct Counted<F> {
    f: F,
    evals: usize,
}

impl<F: FnMut(&DVector<f64>) -> Result<(f64, DVector<f64>)>> Counted<F> {
    fn at(&mut self, x0: &DVector<f64>, p: &DVector<f64>, a: f64) -> Point {
        self.evals += 1;
        let x = x0 + p * a;
        match (self.f)(&x) {
            Ok((f, g)) if f.is_finite() && g.iter().all(|v| v.is_finite()) => Point {
                a,
                f,
                d: Some(g.dot(p)),
                x,
                g,
            },
            _ => Point {
                a,
                f: f64::INFINITY,
                d: None,
                x,
                g: DVector::zeros(0),
            },
        }
    }
}

/// Strong-Wolfe line search from `start` (a = 0) along `p`.
fn line_search<F>(obj: &mut Counted<F>, start: &Point, p: &DVector<f64>, a0: f64) -> Option<Point>
where
    F: FnMut(&DVector<f64>) -> Result<(f64, DVector<f64>)>,
{
    let d0 = start.d?;
    let armijo = |pt: &Point| pt.f <= start.f + C1 * pt.a * d0;
    let wolfe = |pt: &Point| pt.d.is_some_and(|d| d.abs() <= -C2 * d0);
    let (mut lo, mut hi): (Point, Option<Point>) = (start.clone(), None);
    let mut a = a0;
    for _ in 0..LINE_SEARCH_STEPS {
        let pt = obj.at(&start.x, p, a);
        if !armijo(&pt) || pt.f >= lo.f && lo.a > 0.0 || pt.d.is_none() {
            hi = Some(pt);
        } else if wolfe(&pt) {
            return Some(pt);
        } else if pt
            .d
            .is_some_and(|d| d * (hi.as_ref().map_or(f64::INFINITY, |h| h.a) - lo.a) >= 0.0)
        {
            // The slope points back towards lo: the minimum lies between pt and lo.
            hi = Some(lo);
            lo = pt;
        } else {
            lo = pt;
        }
        a = match &hi {
            None => 2.0 * lo.a.max(a), // still descending: extrapolate
            Some(h) => interpolate(&lo, h),
        };
    }
    (lo.a > 0.0).then_some(lo)
}

/// A trial step between `lo` and `hi`: the cubic minimiser if both ends have slopes and it lies
/// safely inside, else the midpoint.
fn interpolate(lo: &Point, hi: &Point) -> f64 {
    let mid = 0.5 * (lo.a + hi.a);
    let (Some(d1), Some(d2)) = (lo.d, hi.d) else {
        return mid;
    };
    let (a1, a2) = (lo.a, hi.a);
    let e1 = d1 + d2 - 3.0 * (lo.f - hi.f) / (a1 - a2);
    let rad = e1 * e1 - d1 * d2;
    if rad < 0.0 || !rad.is_finite() {
        return mid;
    }
    let e2 = rad.sqrt() * (a2 - a1).signum();
    let a = a2 - (a2 - a1) * (d2 + e2 - e1) / (d2 - d1 + 2.0 * e2);
    let (left, right) = (a1.min(a2), a1.max(a2));
    let margin = 0.1 * (right - left);
    if a.is_finite() && a > left + margin && a < right - margin {
        a
    } else {
        mid
    }
}

/// The L-BFGS direction −H g from the stored pairs (two-loop recursion).
fn direction(
    g: &DVector<f64>,
    pairs: &VecDeque<(DVector<f64>, DVector<f64>, f64)>,
) -> DVector<f64> {
    let mut q = -g;
    let mut alphas = Vec::with_capacity(pairs.len());
    for (s, y, rho) in pairs.iter().rev() {
        let a = rho * s.dot(&q);
        q.axpy(-a, y, 1.0);
        alphas.push(a);
    }
    if let Some((s, y, _)) = pairs.back() {
        q *= s.dot(y) / y.dot(y);
    }
    for ((s, y, rho), a) in pairs.iter().zip(alphas.iter().rev()) {
        let b = rho * y.dot(&q);
        q.axpy(a - b, s, 1.0);
    }
    q
}

/// Minimises `f` (returning value and gradient) from `x0`. Fails only if `f(x0)` fails.
pub(crate) fn minimize<F>(f: F, x0: DVector<f64>, opts: LbfgsOptions) -> Result<LbfgsOutcome>
where
    F: FnMut(&DVector<f64>) -> Result<(f64, DVector<f64>)>,
{
    let mut obj = Counted { f, evals: 1 };
    let (f0, g0) = (obj.f)(&x0)?;
    if !f0.is_finite() || g0.iter().any(|v| !v.is_finite()) {
        return Err(GpError::Numerical(
            "the objective is not finite at the starting point".into(),
        ));
    }
    let mut cur = Point {
        a: 0.0,
        f: f0,
        d: None,
        x: x0,
        g: g0,
    };
    let mut pairs = VecDeque::with_capacity(opts.memory);
    let mut iterations = 0;
    let stop = loop {
        if cur.g.amax() <= opts.grad_tol {
            break StopReason::GradientNorm;
        }
        if iterations >= opts.max_iters {
            break StopReason::MaxIterations;
        }
        if obj.evals >= opts.max_evals {
            break StopReason::MaxEvaluations;
        }
        let mut p = direction(&cur.g, &pairs);
        if p.dot(&cur.g) >= 0.0 {
            pairs.clear();
            p = -&cur.g;
        }
        let a0 = if pairs.is_empty() {
            (1.0 / p.norm()).min(1.0)
        } else {
            1.0
        };
        let start = Point {
            a: 0.0,
            d: Some(cur.g.dot(&p)),
            ..cur.clone()
        };
        let Some(next) = line_search(&mut obj, &start, &p, a0) else {
            if pairs.is_empty() {
                break StopReason::LineSearchFailed;
            }
            pairs.clear(); // retry once from steepest descent
            continue;
        };
        iterations += 1;
        let s = &next.x - &cur.x;
        let y = &next.g - &cur.g;
        let sy = s.dot(&y);
        if sy > 1e-12 * s.norm() * y.norm() {
            if pairs.len() == opts.memory {
                pairs.pop_front();
            }
            pairs.push_back((s, y, 1.0 / sy));
        }
        let change = (cur.f - next.f) / cur.f.abs().max(next.f.abs()).max(1.0);
        cur = Point {
            a: 0.0,
            d: None,
            ..next
        };
        if change <= opts.rel_tol {
            break StopReason::ObjectiveChange;
        }
    };
    Ok(LbfgsOutcome {
        x: cur.x,
        f: cur.f,
        iterations,
        evals: obj.evals,
        stop,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn options() -> LbfgsOptions {
        LbfgsOptions {
            max_iters: 500,
            max_evals: 2000,
            memory: 10,
            grad_tol: 1e-8,
            rel_tol: 0.0,
        }
    }

    fn rosenbrock(x: &DVector<f64>) -> Result<(f64, DVector<f64>)> {
        let n = x.len();
        let mut f = 0.0;
        let mut g = DVector::zeros(n);
        for i in 0..n - 1 {
            let (a, b) = (1.0 - x[i], x[i + 1] - x[i] * x[i]);
            f += a * a + 100.0 * b * b;
            g[i] += -2.0 * a - 400.0 * x[i] * b;
            g[i + 1] += 200.0 * b;
        }
        Ok((f, g))
    }

    #[test]
    fn lbfgs_finds_the_minimum_of_a_ten_dimensional_rosenbrock_function() {
        let out = minimize(rosenbrock, DVector::from_element(10, -1.2), options()).expect("runs");
        assert_eq!(out.stop, StopReason::GradientNorm);
        assert!((out.x - DVector::from_element(10, 1.0)).amax() < 1e-6);
    }

    #[test]
    fn failed_evaluations_during_the_line_search_shrink_the_step() {
        // A quadratic with its minimum at 3 that cannot be evaluated beyond 3.2 (NaN or error).
        let f = |x: &DVector<f64>| -> Result<(f64, DVector<f64>)> {
            if x[0] > 3.5 {
                return Err(GpError::Numerical("outside".into()));
            }
            if x[0] > 3.2 {
                return Ok((f64::NAN, DVector::from_element(1, f64::NAN)));
            }
            Ok((
                (x[0] - 3.0).powi(2),
                DVector::from_element(1, 2.0 * (x[0] - 3.0)),
            ))
        };
        let out = minimize(f, DVector::from_element(1, -20.0), options()).expect("runs");
        assert!((out.x[0] - 3.0).abs() < 1e-6, "ended at {}", out.x[0]);
    }

    #[test]
    fn a_failing_start_is_an_error() {
        let f =
            |_: &DVector<f64>| -> Result<(f64, DVector<f64>)> { Ok((f64::NAN, DVector::zeros(1))) };
        assert!(minimize(f, DVector::zeros(1), options()).is_err());
    }
}
