//! Which sequences `patchflow occupancy` maps, and how it reads them (SPEC §7 forms unchanged:
//! the dataset says it). A planar scanner's sequence is read scan by scan as it is. A spinning
//! 3-D lidar's sequence is read through the thesis height slice when the lidar turns at 1 Hz or
//! slower: the DGPOM paper's scan rate, the rate the query times t = 3 … 9 s assume (scan index =
//! seconds), and a rate no driving sequence of the motion-estimation data uses (10 Hz). Training
//! runs (`<name>_train`) are never scored; they are read the same way for the motion map.
//! Dense slices are thinned to a budget per scan ([`Thinning`]); planar scans are not.

use patchflow_dataset::{Dataset, SensorInfo, SensorKind};
use patchflow_occupancy::{OccupancySequence, SampleParams, Thinning};

use super::slice_scan::{height_slice_scan, slice_height_m};
use crate::error::EvalError;

/// How a sequence's sweeps become occupancy observations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SequenceKind {
    /// A planar range scanner: its scans as they are.
    Planar,
    /// A spinning 3-D lidar at 1 Hz or slower: its sweeps cut to the height slice.
    HeightSlice,
}

/// Fastest spinning lidar mapped through the slice, Hz (the paper's 1 Hz scans).
const SLICE_MAX_RATE_HZ: f64 = 1.0;

impl SequenceKind {
    /// The kind of a sequence with `sensor`, `None` if it is not mapped (a spinning lidar
    /// faster than 1 Hz: driving data).
    ///
    /// ```
    /// use patchflow_dataset::{SensorInfo, SensorKind};
    /// use patchflow_eval::SequenceKind;
    /// let planar = SensorInfo {
    ///     kind: SensorKind::Planar,
    ///     rate_hz: 1.0,
    ///     max_range_m: 80.0,
    ///     mount_height_m: 0.5,
    ///     columns: 181,
    ///     first_azimuth_deg: 90.0,
    ///     azimuth_step_deg: -1.0,
    ///     elevations_deg: vec![0.0],
    /// };
    /// assert_eq!(SequenceKind::of(&planar), Some(SequenceKind::Planar));
    /// let driving = SensorInfo { kind: SensorKind::Spinning, rate_hz: 10.0, ..planar };
    /// assert_eq!(SequenceKind::of(&driving), None);
    /// ```
    pub fn of(sensor: &SensorInfo) -> Option<Self> {
        match sensor.kind {
            SensorKind::Planar => Some(Self::Planar),
            SensorKind::Spinning if sensor.rate_hz <= SLICE_MAX_RATE_HZ + 1e-9 => {
                Some(Self::HeightSlice)
            }
            SensorKind::Spinning => None,
        }
    }

    /// The training samples of this kind's maps: free samples placed by `seed`; a slice's
    /// thinned to [`Thinning::default`] per scan.
    pub fn sample_params(self, seed: u64) -> SampleParams {
        SampleParams {
            seed,
            thinning: match self {
                Self::Planar => None,
                Self::HeightSlice => Some(Thinning::default()),
            },
            ..SampleParams::default()
        }
    }

    /// The name in reports.
    pub fn label(self) -> &'static str {
        match self {
            Self::Planar => "planar scanner",
            Self::HeightSlice => "3-D lidar, height slice",
        }
    }
}

/// Reads sequence `name` of `dataset` as occupancy observations of its kind, with its kind; a
/// sequence that is not mapped is an error naming it.
pub fn load_sequence(
    dataset: &Dataset,
    name: &str,
) -> Result<(OccupancySequence, SequenceKind), EvalError> {
    let reader = dataset.sequence(name)?;
    let sensor = reader.sensor()?;
    let kind = SequenceKind::of(&sensor).ok_or_else(|| EvalError::BadResult {
        situation: reader.dir().display().to_string(),
        reason: format!(
            "a spinning lidar at {} Hz is not mapped (occupancy maps take a planar scanner, or a 3-D lidar at {SLICE_MAX_RATE_HZ} Hz or slower)",
            sensor.rate_hz
        ),
    })?;
    let sequence = match kind {
        SequenceKind::Planar => OccupancySequence::load(&reader)?,
        SequenceKind::HeightSlice => {
            OccupancySequence::load_with(&reader, slice_height_m(&sensor), &height_slice_scan)?
        }
    };
    Ok((sequence, kind))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spinning(rate_hz: f64) -> SensorInfo {
        SensorInfo {
            kind: SensorKind::Spinning,
            rate_hz,
            max_range_m: 80.0,
            mount_height_m: 1.73,
            columns: 1800,
            first_azimuth_deg: 180.0,
            azimuth_step_deg: -0.2,
            elevations_deg: vec![2.0, -24.8],
        }
    }

    #[test]
    fn a_spinning_lidar_at_one_hertz_is_read_through_the_slice_and_at_ten_not_at_all() {
        assert_eq!(
            SequenceKind::of(&spinning(1.0)),
            Some(SequenceKind::HeightSlice)
        );
        assert_eq!(
            SequenceKind::of(&spinning(0.5)),
            Some(SequenceKind::HeightSlice)
        );
        assert_eq!(SequenceKind::of(&spinning(10.0)), None);
        assert_eq!(SequenceKind::of(&spinning(1.5)), None);
    }

    #[test]
    fn only_the_slice_is_thinned_and_its_truth_is_taken_in_the_middle_of_the_slice() {
        assert!(SequenceKind::Planar.sample_params(7).thinning.is_none());
        assert_eq!(
            SequenceKind::HeightSlice.sample_params(7).thinning,
            Some(Thinning::default())
        );
        assert_eq!(SequenceKind::HeightSlice.sample_params(9).seed, 9);
        assert!((slice_height_m(&spinning(1.0)) - 0.75).abs() < 1e-12);
    }
}
