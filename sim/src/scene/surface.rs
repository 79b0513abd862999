//! What a collider is to the lidar: its label, reflectivity and box, and the analytic normal of a
//! hit on it (every collider is a cuboid, so the face is found from the hit point alone; this
//! lets the lidar use the cheap `cast_ray` instead of `cast_ray_and_get_normal`).

use patchflow_dataset::SemanticClass;
use rapier3d::math::{Pose, Vector};

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
}

impl Surface {
    /// Outward unit normal of the cuboid face that contains the world point `p` (the collider at `pose`).
    pub fn normal_at(&self, pose: &Pose, p: Vector) -> Vector {
        let local = pose.inverse_transform_point(p);
        let h = self.half_extents_m;
        let ratios = [
            local.x.abs() / h[0],
            local.y.abs() / h[1],
            local.z.abs() / h[2],
        ];
        let axis = if ratios[0] >= ratios[1] && ratios[0] >= ratios[2] {
            0
        } else if ratios[1] >= ratios[2] {
            1
        } else {
            2
        };
        let mut n = Vector::ZERO;
        n[axis] = local[axis].signum();
        pose.transform_vector(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_on_the_side_face_of_a_rotated_box_gets_that_face_normal() {
        let surface = Surface {
            semantic: SemanticClass::Car,
            actor: None,
            half_extents_m: [2.0, 1.0, 0.7],
            reflectivity: 0.5,
        };
        let pose = Pose::new(
            Vector::new(10.0, 0.0, 0.7),
            Vector::new(0.0, 0.0, std::f32::consts::FRAC_PI_2),
        );
        // The box's +y face (local) points along world −x after a 90° yaw.
        let n = surface.normal_at(&pose, Vector::new(9.0, 0.5, 0.9));
        assert!((n - Vector::new(-1.0, 0.0, 0.0)).length() < 1e-5, "{n:?}");
    }
}
