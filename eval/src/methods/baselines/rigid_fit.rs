//! Closed-form least-squares rigid alignment of paired 2-D points (thesis eq. 3.38-3.41, Arun et
//! al. 1987), with Umeyama's reflection fix so the rotation always has det = +1.

use nalgebra::{Matrix2, Vector2};

/// Rotation matrix and translation that best map `source[i]` onto `target[i]` in the least-squares
/// sense, solved by SVD of the cross-covariance `Σ = Σᵢ (qᵢ − q̄)(pᵢ − p̄)ᵀ = U D Vᵀ`:
/// `R = U diag(1, sign(det U · det V)) Vᵀ`, `t = q̄ − R p̄`.
///
/// Arun's plain `R = U Vᵀ` can return a reflection (det −1) for noisy or nearly collinear sets,
/// which single-ring clusters often are; the sign term removes it (Umeyama 1991). When the points
/// have no spread at all (Σ = 0) the rotation is the identity and only the centroids are matched.
/// Returns `None` for empty or unequal-length input, or when the SVD fails.
pub fn fit_rigid_svd(
    source: &[[f64; 2]],
    target: &[[f64; 2]],
) -> Option<(Matrix2<f64>, Vector2<f64>)> {
    let (source_mean, target_mean, cross) = centred_cross_covariance(source, target)?;
    let rotation = if cross.norm() < 1e-15 {
        Matrix2::identity()
    } else {
        let svd = cross.svd(true, true);
        let (u, v_t) = (svd.u?, svd.v_t?);
        let reflection_sign = (u.determinant() * v_t.determinant()).signum();
        let s = Matrix2::new(1.0, 0.0, 0.0, reflection_sign);
        u * s * v_t
    };
    let translation = target_mean - rotation * source_mean;
    Some((rotation, translation))
}

/// The same least-squares fit through the 2-D closed form `θ = atan2(Σ pᵢ × qᵢ, Σ pᵢ · qᵢ)` on centred
/// pairs. It needs no SVD and cannot reflect; the tests cross-check [`fit_rigid_svd`] with it.
#[cfg(test)]
pub(crate) fn fit_rigid_closed_form(
    source: &[[f64; 2]],
    target: &[[f64; 2]],
) -> Option<nalgebra::Isometry2<f64>> {
    let (source_mean, target_mean, cross) = centred_cross_covariance(source, target)?;
    // Σ pᵢ · qᵢ = trace(Σ) and Σ pᵢ × qᵢ = Σ₁₀ − Σ₀₁ for Σ = Σ q pᵀ.
    let dot = cross[(0, 0)] + cross[(1, 1)];
    let cross_z = cross[(1, 0)] - cross[(0, 1)];
    let angle = if dot.abs() + cross_z.abs() < 1e-15 {
        0.0
    } else {
        cross_z.atan2(dot)
    };
    let rotation = nalgebra::Rotation2::new(angle);
    let translation = target_mean - rotation * source_mean;
    Some(nalgebra::Isometry2::new(translation, angle))
}

