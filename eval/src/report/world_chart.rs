//! The drawing vocabulary shared by the scene figures (bird's-eye view and point cloud): a chart
//! in world metres, its drawing area and result types, range rings, actor paths and box
//! footprints.

use plotters::coord::Shift;
use plotters::prelude::*;

/// Range rings around the ego car, metres.
pub(crate) const RINGS_M: [f64; 3] = [10.0, 20.0, 40.0];

pub(crate) type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;
pub(crate) type DrawResult =
    Result<(), DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>>;

/// One actor's path over the sequence.
pub(crate) struct ActorPath {
    /// Whether the actor is the target.
    pub target: bool,
    /// Its centre at every sweep it is in, world x, y.
    pub points: Vec<(f64, f64)>,
}

pub(crate) type WorldChart<'a> = ChartContext<
    'a,
    BitMapBackend<'a>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// Footprint corners of a box, world x, y.
pub(crate) fn footprint(centre: [f64; 3], size: [f64; 3], yaw_rad: f64) -> Vec<(f64, f64)> {
    let (s, c) = yaw_rad.sin_cos();
    let (hl, hw) = (size[0] / 2.0, size[1] / 2.0);
    [(hl, hw), (-hl, hw), (-hl, -hw), (hl, -hw)]
        .iter()
        .map(|(a, b)| (centre[0] + a * c - b * s, centre[1] + a * s + b * c))
        .collect()
}
