//! The ground under one sweep, estimated from the sweep alone: a world-frame height field on
//! 1 m cells over the map window, queried as [`GroundGrid::ground_z_m`]. The thesis measures its
//! height slice from a flat road (2.1.1) and names ground extraction as future work (6); roads
//! with camber, grade changes and curbs, terrain beyond them and a drifting pose estimate move the
//! local ground tens of centimetres to metres away from z = 0. Beyond 20 m, where the road returns
//! little at grazing incidence, the estimate is held near the near ground extended, so the tops
//! of parked cars cannot pass for ground there.

use patchflow_dataset::Sweep;
use rayon::prelude::*;

use crate::features::grid::GridWindow;
use crate::features::ground_cells::{CellLows, band_moments};
use crate::features::ground_envelope::ground_cells;
use crate::features::ground_fit::MomentTable;
use crate::features::ground_pits::lift_pits;
use crate::{LearnError, Result};

/// A ground height per 1 m cell, bilinear between cell centres.
///
/// ```
/// use patchflow_learn::GroundGrid;
/// use patchflow_learn::synthetic::{SyntheticGround, SyntheticLidar, SyntheticWorld};
/// let world = SyntheticWorld {
///     ground: SyntheticGround { base_m: 1.0, grade: [0.04, 0.0], ..SyntheticGround::default() },
///     ..SyntheticWorld::default()
/// };
/// let sweep = world.scan(&SyntheticLidar::with_resolution(32, 720), [0.0, 0.0], 0.0, 0);
/// let ground = GroundGrid::estimate(&sweep, 20.0).unwrap();
/// assert!((ground.ground_z_m(10.0, 3.0) - 1.4).abs() < 0.03);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct GroundGrid {
    window: GridWindow,
    heights_m: Vec<f64>,
    /// Bound on |∇ ground| over the grid (the steepest step between neighbouring centres).
    max_gradient: f64,
    /// The lattice of cell centres the queries interpolate on.
    centres: CentreLattice,
}

/// Cell-centre heights with the last column and row repeated once more, so a bilinear query
/// needs no edge cases (the slice asks a few hundred thousand per sweep).
#[derive(Debug, Clone, PartialEq)]
struct CentreLattice {
    padded_m: Vec<f64>,
    stride: usize,
    inv_cell: f64,
    /// Lattice coordinate of world x = 0 (y = 0), negated.
    offset: [f64; 2],
    /// Largest lattice coordinate (the outermost centre) per axis.
    last: [f64; 2],
}

impl CentreLattice {
    fn new(heights_m: &[f64], window: &GridWindow) -> Self {
        let (cols, rows) = (window.cols, window.rows);
        let stride = cols + 1;
        let mut padded_m = Vec::with_capacity(stride * (rows + 1));
        for r in (0..rows).chain([rows - 1]) {
            let row = &heights_m[r * cols..(r + 1) * cols];
            padded_m.extend_from_slice(row);
            padded_m.push(row[cols - 1]);
        }
        Self {
            padded_m,
            stride,
            inv_cell: 1.0 / window.cell_m,
            offset: [
                window.origin_col as f64 + 0.5,
                window.origin_row as f64 + 0.5,
            ],
            last: [(cols - 1) as f64, (rows - 1) as f64],
        }
    }

    /// Bilinear between centres, held beyond the outermost ones.
    fn at(&self, x_m: f64, y_m: f64) -> f64 {
        let u = (x_m * self.inv_cell - self.offset[0]).clamp(0.0, self.last[0]);
        let v = (y_m * self.inv_cell - self.offset[1]).clamp(0.0, self.last[1]);
        let (c, r) = (u as usize, v as usize);
        let (tu, tv) = (u - c as f64, v - r as f64);
        let s = self.stride;
        let h = &self.padded_m[r * s + c..r * s + c + s + 2];
        let below = h[0] + (h[1] - h[0]) * tu;
        let above = h[s] + (h[s + 1] - h[s]) * tu;
        below + (above - below) * tv
    }
}