/// Means of both sets and the cross-covariance `Σᵢ (qᵢ − q̄)(pᵢ − p̄)ᵀ` (unnormalised).
fn centred_cross_covariance(
    source: &[[f64; 2]],
    target: &[[f64; 2]],
) -> Option<(Vector2<f64>, Vector2<f64>, Matrix2<f64>)> {
    if source.is_empty() || source.len() != target.len() {
        return None;
    }
    let n = source.len() as f64;
    let mean = |points: &[[f64; 2]]| {
        points
            .iter()
            .fold(Vector2::zeros(), |acc, p| acc + Vector2::new(p[0], p[1]))
            / n
    };
    let (source_mean, target_mean) = (mean(source), mean(target));
    let cross = source
        .iter()
        .zip(target)
        .fold(Matrix2::zeros(), |acc, (p, q)| {
            let p = Vector2::new(p[0], p[1]) - source_mean;
            let q = Vector2::new(q[0], q[1]) - target_mean;
            acc + q * p.transpose()
        });
    Some((source_mean, target_mean, cross))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn transform(points: &[[f64; 2]], angle: f64, t: [f64; 2]) -> Vec<[f64; 2]> {
        let (s, c) = angle.sin_cos();
        points
            .iter()
            .map(|p| [c * p[0] - s * p[1] + t[0], s * p[0] + c * p[1] + t[1]])
            .collect()
    }

    fn random_points(rng: &mut ChaCha8Rng, n: usize) -> Vec<[f64; 2]> {
        (0..n)
            .map(|_| [rng.random_range(-3.0..3.0), rng.random_range(-1.0..1.0)])
            .collect()
    }

    #[test]
    fn svd_and_closed_form_recover_a_known_motion_to_1e9() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for _ in 0..20 {
            let source = random_points(&mut rng, 30);
            let angle = rng.random_range(-3.0..3.0);
            let t = [rng.random_range(-20.0..20.0), rng.random_range(-20.0..20.0)];
            let target = transform(&source, angle, t);
            let (r, tr) = fit_rigid_svd(&source, &target).unwrap();
            let iso = fit_rigid_closed_form(&source, &target).unwrap();
            let svd_angle = r[(1, 0)].atan2(r[(0, 0)]);
            let wrap = patchflow_dataset::wrap_angle_rad;
            assert!(wrap(svd_angle - angle).abs() < 1e-9);
            assert!(wrap(iso.rotation.angle() - angle).abs() < 1e-9);
            assert!((tr.x - t[0]).abs() < 1e-9 && (tr.y - t[1]).abs() < 1e-9);
            assert!((iso.translation.vector.x - t[0]).abs() < 1e-9);
        }
    }

    #[test]
    fn the_reflection_fix_keeps_det_plus_one_for_mirrored_noisy_points() {
        // The target is the source mirrored in the x axis: plain U Vᵀ would be a reflection.
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let source = random_points(&mut rng, 25);
        let target: Vec<[f64; 2]> = source
            .iter()
            .map(|p| [p[0] + rng.random_range(-0.05..0.05), -p[1]])
            .collect();
        let (r, _) = fit_rigid_svd(&source, &target).unwrap();
        assert!((r.determinant() - 1.0).abs() < 1e-12);
        // And the SVD route agrees with the reflection-free closed form.
        let iso = fit_rigid_closed_form(&source, &target).unwrap();
        let svd_angle = r[(1, 0)].atan2(r[(0, 0)]);
        assert!((svd_angle - iso.rotation.angle()).abs() < 1e-9);
    }

    #[test]
    fn collinear_points_are_aligned_without_reflection() {
        let source: Vec<[f64; 2]> = (0..10).map(|i| [i as f64 * 0.3, 0.0]).collect();
        let target = transform(&source, 0.4, [2.0, 1.0]);
        let (r, t) = fit_rigid_svd(&source, &target).unwrap();
        assert!((r.determinant() - 1.0).abs() < 1e-12);
        assert!((r[(1, 0)].atan2(r[(0, 0)]) - 0.4).abs() < 1e-9);
        assert!((t.x - 2.0).abs() < 1e-9 && (t.y - 1.0).abs() < 1e-9);
    }

    #[test]
    fn coincident_points_give_a_pure_translation() {
        let source = vec![[1.0, 1.0]; 4];
        let target = vec![[3.0, 0.0]; 4];
        let (r, t) = fit_rigid_svd(&source, &target).unwrap();
        assert_eq!(r, Matrix2::identity());
        assert!((t.x - 2.0).abs() < 1e-12 && (t.y + 1.0).abs() < 1e-12);
    }

    #[test]
    fn empty_or_unequal_input_gives_none() {
        assert!(fit_rigid_svd(&[], &[]).is_none());
        assert!(fit_rigid_closed_form(&[[0.0, 0.0]], &[]).is_none());
    }
}
