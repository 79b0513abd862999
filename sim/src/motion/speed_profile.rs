//! A speed profile along a path: piecewise constant acceleration within a limit, integrated
//! exactly, so arc length, speed and acceleration are known in closed form at any time.

/// One piece of constant acceleration starting at `t0`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Piece {
    t0: f64,
    s0: f64,
    v0: f64,
    a: f64,
}

/// Arc length, speed and acceleration at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileState {
    /// Arc length along the path, metres (0 at the first waypoint).
    pub s_m: f64,
    /// Speed, m/s.
    pub speed_mps: f64,
    /// Tangential acceleration, m/s².
    pub accel_mps2: f64,
}

/// Speed over time: `initial` before `start`, then towards each target speed in turn.
#[derive(Debug, Clone, PartialEq)]
pub struct SpeedProfile {
    start_secs: f64,
    initial_mps: f64,
    pieces: Vec<Piece>,
}

impl SpeedProfile {
    /// Builds the profile. At `start_secs` the actor passes arc length 0 at `initial_mps` and
    /// approaches `cruise_mps`; each `[time, speed]` of `changes` sets a new target from that time.
    /// Speed changes at `accel_mps2` until the target is met.
    pub fn new(
        start_secs: f64,
        initial_mps: f64,
        cruise_mps: f64,
        accel_mps2: f64,
        changes: &[[f64; 2]],
    ) -> Self {
        let targets: Vec<(f64, f64)> = std::iter::once((start_secs, cruise_mps))
            .chain(changes.iter().map(|c| (c[0], c[1])))
            .collect();
        let (mut t, mut s, mut v) = (start_secs, 0.0, initial_mps);
        let mut pieces = Vec::new();
        for (i, &(_, target)) in targets.iter().enumerate() {
            let next_t = targets.get(i + 1).map_or(f64::INFINITY, |n| n.0);
            if v != target {
                let a = accel_mps2.copysign(target - v);
                let ramp_secs = (target - v).abs() / accel_mps2;
                pieces.push(Piece {
                    t0: t,
                    s0: s,
                    v0: v,
                    a,
                });
                let dt = ramp_secs.min(next_t - t);
                s += v * dt + 0.5 * a * dt * dt;
                v += a * dt;
                t += dt;
                if ramp_secs > next_t - (t - dt) {
                    continue;
                }
                v = target;
            }
            pieces.push(Piece {
                t0: t,
                s0: s,
                v0: v,
                a: 0.0,
            });
            if next_t.is_finite() {
                s += v * (next_t - t);
                t = next_t;
            }
        }
        Self {
            start_secs,
            initial_mps,
            pieces,
        }
    }

    /// Arc length, speed and acceleration at time `t_secs`.
    pub fn at(&self, t_secs: f64) -> ProfileState {
        if t_secs < self.start_secs {
            return ProfileState {
                s_m: self.initial_mps * (t_secs - self.start_secs),
                speed_mps: self.initial_mps,
                accel_mps2: 0.0,
            };
        }
        let i = self
            .pieces
            .partition_point(|p| p.t0 <= t_secs)
            .saturating_sub(1);
        let Some(p) = self.pieces.get(i) else {
            return ProfileState {
                s_m: 0.0,
                speed_mps: self.initial_mps,
                accel_mps2: 0.0,
            };
        };
        let dt = t_secs - p.t0;
        ProfileState {
            s_m: p.s0 + p.v0 * dt + 0.5 * p.a * dt * dt,
            speed_mps: (p.v0 + p.a * dt).max(0.0),
            accel_mps2: p.a,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speed_never_changes_faster_than_the_limit_and_arc_length_integrates_it() {
        let profile = SpeedProfile::new(1.0, 0.0, 8.0, 2.0, &[[4.0, 3.0], [5.0, 9.0], [12.0, 0.0]]);
        let dt = 1e-3;
        let mut prev = profile.at(-1.0);
        for i in 1..20_000 {
            let t = -1.0 + i as f64 * dt;
            let now = profile.at(t);
            assert!(
                (now.speed_mps - prev.speed_mps).abs() <= 2.0 * dt + 1e-9,
                "speed jumps at t = {t}"
            );
            let mean_v = 0.5 * (now.speed_mps + prev.speed_mps);
            assert!(
                (now.s_m - prev.s_m - mean_v * dt).abs() < 1e-9,
                "s does not integrate v at t = {t}"
            );
            assert!(now.speed_mps >= 0.0);
            prev = now;
        }
    }

    #[test]
    fn targets_are_reached_and_held() {
        let profile = SpeedProfile::new(0.0, 0.0, 8.0, 2.0, &[]);
        assert!((profile.at(2.0).speed_mps - 4.0).abs() < 1e-12);
        assert!((profile.at(4.0).speed_mps - 8.0).abs() < 1e-12);
        assert!((profile.at(100.0).speed_mps - 8.0).abs() < 1e-12);
        assert!((profile.at(4.0).s_m - 16.0).abs() < 1e-12);
    }

    #[test]
    fn a_target_interrupted_before_it_is_reached_continues_from_the_current_speed() {
        let profile = SpeedProfile::new(0.0, 0.0, 10.0, 1.0, &[[2.0, 0.0]]);
        assert!((profile.at(2.0).speed_mps - 2.0).abs() < 1e-12);
        assert!((profile.at(3.0).speed_mps - 1.0).abs() < 1e-12);
        assert!(profile.at(10.0).speed_mps.abs() < 1e-12);
        assert!((profile.at(10.0).s_m - 4.0).abs() < 1e-12);
    }

    #[test]
    fn before_the_start_a_moving_actor_is_on_the_lead_in_and_a_standing_one_waits() {
        assert!((SpeedProfile::new(2.0, 5.0, 5.0, 2.0, &[]).at(0.0).s_m + 10.0).abs() < 1e-12);
        assert_eq!(SpeedProfile::new(2.0, 0.0, 5.0, 2.0, &[]).at(0.0).s_m, 0.0);
    }
}