impl GroundGrid {
    /// Side of a ground cell, metres: fine enough for curbs and camber near the sensor, coarse
    /// enough that most cells within 20 m hold a ground return.
    pub const CELL_M: f64 = 1.0;
    /// Extra margin around the requested half extent, metres: the previous sweep's slice is
    /// traced onto the current sweep's window, up to a couple of metres away.
    pub const MARGIN_M: f64 = 4.0;

    /// Estimates the ground within `half_extent_m` (plus [`Self::MARGIN_M`]) of the sweep's
    /// sensor from its points (sensor frame) and the ego's estimated pose. A non-finite point is
    /// an error.
    pub fn estimate(sweep: &Sweep, half_extent_m: f64) -> Result<Self> {
        let points = points_in_world(sweep)?;
        let sensor = sweep.estimated_pose().translation.vector;
        Ok(Self::from_points_in_world(
            &points,
            [sensor.x, sensor.y],
            half_extent_m,
        ))
    }

    /// The ground under world points, on a window centred on `centre_xy`.
    pub(crate) fn from_points_in_world(
        points_in_world: &[[f64; 3]],
        centre_xy: [f64; 2],
        half_extent_m: f64,
    ) -> Self {
        let window = GridWindow::centred(centre_xy, half_extent_m + Self::MARGIN_M, Self::CELL_M);
        // The lowest robust return of every cell, not deep below its neighbourhood.
        let mut lows = CellLows::bin(points_in_world, &window);
        lift_pits(points_in_world, &window, &mut lows);
        // Slope-based filter: cells standing above their surroundings are objects, not ground.
        let ground = ground_cells(&lows.low_m, &window);
        // The ground band of every ground cell, as moments.
        let moments = band_moments(points_in_world, &window, &lows, &ground);
        // A plane at every cell centre through the nearest ground that pins one down: smooths,
        // and fills the holes under objects and between rings. Without any ground, z = 0.
        let mut heights_m = MomentTable::new(&moments, &window).fit_heights(&window, 0.0);
        // Far from the sensor, where the road returns little, object tops must not pass for ground.
        hold_far_ground_to_near_ground(&mut heights_m, &window, centre_xy);
        let max_gradient = max_gradient(&heights_m, &window);
        let centres = CentreLattice::new(&heights_m, &window);
        Self {
            window,
            heights_m,
            max_gradient,
            centres,
        }
    }

    /// Ground height at world `(x, y)`, metres: bilinear between cell centres, held constant
    /// beyond the outermost centres.
    pub fn ground_z_m(&self, x_m: f64, y_m: f64) -> f64 {
        self.centres.at(x_m, y_m)
    }

    /// The window of ground cells.
    pub fn window(&self) -> &GridWindow {
        &self.window
    }

    /// Ground height at every cell centre, row-major.
    pub fn heights_m(&self) -> &[f64] {
        &self.heights_m
    }

    /// A bound on the ground's slope anywhere on the grid (rise per metre).
    pub fn max_gradient(&self) -> f64 {
        self.max_gradient
    }
}

/// Every point of the sweep in the world frame as the ego places it, with its estimated pose
/// ([`Sweep::estimated_pose`], the truth where the dataset has no estimate); a non-finite point
/// is an error.
pub(crate) fn points_in_world(sweep: &Sweep) -> Result<Vec<[f64; 3]>> {
    let finite = |p: &[f32; 3]| p.iter().all(|v| v.is_finite());
    if let Some(index) = sweep.points_in_sensor.iter().position(|p| !finite(p)) {
        return Err(LearnError::degenerate_data(format!(
            "sweep {}: point {index} is not finite",
            sweep.index
        )));
    }
    let world_from_sensor = sweep.estimated_pose();
    let origin = world_from_sensor.translation.vector;
    let rotation = world_from_sensor.rotation.to_rotation_matrix();
    // Each point on its own: in parallel tasks, in point order.
    Ok(sweep
        .points_in_sensor
        .par_iter()
        .with_min_len(TASK_POINTS)
        .map(|p| {
            let end = rotation
                * nalgebra::Vector3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
                + origin;
            [end.x, end.y, end.z]
        })
        .collect())
}

