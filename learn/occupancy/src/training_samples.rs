//! Training data of an occupancy map from planar scans (DGPOM paper, Section 2; GPOM): each
//! return is an occupied sample, and free samples lie along every beam between its start (the
//! sensor, or where a 3-D beam enters the height slice) and its return (stopping short of the surface) or out to maximum range for a beam that returned
//! nothing. Free samples are stratified along the beam, one per `free_spacing_m` at a seeded
//! random place within its stretch, so beams of one scan do not put their samples on common
//! circles around the sensor.

use patchflow_dataset::{GOLDEN_GAMMA, splitmix64_finalize};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use crate::{OccupancyError, PlanarScan, Result, Thinning};

/// One labelled training point: a place in the ground plane at a time, occupied or free.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OccupancySample {
    /// Position, world frame, metres.
    pub xy_m: [f64; 2],
    /// Time of the scan it comes from, seconds since the sequence started.
    pub t_secs: f64,
    /// True at a return, false along a beam.
    pub occupied: bool,
}

/// How training samples are drawn from a scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SampleParams {
    /// One free sample per this length of beam, metres.
    pub free_spacing_m: f64,
    /// Free samples stop this far before a return, metres (the surface is not free space).
    pub stop_short_m: f64,
    /// Seed of the places of the free samples along their stretches.
    pub seed: u64,
    /// Thinning of each scan's samples to a budget, for dense scans (a 3-D lidar's height
    /// slice); `None` keeps every sample (a planar scanner's scans).
    pub thinning: Option<Thinning>,
    /// Whether the scans before the query scan give free samples too (else only their returns).
    pub past_free: bool,
}

impl Default for SampleParams {
    fn default() -> Self {
        Self {
            free_spacing_m: 3.0,
            stop_short_m: 0.5,
            seed: 7,
            thinning: None,
            past_free: true,
        }
    }
}

impl SampleParams {
    /// Checks the parameters; an error names the bad field.
    pub fn validate(&self) -> Result<()> {
        if !(self.free_spacing_m.is_finite() && self.free_spacing_m >= 0.05) {
            return Err(OccupancyError::BadParameter {
                name: "SampleParams.free_spacing_m",
                reason: format!("must be at least 0.05 m, got {}", self.free_spacing_m),
            });
        }
        if !(self.stop_short_m.is_finite() && self.stop_short_m >= 0.0) {
            return Err(OccupancyError::BadParameter {
                name: "SampleParams.stop_short_m",
                reason: format!("must be zero or positive, got {}", self.stop_short_m),
            });
        }
        match &self.thinning {
            Some(thinning) => thinning.validate(),
            None => Ok(()),
        }
    }
}

/// The training samples of a map's `scans` (oldest first), each scan's thinned to its budget if
/// `params` thins, and how many were drawn before thinning.
pub fn window_samples(
    scans: &[PlanarScan],
    params: &SampleParams,
) -> (Vec<OccupancySample>, usize) {
    let (mut kept, mut drawn) = (Vec::new(), 0);
    for (i, scan) in scans.iter().enumerate() {
        let mut samples = scan_samples(scan, params);
        if !params.past_free && i + 1 < scans.len() {
            samples.retain(|s| s.occupied);
        }
        drawn += samples.len();
        match &params.thinning {
            Some(thinning) => {
                let places: Vec<([f64; 2], bool)> =
                    samples.iter().map(|s| (s.xy_m, s.occupied)).collect();
                kept.extend(thinning.kept(&places).into_iter().map(|i| samples[i]));
            }
            None => kept.extend(samples),
        }
    }
    (kept, drawn)
}

