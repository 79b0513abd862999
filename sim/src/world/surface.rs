//! What a collider is to the lidar: its label, reflectivity, material, shape kind and current
//! placement, and the analytic normal of a hit on it. A cuboid yawed about z (every collider of
//! the `ideal` world) finds its face from the hit point alone, so the lidar uses the cheap
//! `cast_ray` instead of `cast_ray_and_get_normal` and never touches the (large, cache-cold)
//! Rapier collider per point; the ground reads its normal and material from its height field,
//! and other shapes ask parry for the normal of the one part that was hit.

use patchflow_dataset::SemanticClass;
use rapier3d::math::Vector;

/// How the lidar finds the normal of a hit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceKind {
    /// A cuboid yawed about z: the analytic face normal.
    Box,
    /// The street world's ground: normal and material from its height field.
    Ground,
    /// Any other shape: the normal parry reports for the hit part.
    Shape,
}

/// Which faces of a surface are glass (fewer returns, some rays pass through).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Glass {
    /// No glass.
    None,
    /// Every face.
    All,
    /// Faces steeper than 45° (a car cabin: windows all round, a painted roof).
    Sides,
    /// Where the shape reports a glass feature (a building's recessed windows).
    Windows,
}

/// How a surface treats the beam beyond its reflectivity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Glass faces.
    pub glass: Glass,
    /// Mean free path of a beam inside a porous volume (foliage), metres; 0 for a solid.
    pub porous_m: f32,
}

impl Material {
    /// An opaque, solid surface.
    pub const SOLID: Self = Self {
        glass: Glass::None,
        porous_m: 0.0,
    };
    /// Glass on every face.
    pub const GLASS: Self = Self {
        glass: Glass::All,
        porous_m: 0.0,
    };
    /// A car cabin: glass sides, painted roof.
    pub const CABIN: Self = Self {
        glass: Glass::Sides,
        porous_m: 0.0,
    };

    /// A building: glass in its window openings.
    pub const WINDOWS: Self = Self {
        glass: Glass::Windows,
        porous_m: 0.0,
    };

    /// Foliage with the given mean free path.
    pub const fn foliage(porous_m: f32) -> Self {
        Self {
            glass: Glass::None,
            porous_m,
        }
    }
}

/// Lidar-relevant facts of one collider; `Collider::user_data` indexes a table of these.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surface {
    /// Label of static surfaces (actors are labelled from their class and motion instead).
    pub semantic: SemanticClass,
    /// Index of the actor this collider belongs to, if it is one.
    pub actor: Option<usize>,
    /// Half extents of the cuboid, metres.
    pub half_extents_m: [f32; 3],
    /// Reflectivity in [0, 1].
    pub reflectivity: f32,
    /// How the lidar finds a hit's normal.
    pub kind: SurfaceKind,
    /// Glass and foliage.
    pub material: Material,
    /// Index of this collider among the scene's moving colliders, if it moves.
    pub mover: Option<u32>,
    /// Box centre, world frame, metres (kept equal to the collider's pose by the scene).
    centre_m: Vector,
    /// Cosine and sine of the box yaw about z.
    yaw_cos_sin: (f32, f32),
    /// 1 / half extents, so the face test multiplies instead of divides.
    inverse_half_extents: [f32; 3],
}

impl Surface {
    /// A box surface with its centre at the origin and no yaw; place it with [`Surface::place`].
    pub fn new(
        semantic: SemanticClass,
        actor: Option<usize>,
        half_extents_m: [f32; 3],
        reflectivity: f32,
    ) -> Self {
        Self {
            semantic,
            actor,
            half_extents_m,
            reflectivity,
            kind: SurfaceKind::Box,
            material: Material::SOLID,
            mover: None,
            centre_m: Vector::ZERO,
            yaw_cos_sin: (1.0, 0.0),
            inverse_half_extents: half_extents_m.map(|h| 1.0 / h),
        }
    }

    /// The same surface with another kind and material.
    pub fn with(mut self, kind: SurfaceKind, material: Material) -> Self {
        self.kind = kind;
        self.material = material;
        self
    }

    /// Moves the box to `centre_m` with yaw `yaw_rad` about z (the pose of its collider).
    pub fn place(&mut self, centre_m: Vector, yaw_rad: f32) {
        self.centre_m = centre_m;
        let (s, c) = yaw_rad.sin_cos();
        self.yaw_cos_sin = (c, s);
    }

    /// Outward unit normal, world frame, of the box face that contains the world point `p`.
    pub fn normal_at(&self, p: Vector) -> Vector {
        let (axis, sign) = self.face_of(p);
        let (c, s) = self.yaw_cos_sin;
        match axis {
            0 => Vector::new(sign * c, sign * s, 0.0),
            1 => Vector::new(-sign * s, sign * c, 0.0),
            _ => Vector::new(0.0, 0.0, sign),
        }
    }

