//! Bounds on every number of a scenario, checked after parsing and before anything is allocated
//! or built. Finite is not enough: `rate_hz = 1e-20` or a centre of 1e300 m are finite, pass a
//! plain sign check, and then overflow the `f32` the physics library works in (its BVH build
//! panicked on them). Each bound states its unit and why it is where it is; a value outside gets
//! a message with the value, the range and the reason, e.g.
//! `rate_hz = 1e-20 is below 0.1 Hz (allowed 0.1 to 100 Hz: ...)`.
//!
//! Sizes derived from several fields (rays in a sweep, boxes in a row, the farthest an actor
//! gets) are checked in [`super::derived_limits`] against the limits below, also before any work.
//! New scenario fields adopt the mechanism by naming a [`Bound`] and calling [`Bound::check`].

/// A closed range a number must lie in, with its unit and the reason for the range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Bound {
    /// Smallest allowed value.
    pub min: f64,
    /// Largest allowed value.
    pub max: f64,
    /// Unit written after the numbers ("" for none).
    pub unit: &'static str,
    /// Why the range is what it is, in a few words.
    pub why: &'static str,
}

impl Bound {
    /// A range `[min, max]` in `unit`, for the reason `why`.
    pub(crate) const fn new(min: f64, max: f64, unit: &'static str, why: &'static str) -> Self {
        Self {
            min,
            max,
            unit,
            why,
        }
    }

    /// What is wrong with `value` of `field`, if it lies outside the range (or is not a number).
    pub(crate) fn problem(&self, field: &str, value: f64) -> Option<String> {
        let unit = |v: f64| match self.unit {
            "" => show(v),
            u => format!("{} {u}", show(v)),
        };
        let what = if value.is_nan() {
            "is not a finite number".to_owned()
        } else if value < self.min {
            format!("is below {}", unit(self.min))
        } else if value > self.max {
            format!("is above {}", unit(self.max))
        } else {
            return None;
        };
        Some(format!(
            "{field} = {} {what} (allowed {} to {}: {})",
            show(value),
            show(self.min),
            unit(self.max),
            self.why
        ))
    }

    /// [`Self::problem`] paired with the field it is about, as the scenario checks collect them.
    pub(crate) fn check(&self, field: &'static str, value: f64) -> Option<(&'static str, String)> {
        self.problem(field, value).map(|reason| (field, reason))
    }

    /// The first value of `values` outside the range, reported as `field`.
    pub(crate) fn check_each<'a>(
        &self,
        field: &'static str,
        values: impl IntoIterator<Item = &'a f64>,
    ) -> Option<(&'static str, String)> {
        values.into_iter().find_map(|&v| self.check(field, v))
    }
}

/// A whole number that must lie in `min..=max` (a count), with the reason.
pub(crate) fn check_count(
    field: &'static str,
    value: u64,
    min: u64,
    max: u64,
    why: &str,
) -> Option<(&'static str, String)> {
    (!(min..=max).contains(&value)).then(|| {
        (
            field,
            format!("{field} = {value} is outside {min} to {max} ({why})"),
        )
    })
}

