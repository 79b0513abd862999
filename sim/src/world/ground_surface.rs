//! What the ground of a street world is at a point: its height, the normal of its triangle and
//! its cell's material, read from the height field (the lookups of [`GroundField`], apart from
//! its ray cast).

use super::{GroundField, GroundMaterial};

impl GroundField {
    #[inline]
    pub(super) fn h(&self, i: usize, j: usize) -> f32 {
        self.heights[j * (self.cells[0] + 1) + i]
    }

    /// The cell holding world `(x, y)` and the position inside it in cell units, if on the field.
    #[inline]
    pub(super) fn locate(&self, x: f32, y: f32) -> Option<(usize, usize, f32, f32)> {
        let u = (x - self.origin_m[0] as f32) * self.inverse_cell;
        let v = (y - self.origin_m[1] as f32) * self.inverse_cell;
        if !(u >= 0.0 && v >= 0.0) {
            return None;
        }
        let (i, j) = (
            (u as usize).min(self.cells[0] - 1),
            (v as usize).min(self.cells[1] - 1),
        );
        if u as usize > self.cells[0] || v as usize > self.cells[1] {
            return None;
        }
        Some((i, j, u - i as f32, v - j as f32))
    }

    /// Height of the ground at `(x, y)` (the lower-left corner's height off the field).
    pub(crate) fn height_at(&self, x: f32, y: f32) -> f32 {
        let Some((i, j, u, v)) = self.locate(x, y) else {
            return self.heights[0];
        };
        let (h00, h10, h01, h11) = (
            self.h(i, j),
            self.h(i + 1, j),
            self.h(i, j + 1),
            self.h(i + 1, j + 1),
        );
        if u >= v {
            h00 + (h10 - h00) * u + (h11 - h10) * v
        } else {
            h00 + (h11 - h01) * u + (h01 - h00) * v
        }
    }

    /// Upward unit normal of the ground triangle under `(x, y)`.
    pub(crate) fn normal_at(&self, x: f32, y: f32) -> [f32; 3] {
        self.locate(x, y)
            .map_or([0.0, 0.0, 1.0], |cell| self.normal_in(cell))
    }

    /// Material and reflectivity of the cell under `(x, y)`.
    pub(crate) fn material_at(&self, x: f32, y: f32) -> (GroundMaterial, f32) {
        self.locate(x, y)
            .map_or((GroundMaterial::Grass, 0.45), |cell| self.material_in(cell))
    }

    /// [`GroundField::normal_at`] and [`GroundField::material_at`] together, the point located
    /// once (the lidar asks for both at every ground return).
    #[inline]
    pub(crate) fn surface_at(&self, x: f32, y: f32) -> ([f32; 3], GroundMaterial, f32) {
        match self.locate(x, y) {
            Some(cell) => {
                let (material, reflectivity) = self.material_in(cell);
                (self.normal_in(cell), material, reflectivity)
            }
            None => ([0.0, 0.0, 1.0], GroundMaterial::Grass, 0.45),
        }
    }

    /// Upward unit normal of the triangle at a located point (see [`GroundField::locate`]).
    #[inline]
    fn normal_in(&self, (i, j, u, v): (usize, usize, f32, f32)) -> [f32; 3] {
        let (h00, h10, h01, h11) = (
            self.h(i, j),
            self.h(i + 1, j),
            self.h(i, j + 1),
            self.h(i + 1, j + 1),
        );
        let (gx, gy) = if u >= v {
            (h10 - h00, h11 - h10)
        } else {
            (h11 - h01, h01 - h00)
        };
        let (gx, gy) = (gx * self.inverse_cell, gy * self.inverse_cell);
        let n = (1.0 + gx * gx + gy * gy).sqrt().recip();
        [-gx * n, -gy * n, n]
    }

    /// Material and reflectivity of the cell of a located point.
    #[inline]
    fn material_in(&self, (i, j, _, _): (usize, usize, f32, f32)) -> (GroundMaterial, f32) {
        let (m, r) = self.materials[j * self.cells[0] + i];
        (m, f32::from(r) / 255.0)
    }
}
