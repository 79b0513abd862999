//! The motion map a motion-adapted kernel reads (DGPOM paper, Sections 2.2-2.4): a mean velocity
//! field Υ(x) and its error field ε(x) over the ground plane, and the displacement of a particle
//! carried by Υ (eq. 4), integrated numerically with classical Runge-Kutta steps of a fixed
//! length. The field does not change with time (the paper's "temporally intransigent" motion map),
//! so a flow line depends only on where it starts and for how long it is followed.

use std::fmt;

/// A stationary velocity field with an error estimate, in metres and seconds.
pub trait MotionField: fmt::Debug + Send + Sync {
    /// Υ(x): the mean velocity at `xy_m`, m/s.
    fn velocity_mps(&self, xy_m: [f64; 2]) -> [f64; 2];

    /// ε(x): the expected error of Υ at `xy_m`, m/s; positive.
    fn error_mps(&self, xy_m: [f64; 2]) -> f64;
}

/// Where a particle at `xy_m` at time `from_secs` is at `to_secs` when carried by `field`
/// (backwards in time if `to_secs < from_secs`): x + ψ(t, t', x) of eq. 4, by fourth-order
/// Runge-Kutta with equal steps of at most `step_secs`.
///
/// ```
/// use patchflow_gp::{MotionField, transported};
/// #[derive(Debug)]
/// struct Uniform;
/// impl MotionField for Uniform {
///     fn velocity_mps(&self, _: [f64; 2]) -> [f64; 2] { [2.0, -1.0] }
///     fn error_mps(&self, _: [f64; 2]) -> f64 { 0.1 }
/// }
/// let p = transported(&Uniform, [1.0, 1.0], 3.0, 5.0, 0.1);
/// assert!((p[0] - 5.0).abs() < 1e-12 && (p[1] + 1.0).abs() < 1e-12);
/// ```
pub fn transported<F: MotionField + ?Sized>(
    field: &F,
    xy_m: [f64; 2],
    from_secs: f64,
    to_secs: f64,
    step_secs: f64,
) -> [f64; 2] {
    let span = to_secs - from_secs;
    if span == 0.0 || !span.is_finite() {
        return xy_m;
    }
    let steps = (span.abs() / step_secs.max(1e-6)).ceil().max(1.0);
    let h = span / steps;
    let mut p = xy_m;
    let along = |p: [f64; 2], k: [f64; 2], f: f64| [p[0] + f * k[0], p[1] + f * k[1]];
    for _ in 0..steps as usize {
        let k1 = field.velocity_mps(p);
        let k2 = field.velocity_mps(along(p, k1, h / 2.0));
        let k3 = field.velocity_mps(along(p, k2, h / 2.0));
        let k4 = field.velocity_mps(along(p, k3, h));
        for d in 0..2 {
            p[d] += h / 6.0 * (k1[d] + 2.0 * k2[d] + 2.0 * k3[d] + k4[d]);
        }
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rigid rotation about the origin at 0.5 rad/s.
    #[derive(Debug)]
    struct Rotation;

    impl MotionField for Rotation {
        fn velocity_mps(&self, xy_m: [f64; 2]) -> [f64; 2] {
            [-0.5 * xy_m[1], 0.5 * xy_m[0]]
        }
        fn error_mps(&self, _: [f64; 2]) -> f64 {
            1.0
        }
    }

    #[test]
    fn a_particle_in_a_rotating_field_stays_on_its_circle_and_turns_by_the_elapsed_angle() {
        // 4 s at 0.5 rad/s: 2 rad around a circle of radius 10.
        let p = transported(&Rotation, [10.0, 0.0], 1.0, 5.0, 0.1);
        let (c, s) = (2f64.cos(), 2f64.sin());
        assert!(
            (p[0] - 10.0 * c).abs() < 1e-5 && (p[1] - 10.0 * s).abs() < 1e-5,
            "{p:?}"
        );
    }

    #[test]
    fn carrying_a_particle_back_returns_it_where_it_started() {
        let there = transported(&Rotation, [3.0, -4.0], 0.0, 2.7, 0.1);
        let back = transported(&Rotation, there, 2.7, 0.0, 0.1);
        assert!(
            (back[0] - 3.0).abs() < 1e-6 && (back[1] + 4.0).abs() < 1e-6,
            "{back:?}"
        );
        assert_eq!(
            transported(&Rotation, [3.0, -4.0], 2.0, 2.0, 0.1),
            [3.0, -4.0]
        );
    }
}
