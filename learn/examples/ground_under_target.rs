//! The estimated ground under a situation's target, sweep by sweep, against the truth (the
//! bottom of the target's box): at its centre, its front and back ends, and 2 m ahead of it.
//! Found the far-ground fault of `urban` (docs/ground.md, "The ground under far targets"): with the far
//! road's returns lost, the estimate under targets 30-45 m away stood 0.2-1.5 m high.
//!
//! `cargo run --release -p patchflow-learn --example ground_under_target -- DATASET SEQUENCE`
//! prints one line per sweep: sweep, range (m), then estimate − truth (m) at each place.

use std::path::PathBuf;

use patchflow_dataset::Dataset;
use patchflow_learn::GroundGrid;

/// Half extent of the ground grid, metres (the feature maps' default window).
const HALF_EXTENT_M: f64 = 40.0;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let [_, dataset, sequence] = args.as_slice() else {
        return Err("usage: ground_under_target DATASET SEQUENCE".into());
    };
    let sequence = Dataset::open(&PathBuf::from(dataset))?.sequence(sequence)?;
    for k in 0..sequence.len() {
        let sweep = sequence.read_sweep(k)?;
        let Some(target) = sweep.target() else {
            continue;
        };
        let ground = GroundGrid::estimate(&sweep, HALF_EXTENT_M)?;
        let sensor = sweep.estimated_pose().translation.vector;
        let [x, y, z] = target.centre_m;
        let truth_m = z - target.size_m[2] / 2.0;
        let (sin, cos) = target.yaw_rad.sin_cos();
        // Estimate − truth at `ahead_m` along the target's axis from its centre.
        let error_at =
            |ahead_m: f64| ground.ground_z_m(x + cos * ahead_m, y + sin * ahead_m) - truth_m;
        let half_length_m = target.size_m[0] / 2.0;
        println!(
            "{k:3} {:5.1} m  centre {:+.3}  front {:+.3}  back {:+.3}  2 m ahead {:+.3}",
            (x - sensor.x).hypot(y - sensor.y),
            error_at(0.0),
            error_at(half_length_m),
            error_at(-half_length_m),
            error_at(half_length_m + 2.0)
        );
    }
    Ok(())
}
