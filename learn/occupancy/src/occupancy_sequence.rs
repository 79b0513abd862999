//! One sequence of a dataset made ready for occupancy maps: its sensor, every scan as beams in
//! the world's ground plane, and the exact ground truth. Everything comes from the dataset crate
//! (no scene code); a dataset written before `static.json` and `sensor.json` existed is an error
//! that names the missing file.

use std::path::PathBuf;

use patchflow_dataset::{SensorInfo, SequenceReader};

use crate::{GroundTruth, OccupancyError, PlanarScan, Result};

/// A planar scanner's sequence: scans and truth.
#[derive(Debug, Clone)]
pub struct OccupancySequence {
    /// Sequence name.
    pub name: String,
    /// The sequence folder.
    pub dir: PathBuf,
    /// The sensor's beam pattern.
    pub sensor: SensorInfo,
    /// Every scan, in order.
    pub scans: Vec<PlanarScan>,
    /// Exact occupancy.
    pub truth: GroundTruth,
}

impl OccupancySequence {
    /// Reads every scan and the truth of `reader`'s sequence.
    pub fn load(reader: &SequenceReader) -> Result<Self> {
        let sensor = reader.sensor()?;
        let statics = reader.static_obstacles()?;
        let mut scans = Vec::with_capacity(reader.len());
        let mut actors = Vec::with_capacity(reader.len());
        for index in 0..reader.len() {
            let sweep = reader.read_sweep(index)?;
            let scan = PlanarScan::from_sweep(&sweep, &sensor).map_err(|reason| {
                OccupancyError::Unsupported {
                    path: reader.dir().to_owned(),
                    reason: format!("scan {index}: {reason}"),
                }
            })?;
            scans.push(scan);
            actors.push((sweep.stamp_secs, sweep.objects));
        }
        Ok(Self {
            name: reader.info().name.clone(),
            dir: reader.dir().to_owned(),
            truth: GroundTruth::new(&statics, actors),
            sensor,
            scans,
        })
    }

    /// The height above the ground the scanner sees: its mount height, where truth is taken.
    pub fn scan_height_m(&self) -> f64 {
        self.sensor.mount_height_m
    }
}
