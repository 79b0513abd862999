//! Return intensity: surface reflectivity × cosine of the incidence angle (Lambertian) × the
//! atmospheric attenuation exp(−a·r), in [0, 1]. Unlike CARLA's range-only model it separates
//! materials (per-class reflectivity) and shows grazing angles (far road is dark).

/// Intensity of a return from a surface of `reflectivity` hit at `range_m` with `cos_incidence`
/// between the ray and the surface normal.
pub fn intensity(
    reflectivity: f32,
    cos_incidence: f32,
    range_m: f32,
    attenuation_per_m: f32,
) -> f32 {
    (reflectivity * cos_incidence.abs() * (-attenuation_per_m * range_m).exp()).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intensity_falls_with_range_and_incidence_and_rises_with_reflectivity() {
        let base = intensity(0.5, 1.0, 10.0, 0.004);
        assert!(intensity(0.5, 1.0, 50.0, 0.004) < base);
        assert!(intensity(0.5, 0.3, 10.0, 0.004) < base);
        assert!(intensity(0.9, 1.0, 10.0, 0.004) > base);
        assert!((0.0..=1.0).contains(&intensity(1.0, 1.0, 0.0, 0.0)));
    }
}