/// A number as a person writes it: `1e-20`, `1e300`, `0.1`, `2000`.
pub(crate) fn show(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && a.is_finite() && !(1e-4..1e9).contains(&a) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

// ── Limits ─────────────────────────────────────────────────────────────────────────────────
// Documented in scenarios/README.md ("Limits"); change both together.

/// Any scenario time (start, actor start, speed change, the end of the last sweep).
pub(crate) const TIME_SECS: Bound = Bound::new(
    -86_400.0,
    86_400.0,
    "s",
    "scenario times lie within a day of zero",
);

/// Any ground-plane coordinate given in a scenario (paths, centres, row ends).
pub(crate) const COORD_M: Bound = Bound::new(
    -100_000.0,
    100_000.0,
    "m",
    "the world reaches 100 km from the origin, where the physics' f32 still resolves 8 mm",
);

/// Any box side (actors, structures).
pub(crate) const SIZE_M: Bound = Bound::new(0.01, 1000.0, "m", "a box is 1 cm to 1 km a side");

/// Any yaw angle.
pub(crate) const YAW_DEG: Bound = Bound::new(-3600.0, 3600.0, "°", "at most ten turns");

/// Any reflectivity.
pub(crate) const REFLECTIVITY: Bound = Bound::new(0.0, 1.0, "", "a share of the light");

/// The problem with a surface's lidar reflectivity, if it lies outside [0, 1].
pub(crate) fn reflectivity_problem(reflectivity: Option<f64>) -> Option<(&'static str, String)> {
    REFLECTIVITY.check("reflectivity", reflectivity?)
}

/// Distance between the boxes of a row.
pub(crate) const SPACING_M: Bound =
    Bound::new(0.1, 10_000.0, "m", "rows of boxes 10 cm to 10 km apart");

/// A turn radius.
pub(crate) const TURN_RADIUS_M: Bound = Bound::new(
    0.3,
    10_000.0,
    "m",
    "from a pedestrian's turn to a straight road",
);

/// Sweep rate of the lidar.
pub(crate) const RATE_HZ: Bound = Bound::new(0.1, 100.0, "Hz", "a turn takes 10 ms to 10 s");

/// Elevation of a lidar channel.
pub(crate) const ELEVATION_DEG: Bound = Bound::new(
    -89.9,
    89.9,
    "°",
    "a beam below the zenith and above the nadir",
);

/// A planar scanner's field of view.
pub(crate) const FOV_DEG: Bound = Bound::new(1.0, 360.0, "°", "a slit to a full turn");

/// Maximum range of the lidar.
pub(crate) const MAX_RANGE_M: Bound = Bound::new(
    0.1,
    2000.0,
    "m",
    "automotive lidars reach at most a few hundred metres",
);

/// Height of the lidar's optical centre above the ground.
pub(crate) const MOUNT_HEIGHT_M: Bound = Bound::new(0.1, 50.0, "m", "from a bumper to a mast");

/// Range noise of the lidar (std).
pub(crate) const RANGE_NOISE_STD_M: Bound =
    Bound::new(0.0, 1.0, "m", "noise above 1 m would swamp the geometry");

/// Share of returns dropped at random.
pub(crate) const DROPOUT: Bound =
    Bound::new(0.0, 0.99, "", "a probability; 1 would drop every return");

/// Atmospheric attenuation of the intensity.
pub(crate) const ATTENUATION_PER_M: Bound = Bound::new(
    0.0,
    1.0,
    "1/m",
    "exp(-1 · r) is dark beyond a few metres already",
);

/// Most boxes in one structure row.
pub(crate) const MAX_ROW_BOXES: u64 = 10_000;

/// Most boxes in all structures together.
pub(crate) const MAX_BOXES: u64 = 100_000;

/// Most listed actors (instance ids are 16 bits, random traffic needs some).
pub(crate) const MAX_ACTORS: u64 = 60_000;

/// Most waypoints of one path, and speed changes of one actor.
pub(crate) const MAX_PATH_POINTS: u64 = 100_000;

/// Most random actors.
pub(crate) const MAX_RANDOM_ACTORS: u64 = 2000;

/// Most path length random cars may need together (each drives its speed × the run's length),
/// metres; their waypoints (one per block of the grid) are held in memory.
pub(crate) const MAX_TRAFFIC_PATH_M: f64 = 10_000_000.0;

/// Most sweeps of one scenario.
pub(crate) const MAX_SWEEPS: u64 = patchflow_dataset::MAX_SWEEPS as u64;

/// Most rays one sweep may cast (channels × azimuth steps): the dataset format's point limit.
pub(crate) const MAX_RAYS_PER_SWEEP: u64 = patchflow_dataset::MAX_POINTS_PER_SWEEP as u64;

/// Memory one ray costs while a sweep is cast and written, bytes: its scratch slot (36), the
/// gathered sweep (36), the file buffers (36) and its firing-table direction (12).
pub(crate) const BYTES_PER_RAY: u64 = 120;

/// Largest scenario file read, bytes: far above any real scenario, small enough to parse at once.
pub(crate) const MAX_SCENARIO_BYTES: u64 = 16 << 20;

/// Bytes as a person reads them: `5.6 GB`, `480 MB`.
pub(crate) fn gigabytes(bytes: u64) -> String {
    let b = bytes as f64;
    if b >= 1e9 {
        format!("{:.1} GB", b / 1e9)
    } else {
        format!("{:.0} MB", (b / 1e6).max(1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_below_the_range_names_value_range_unit_and_reason() {
        let reason = RATE_HZ.problem("rate_hz", 1e-20).unwrap();
        assert!(
            reason.starts_with("rate_hz = 1e-20 is below 0.1 Hz"),
            "{reason}"
        );
        assert!(reason.contains("allowed 0.1 to 100 Hz"), "{reason}");
    }

    #[test]
    fn huge_and_non_numbers_are_reported_readably() {
        let reason = COORD_M.problem("centre_m", 1e300).unwrap();
        assert!(
            reason.starts_with("centre_m = 1e300 is above 100000 m"),
            "{reason}"
        );
        assert!(
            COORD_M
                .problem("x", f64::NAN)
                .unwrap()
                .contains("not a finite number")
        );
        assert!(
            COORD_M
                .problem("x", f64::INFINITY)
                .unwrap()
                .contains("above")
        );
    }

    #[test]
    fn values_inside_the_range_and_on_its_edges_pass() {
        for v in [0.1, 10.0, 100.0] {
            assert_eq!(RATE_HZ.problem("rate_hz", v), None);
        }
    }

    #[test]
    fn a_count_outside_its_range_is_reported() {
        assert!(check_count("channels", 0, 1, 512, "lasers").is_some());
        assert!(check_count("channels", 64, 1, 512, "lasers").is_none());
    }
}
