//! One sequence of a dataset made ready for occupancy maps: its sensor, every scan as beams in
//! the world's ground plane, and the exact ground truth. Everything comes from the dataset crate
//! (no scene code); a dataset written before `static.json` and `sensor.json` existed is an error
//! that names the missing file. A planar scanner's sweeps are its scans as they are
//! ([`OccupancySequence::load`]); a 3-D lidar's are cut to a height slice by a function the
//! caller hands in ([`OccupancySequence::load_with`]: the slice lives with the motion-estimation
//! features, which this crate does not depend on).

use std::path::PathBuf;

use patchflow_dataset::{SensorInfo, SequenceReader, Sweep};

use crate::{GroundTruth, OccupancyError, PlanarScan, Result};

/// A sequence's scans in the plane, and its truth.
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
    /// Height above the ground the scans observe, where the truth is taken, metres.
    pub scan_height_m: f64,
}

impl OccupancySequence {
    /// Reads every scan and the truth of a planar scanner's sequence (truth at its mount
    /// height); another sensor's sweep is an error naming the folder.
    pub fn load(reader: &SequenceReader) -> Result<Self> {
        let height_m = reader.sensor()?.mount_height_m;
        Self::load_with(reader, height_m, &PlanarScan::from_sweep)
    }

    /// Reads every sweep of `reader`'s sequence as a scan in the plane through `to_plane` (the
    /// sweep and the sensor to the scan, or why not), with the truth taken `scan_height_m` above
    /// the ground.
    pub fn load_with(
        reader: &SequenceReader,
        scan_height_m: f64,
        to_plane: &(dyn Fn(&Sweep, &SensorInfo) -> std::result::Result<PlanarScan, String> + Sync),
    ) -> Result<Self> {
        let sensor = reader.sensor()?;
        let statics = reader.static_obstacles()?;
        let mut scans = Vec::with_capacity(reader.len());
        let mut actors = Vec::with_capacity(reader.len());
        for index in 0..reader.len() {
            let sweep = reader.read_sweep(index)?;
            let scan = to_plane(&sweep, &sensor).map_err(|reason| OccupancyError::Unsupported {
                path: reader.dir().to_owned(),
                reason: format!("scan {index}: {reason}"),
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
            scan_height_m,
        })
    }

    /// The height above the ground the scans observe, where truth is taken.
    pub fn scan_height_m(&self) -> f64 {
        self.scan_height_m
    }
}