/// The training samples of one scan: for each beam in firing order, its free samples from the
/// sensor outwards, then its return if it has one.
pub fn scan_samples(scan: &PlanarScan, params: &SampleParams) -> Vec<OccupancySample> {
    let mut out = Vec::new();
    for (b, beam) in scan.beams.iter().enumerate() {
        let [ox, oy] = beam.start_m;
        let (dx, dy) = (beam.end_m[0] - ox, beam.end_m[1] - oy);
        let length = dx.hypot(dy);
        if length <= 0.0 {
            continue;
        }
        let free_length = if beam.hit {
            length - params.stop_short_m
        } else {
            length
        };
        let mut rng = ChaCha8Rng::seed_from_u64(stream_seed(params.seed, scan.index, b));
        let mut k = 0.0;
        loop {
            let d = (k + rng.random::<f64>()) * params.free_spacing_m;
            if d >= free_length {
                break;
            }
            let f = d / length;
            out.push(OccupancySample {
                xy_m: [ox + f * dx, oy + f * dy],
                t_secs: scan.stamp_secs,
                occupied: false,
            });
            k += 1.0;
        }
        if beam.hit {
            out.push(OccupancySample {
                xy_m: beam.end_m,
                t_secs: scan.stamp_secs,
                occupied: true,
            });
        }
    }
    out
}

/// Seed of one beam's stream: a SplitMix64-style mix of the run seed, the scan and the beam, so
/// a scan's samples do not depend on which other scans are drawn.
fn stream_seed(seed: u64, scan: usize, beam: usize) -> u64 {
    splitmix64_finalize(seed ^ (scan as u64).wrapping_mul(GOLDEN_GAMMA) ^ (beam as u64) << 32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Beam;

    fn two_metres() -> SampleParams {
        SampleParams {
            free_spacing_m: 2.0,
            ..SampleParams::default()
        }
    }

    /// A scan from the origin: one beam hits at 10 m along +x, one sees nothing along +y (20 m).
    fn scan() -> PlanarScan {
        PlanarScan {
            index: 4,
            stamp_secs: 4.0,
            sensor_m: [0.0, 0.0],
            yaw_rad: 0.0,
            beams: vec![
                Beam {
                    start_m: [0.0, 0.0],
                    end_m: [10.0, 0.0],
                    hit: true,
                },
                Beam {
                    start_m: [0.0, 0.0],
                    end_m: [0.0, 20.0],
                    hit: false,
                },
            ],
        }
    }

    #[test]
    fn free_samples_lie_on_their_beam_short_of_the_return_and_the_return_is_occupied() {
        let params = two_metres();
        let samples = scan_samples(&scan(), &params);
        let (along_x, along_y): (Vec<&OccupancySample>, Vec<&OccupancySample>) =
            samples.iter().partition(|s| s.xy_m[1] == 0.0);
        let occupied: Vec<_> = samples.iter().filter(|s| s.occupied).collect();
        assert_eq!(occupied.len(), 1);
        assert_eq!(occupied[0].xy_m, [10.0, 0.0]);
        for s in along_x.iter().filter(|s| !s.occupied) {
            assert!((0.0..9.5).contains(&s.xy_m[0]), "{:?}", s.xy_m);
        }
        // One free sample per 2 m stretch: 9.5 m of the hit beam give 4 or 5.
        let free_x = along_x.iter().filter(|s| !s.occupied).count();
        assert!((4..=5).contains(&free_x), "{free_x}");
        // The beam without a return is free all the way to maximum range: 10 samples.
        assert_eq!(along_y.len(), 10);
        assert!(
            along_y
                .iter()
                .all(|s| !s.occupied && s.xy_m[0] == 0.0 && s.xy_m[1] < 20.0)
        );
        assert!(along_y.iter().any(|s| s.xy_m[1] > 18.0));
        assert!(samples.iter().all(|s| s.t_secs == 4.0));
    }

    #[test]
    fn free_samples_fall_one_per_stretch_at_seeded_places() {
        let params = two_metres();
        let ys: Vec<f64> = scan_samples(&scan(), &params)
            .iter()
            .filter(|s| s.xy_m[0] == 0.0 && s.xy_m[1] > 0.0)
            .map(|s| s.xy_m[1])
            .collect();
        for (k, y) in ys.iter().enumerate() {
            let stretch = 2.0 * k as f64..2.0 * (k + 1) as f64;
            assert!(stretch.contains(y), "sample {k} at {y}");
        }
        assert_eq!(
            scan_samples(&scan(), &params),
            scan_samples(&scan(), &params)
        );
        let other = SampleParams { seed: 8, ..params };
        assert_ne!(
            scan_samples(&scan(), &other),
            scan_samples(&scan(), &two_metres())
        );
    }
}
