//! A motion map's fields sampled on a regular lattice and read back by bilinear interpolation: the
//! flow lines of the motion-adapted kernel ask for the velocity at every Runge-Kutta stage of
//! every point, far too often to ask the regressors each time. Outside the lattice the nearest
//! edge value holds (the lattice covers what the training run observed, plus a margin where the
//! regressors have already returned to their prior).

use serde::{Deserialize, Serialize};

/// Values of several fields on a lattice of `size[0]` × `size[1]` nodes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FieldRaster {
    /// World position of node (0, 0), metres.
    pub origin_m: [f64; 2],
    /// Distance between neighbouring nodes, metres.
    pub step_m: f64,
    /// Nodes along x and along y.
    pub size: [usize; 2],
    /// Per field, the node values row by row from the lowest y.
    pub values: Vec<Vec<f64>>,
}

impl FieldRaster {
    /// The node positions of a lattice from `lo_m` to at least `hi_m` with spacing `step_m`, row
    /// by row; and the empty raster they belong to.
    pub fn lattice(lo_m: [f64; 2], hi_m: [f64; 2], step_m: f64) -> (Self, Vec<[f64; 2]>) {
        let count = |a: f64, b: f64| ((b - a) / step_m).ceil().max(0.0) as usize + 1;
        let size = [count(lo_m[0], hi_m[0]), count(lo_m[1], hi_m[1])];
        let nodes = (0..size[1])
            .flat_map(|r| {
                (0..size[0])
                    .map(move |c| [lo_m[0] + c as f64 * step_m, lo_m[1] + r as f64 * step_m])
            })
            .collect();
        let raster = Self {
            origin_m: lo_m,
            step_m,
            size,
            values: Vec::new(),
        };
        (raster, nodes)
    }

    /// Node positions, row by row.
    pub fn nodes(&self) -> Vec<[f64; 2]> {
        Self::lattice(
            self.origin_m,
            [
                self.origin_m[0] + (self.size[0] - 1) as f64 * self.step_m,
                self.origin_m[1] + (self.size[1] - 1) as f64 * self.step_m,
            ],
            self.step_m,
        )
        .1
    }

    /// Field `field` at `xy_m`, bilinear between the four surrounding nodes.
    pub fn at(&self, field: usize, xy_m: [f64; 2]) -> f64 {
        let values = &self.values[field];
        let cell = |axis: usize| -> (usize, f64) {
            let n = self.size[axis];
            let f = ((xy_m[axis] - self.origin_m[axis]) / self.step_m).clamp(0.0, (n - 1) as f64);
            let i = (f.floor() as usize).min(n.saturating_sub(2));
            (i, f - i as f64)
        };
        let ((i, fx), (j, fy)) = (cell(0), cell(1));
        let w = self.size[0];
        let v = |c: usize, r: usize| {
            let (c, r) = (c.min(w - 1), r.min(self.size[1] - 1));
            values[r * w + c]
        };
        let bottom = v(i, j) * (1.0 - fx) + v(i + 1, j) * fx;
        let top = v(i, j + 1) * (1.0 - fx) + v(i + 1, j + 1) * fx;
        bottom * (1.0 - fy) + top * fy
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_field_is_read_back_exactly_inside_and_held_at_the_edge_outside() {
        let (mut raster, nodes) = FieldRaster::lattice([-2.0, 1.0], [3.0, 4.0], 0.5);
        assert_eq!(raster.size, [11, 7]);
        raster.values = vec![nodes.iter().map(|p| 2.0 * p[0] - p[1] + 0.5).collect()];
        for p in [[0.3, 2.2], [-2.0, 1.0], [2.99, 3.7], [1.25, 1.75]] {
            assert!(
                (raster.at(0, p) - (2.0 * p[0] - p[1] + 0.5)).abs() < 1e-12,
                "{p:?}"
            );
        }
        assert!((raster.at(0, [10.0, 2.0]) - (6.0 - 2.0 + 0.5)).abs() < 1e-12);
        assert_eq!(raster.nodes(), nodes);
    }
}