/// Least points of a parallel task that moves points into the world frame.
const TASK_POINTS: usize = 8192;

/// Radius of the near ground, metres: where the road still returns densely (beyond about 20 m a
/// real HDL-64E, and the `urban` rung, lose most road returns at grazing incidence).
const NEAR_M: f64 = 20.0;
/// How far above the near ground, extended, a far cell's estimate may stand before it is taken
/// for object tops rather than ground: a curb and the camber across the street.
const ABOVE_NEAR_GROUND_M: f64 = 0.15;
/// Length over which the near ground's slope outward is read, metres: from 8 m out, where the
/// rings lie close, to the rim.
const SLOPE_BASE_M: f64 = 12.0;

/// Beyond [`NEAR_M`] from `centre_xy`, replaces every height standing more than
/// [`ABOVE_NEAR_GROUND_M`] above the near ground extended by that extension, which follows
/// the line from the sensor outward with the estimate's height at the near zone's rim and its
/// slope over the last [`SLOPE_BASE_M`] before it.
///
/// Where the far road returns nothing, the slope filter's cones reach from ground metres away,
/// and the roofs, hoods and sills of parked cars seen over nearer traffic (one ring per cell, no
/// face below it) pass as ground; on `urban` the estimate under targets 30-45 m away stood
/// 0.2-1.5 m high, the height slice with it, and the targets' motion was misread there (docs/ground.md,
/// "The ground under far targets"). With no far ground to go by, the near road extended is the
/// best guess; a far estimate within a curb of it is kept, so seen ground that rises gently
/// (grade changes, terrain) keeps its own.
fn hold_far_ground_to_near_ground(heights_m: &mut [f64], window: &GridWindow, centre_xy: [f64; 2]) {
    let estimate = CentreLattice::new(heights_m, window);
    let along = |[dx, dy]: [f64; 2], range: f64, at_m: f64| {
        estimate.at(
            centre_xy[0] + dx * at_m / range,
            centre_xy[1] + dy * at_m / range,
        )
    };
    for (k, h) in heights_m.iter_mut().enumerate() {
        let centre = [
            ((window.origin_col + (k % window.cols) as i64) as f64 + 0.5) * window.cell_m,
            ((window.origin_row + (k / window.cols) as i64) as f64 + 0.5) * window.cell_m,
        ];
        let d = [centre[0] - centre_xy[0], centre[1] - centre_xy[1]];
        let range = d[0].hypot(d[1]);
        if range <= NEAR_M {
            continue;
        }
        let rim = along(d, range, NEAR_M);
        let slope = (rim - along(d, range, NEAR_M - SLOPE_BASE_M)) / SLOPE_BASE_M;
        let extended = rim + slope * (range - NEAR_M);
        if *h > extended + ABOVE_NEAR_GROUND_M {
            *h = extended;
        }
    }
}

/// The largest |∇| of the bilinear field: per axis the steepest step between neighbouring
/// centres, combined.
fn max_gradient(heights_m: &[f64], window: &GridWindow) -> f64 {
    let (cols, rows) = (window.cols, window.rows);
    let (mut gx, mut gy) = (0.0f64, 0.0f64);
    for r in 0..rows {
        for c in 0..cols {
            let h = heights_m[r * cols + c];
            if c + 1 < cols {
                gx = gx.max((heights_m[r * cols + c + 1] - h).abs());
            }
            if r + 1 < rows {
                gy = gy.max((heights_m[(r + 1) * cols + c] - h).abs());
            }
        }
    }
    gx.hypot(gy) / window.cell_m
}

#[cfg(test)]
#[path = "ground_grid_tests.rs"]
mod tests;
