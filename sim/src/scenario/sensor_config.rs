//! The `[sensor]` table: how the lidar departs from an ideal one (ray drop, range noise growing
//! with range, mixed pixels at edges, per-channel intensity gain and elevation calibration error).
//! The `[lidar]` table keeps the geometry and the constant range noise; every knob here is
//! optional and defaults to the scenario's realism rung. Zero switches an effect off.

use serde::{Deserialize, Serialize};

use super::bounds::Bound;
use super::realism::Realism;

/// Sensor-error knobs, as written in a scenario file.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SensorConfig {
    /// Range at which a Lambertian surface of reflectivity 0.1 seen head-on returns half of the
    /// time, metres; the return probability falls with reflectivity × cos(incidence) / range²
    /// (dark, far and grazing surfaces lose returns). 0: no ray drop.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub detection_range_m: Option<f64>,
    /// Extra range noise per metre of range (std, added to `[lidar] range_noise_std_m`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range_noise_per_m: Option<f64>,
    /// Chance that a beam straddling a depth edge returns a mixed range between the two surfaces.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mixed_pixels: Option<f64>,
    /// Std of the per-channel intensity gain (log-normal, fixed for the sequence).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub intensity_gain_std: Option<f64>,
    /// Std of the per-channel elevation calibration error, degrees: the beam is cast at the true
    /// elevation, the point is written at the nominal one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elevation_error_deg: Option<f64>,
}

/// The resolved `[sensor]` knobs as plain values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorKnobs {
    /// See [`SensorConfig::detection_range_m`].
    pub detection_range_m: f64,
    /// See [`SensorConfig::range_noise_per_m`].
    pub range_noise_per_m: f64,
    /// See [`SensorConfig::mixed_pixels`].
    pub mixed_pixels: f64,
    /// See [`SensorConfig::intensity_gain_std`].
    pub intensity_gain_std: f64,
    /// See [`SensorConfig::elevation_error_deg`].
    pub elevation_error_deg: f64,
}

impl SensorKnobs {
    /// The knobs of a rung.
    pub fn of(rung: Realism) -> Self {
        match rung {
            Realism::Ideal => Self {
                detection_range_m: 0.0,
                range_noise_per_m: 0.0,
                mixed_pixels: 0.0,
                intensity_gain_std: 0.0,
                elevation_error_deg: 0.0,
            },
            Realism::Urban => Self {
                detection_range_m: 140.0,
                range_noise_per_m: 0.0002,
                mixed_pixels: 0.5,
                intensity_gain_std: 0.1,
                elevation_error_deg: 0.05,
            },
            Realism::Harsh => Self {
                detection_range_m: 90.0,
                range_noise_per_m: 0.0004,
                mixed_pixels: 0.8,
                intensity_gain_std: 0.2,
                elevation_error_deg: 0.1,
            },
        }
    }

    /// True if the sensor is the ideal one of the first release.
    pub fn ideal(&self) -> bool {
        *self == Self::of(Realism::Ideal)
    }
}

impl SensorConfig {
    /// Fills every missing knob from `rung`.
    pub(crate) fn resolve(&mut self, rung: Realism) {
        let k = SensorKnobs::of(rung);
        self.detection_range_m.get_or_insert(k.detection_range_m);
        self.range_noise_per_m.get_or_insert(k.range_noise_per_m);
        self.mixed_pixels.get_or_insert(k.mixed_pixels);
        self.intensity_gain_std.get_or_insert(k.intensity_gain_std);
        self.elevation_error_deg
            .get_or_insert(k.elevation_error_deg);
    }

    /// The knobs as plain values (those still missing from the `urban` rung).
    pub fn knobs(&self) -> SensorKnobs {
        let k = SensorKnobs::of(Realism::Urban);
        SensorKnobs {
            detection_range_m: self.detection_range_m.unwrap_or(k.detection_range_m),
            range_noise_per_m: self.range_noise_per_m.unwrap_or(k.range_noise_per_m),
            mixed_pixels: self.mixed_pixels.unwrap_or(k.mixed_pixels),
            intensity_gain_std: self.intensity_gain_std.unwrap_or(k.intensity_gain_std),
            elevation_error_deg: self.elevation_error_deg.unwrap_or(k.elevation_error_deg),
        }
    }

    /// Every knob outside its range, with the field's name.
    pub(crate) fn problems(&self) -> Vec<(&'static str, String)> {
        let k = self.knobs();
        let detection = match k.detection_range_m {
            0.0 => None,
            r => DETECTION_RANGE_M.check("detection_range_m", r),
        };
        [
            detection,
            RANGE_NOISE_PER_M.check("range_noise_per_m", k.range_noise_per_m),
            MIXED_PIXELS.check("mixed_pixels", k.mixed_pixels),
            INTENSITY_GAIN_STD.check("intensity_gain_std", k.intensity_gain_std),
            ELEVATION_ERROR_DEG.check("elevation_error_deg", k.elevation_error_deg),
        ]
        .into_iter()
        .flatten()
        .collect()
    }
}

// Documented in scenarios/README.md ("The realism ladder"); change both together.

/// Range of half detection for a dark target (0, outside the bound, switches ray drop off).
const DETECTION_RANGE_M: Bound = Bound::new(
    10.0,
    1000.0,
    "m",
    "a lidar that sees dark asphalt at 10 m to 1 km; 0 switches ray drop off",
);
/// Range noise per metre of range.
const RANGE_NOISE_PER_M: Bound = Bound::new(0.0, 0.01, "m/m", "at most 1 m of noise at 100 m");
/// Chance of a mixed pixel at an edge.
const MIXED_PIXELS: Bound = Bound::new(0.0, 1.0, "", "a probability");
/// Spread of the per-channel intensity gain.
const INTENSITY_GAIN_STD: Bound = Bound::new(
    0.0,
    1.0,
    "",
    "a log-normal gain within a factor of e per std",
);
/// Per-channel elevation calibration error.
const ELEVATION_ERROR_DEG: Bound = Bound::new(
    0.0,
    1.0,
    "°",
    "factory calibration is good to a few hundredths of a degree",
);