    /// |cos| of the angle between the world direction `dir` (unit) and the face containing `p`
    /// (the face of [`Surface::normal_at`], chosen without branches: the lidar calls this for
    /// every return, and which face a ray meets is hard to predict).
    #[inline]
    pub fn cos_incidence(&self, p: Vector, dir: Vector) -> f32 {
        let (c, s) = self.yaw_cos_sin;
        let d = p - self.centre_m;
        let k = self.inverse_half_extents;
        let ratio_x = (c * d.x + s * d.y).abs() * k[0];
        let ratio_y = (c * d.y - s * d.x).abs() * k[1];
        let ratio_z = d.z.abs() * k[2];
        let cos_x = (c * dir.x + s * dir.y).abs();
        let cos_y = (c * dir.y - s * dir.x).abs();
        // Ties go to the lower axis, as in `face_of`.
        let (ratio_xy, cos_xy) = if ratio_x >= ratio_y {
            (ratio_x, cos_x)
        } else {
            (ratio_y, cos_y)
        };
        if ratio_xy >= ratio_z {
            cos_xy
        } else {
            dir.z.abs()
        }
    }

    /// The face containing `p`: the local axis whose |coordinate| / half extent is largest, and
    /// the sign of that coordinate.
    fn face_of(&self, p: Vector) -> (usize, f32) {
        let (c, s) = self.yaw_cos_sin;
        let d = p - self.centre_m;
        let local = [c * d.x + s * d.y, c * d.y - s * d.x, d.z];
        let k = self.inverse_half_extents;
        let ratios = [
            local[0].abs() * k[0],
            local[1].abs() * k[1],
            local[2].abs() * k[2],
        ];
        let axis = if ratios[0] >= ratios[1] && ratios[0] >= ratios[2] {
            0
        } else if ratios[1] >= ratios[2] {
            1
        } else {
            2
        };
        (axis, local[axis].signum())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rotated_car() -> Surface {
        let mut surface = Surface::new(SemanticClass::Car, None, [2.0, 1.0, 0.7], 0.5);
        surface.place(Vector::new(10.0, 0.0, 0.7), std::f32::consts::FRAC_PI_2);
        surface
    }

    #[test]
    fn a_point_on_the_side_face_of_a_rotated_box_gets_that_face_normal() {
        // The box's +y face (local) points along world −x after a 90° yaw.
        let n = rotated_car().normal_at(Vector::new(9.0, 0.5, 0.9));
        assert!((n - Vector::new(-1.0, 0.0, 0.0)).length() < 1e-5, "{n:?}");
    }

    #[test]
    fn a_point_on_the_roof_gets_the_up_normal() {
        let n = rotated_car().normal_at(Vector::new(10.3, 1.2, 1.4));
        assert!((n - Vector::new(0.0, 0.0, 1.0)).length() < 1e-6, "{n:?}");
    }

    #[test]
    fn the_incidence_cosine_is_the_absolute_dot_product_with_the_face_normal() {
        let surface = rotated_car();
        let p = Vector::new(9.0, 0.5, 0.9);
        let dir = Vector::new(0.6, 0.0, -0.8);
        let expected = dir.dot(surface.normal_at(p)).abs();
        assert!((surface.cos_incidence(p, dir) - expected).abs() < 1e-6);
        assert!((expected - 0.6).abs() < 1e-5);
    }

    #[test]
    fn the_incidence_cosine_uses_the_face_of_the_normal_on_every_face_and_edge() {
        let surface = rotated_car();
        let dir = Vector::new(0.48, -0.6, -0.64);
        // Points on each face, on edges and corners (ties), of the box (centre 10, 0, 0.7;
        // local x along world y, local y along world −x after the 90° yaw).
        for local in [
            [2.0, 0.3, 0.1],
            [-2.0, -0.5, 0.2],
            [0.4, 1.0, -0.3],
            [1.1, -1.0, 0.6],
            [0.5, 0.2, 0.7],
            [-1.5, 0.9, -0.7],
            [2.0, 1.0, 0.2],
            [2.0, 0.5, 0.7],
            [-2.0, -1.0, -0.7],
        ] {
            let p = Vector::new(10.0 - local[1], local[0], 0.7 + local[2]);
            let expected = dir.dot(surface.normal_at(p)).abs();
            assert!(
                (surface.cos_incidence(p, dir) - expected).abs() < 1e-6,
                "{local:?}"
            );
        }
    }
}
