//! KITTI pose lines: a 3 × 4 row-major matrix `[R | t]` written as 12 floats.

use nalgebra::{Matrix3, Rotation3, Translation3, UnitQuaternion};

use crate::Pose;

/// Formats a pose as one KITTI `poses.txt` line (12 floats, row-major 3 × 4, no newline).
pub fn format_kitti_pose(pose: &Pose) -> String {
    let r = pose.rotation.to_rotation_matrix();
    let t = pose.translation.vector;
    let mut fields = Vec::with_capacity(12);
    for row in 0..3 {
        for col in 0..3 {
            fields.push(format!("{:.9e}", r[(row, col)]));
        }
        fields.push(format!("{:.9e}", t[row]));
    }
    fields.join(" ")
}

/// Parses one KITTI pose line; `None` if it is not 12 finite numbers forming a rotation.
pub fn parse_kitti_pose(line: &str) -> Option<Pose> {
    let values: Vec<f64> = line
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .ok()?;
    if values.len() != 12 || values.iter().any(|v| !v.is_finite()) {
        return None;
    }
    if [values[3], values[7], values[11]]
        .iter()
        .any(|t| t.abs() > crate::MAX_COORDINATE_M)
    {
        return None;
    }
    let m = Matrix3::new(
        values[0], values[1], values[2], values[4], values[5], values[6], values[8], values[9],
        values[10],
    );
    // A rotation has orthonormal rows; allow the rounding of 9 significant digits.
    if ((m * m.transpose()) - Matrix3::identity()).abs().max() > 1e-6 {
        return None;
    }
    let rotation = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m));
    Some(Pose::from_parts(
        Translation3::new(values[3], values[7], values[11]),
        rotation,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn pose_line_round_trips_to_nanometres() {
        let pose = Pose::new(
            Vector3::new(12.5, -3.25, 1.73),
            Vector3::new(0.01, -0.02, 2.5),
        );
        let back = parse_kitti_pose(&format_kitti_pose(&pose)).unwrap();
        assert!((back.translation.vector - pose.translation.vector).norm() < 1e-9);
        assert!(back.rotation.angle_to(&pose.rotation) < 1e-8);
    }

    #[test]
    fn a_line_with_eleven_numbers_is_rejected() {
        assert!(parse_kitti_pose("1 0 0 0 0 1 0 0 0 0 1").is_none());
    }

    #[test]
    fn a_non_rotation_matrix_is_rejected() {
        assert!(parse_kitti_pose("2 0 0 0 0 1 0 0 0 0 1 0").is_none());
    }
}
