//! Mirror images of training samples: the reflection symmetry of the lidar and the maps, used to
//! balance a training set that right-hand traffic leaves lopsided.
//!
//! Reflect the world across the line sensor → point: the scan pattern, the height slice, the
//! maps and the patch grid are all symmetric under it, so a car moving at heading `bearing + φ`
//! turns into one moving at `bearing − φ`, and its heading patch into the same patch with its
//! rows (the across-axis index) reversed. The heading targets map as sin φ → −sin φ, cos φ → cos φ.
//! The speed patch is aligned to the heading; reflecting across that axis keeps the speed. The
//! Gabor bank reflects into itself: filter θ_k becomes θ_{−k}, so Gabor features are permuted.
//!
//! Why: traffic drives on one side, so most cars a training run sees pass on one side and cross
//! in one sense (in our nine tracks 70 % of the samples have sin φ > 0). A GP trained on that
//! learns the side as a prior and gets a crossing from the other side wrong. The rolling shutter
//! spins one way and is not mirrored; its smear is a few centimetres, under a 10 cm cell.

use crate::features::feature_kind::FeatureKind;
use crate::features::gabor::GABOR_FILTERS;
use crate::features::patch::{PATCH_CELLS, PATCH_LEN, PATCH_SIDE, Patch};
use crate::features::sample_set::SampleSet;
use crate::features::training_sample::TrainingSample;

impl Patch {
    /// The patch reflected across its reference axis: row `r` becomes row `10 − r` in both halves.
    pub fn mirrored(&self) -> Patch {
        let mut values = [0.0; PATCH_LEN];
        for half in [0, PATCH_CELLS] {
            for r in 0..PATCH_SIDE {
                let (to, from) = (
                    half + r * PATCH_SIDE,
                    half + (PATCH_SIDE - 1 - r) * PATCH_SIDE,
                );
                values[to..to + PATCH_SIDE].copy_from_slice(&self.values[from..from + PATCH_SIDE]);
            }
        }
        Patch { values }
    }
}

impl FeatureKind {
    /// The features of the mirrored patch, computed from the features of the patch: patch
    /// values with their rows reversed, or Gabor responses with filter `k` swapped for `16 − k`.
    /// A vector of the wrong length is returned unchanged (training rejects it with an error).
    pub fn mirror(self, features: &[f64]) -> Vec<f64> {
        match self {
            Self::Patch => match <&[f64; PATCH_LEN]>::try_from(features) {
                Ok(values) => Patch { values: *values }.mirrored().values.to_vec(),
                Err(_) => features.to_vec(),
            },
            Self::Gabor if features.len() == GABOR_FILTERS => (0..GABOR_FILTERS)
                .map(|k| features[(GABOR_FILTERS - k) % GABOR_FILTERS])
                .collect(),
            Self::Gabor => features.to_vec(),
        }
    }
}

impl TrainingSample {
    /// This sample in the world reflected across its line of sight (see the module docs).
    pub fn mirror_image(&self, kind: FeatureKind) -> TrainingSample {
        TrainingSample {
            sin_rel: -self.sin_rel,
            heading_rad: 2.0 * self.bearing_rad - self.heading_rad,
            heading_features: kind.mirror(&self.heading_features),
            speed_features: kind.mirror(&self.speed_features),
            ..self.clone()
        }
    }
}

impl SampleSet {
    /// The mirror image of every sample, in the same order.
    pub fn mirror_images(&self) -> SampleSet {
        SampleSet {
            samples: self
                .samples
                .iter()
                .map(|s| s.mirror_image(self.kind))
                .collect(),
            ..self.clone()
        }
    }

    /// The samples followed by their mirror images (`2 n` samples).
    pub fn with_mirror_images(&self) -> SampleSet {
        let mut set = self.clone();
        set.samples.extend(self.mirror_images().samples);
        set
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::features::gabor::GaborBank;
    use crate::features::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
    use crate::{FeatureParams, SweepFeatures};

    fn numbered_patch() -> Patch {
        let mut values = [0.0; PATCH_LEN];
        for (k, v) in values.iter_mut().enumerate() {
            *v = (k as f64 * 0.37).sin();
        }
        Patch { values }
    }

    #[test]
    fn mirroring_a_patch_twice_gives_it_back() {
        let p = numbered_patch();
        assert_eq!(p.mirrored().mirrored(), p);
        assert_ne!(p.mirrored(), p);
    }

    #[test]
    fn a_mirrored_patch_swaps_the_rows_left_and_right_of_the_axis() {
        let p = numbered_patch();
        let m = p.mirrored();
        // Row 0 (right of the axis) of the mirror is row 10 (left) of the patch; row 5 stays.
        assert_eq!(m.values[3], p.values[10 * PATCH_SIDE + 3]);
        assert_eq!(m.values[5 * PATCH_SIDE + 7], p.values[5 * PATCH_SIDE + 7]);
        assert_eq!(
            m.values[PATCH_CELLS + 2],
            p.values[PATCH_CELLS + 10 * PATCH_SIDE + 2]
        );
    }

    #[test]
    fn gabor_responses_of_a_mirrored_patch_are_the_permuted_responses() {
        let params = FeatureParams::default();
        let bank = GaborBank::new(&params.gabor, params.cell_m);
        let p = numbered_patch();
        let direct = bank.responses(&p.mirrored());
        let permuted = FeatureKind::Gabor.mirror(&bank.responses(&p));
        for (a, b) in direct.iter().zip(&permuted) {
            assert!((a - b).abs() < 1e-9, "{a} vs {b}");
        }
    }

    #[test]
    fn the_mirror_of_a_car_patch_matches_the_patch_of_the_mirrored_car() {
        // A car 14 m ahead heading 1.2 rad and the same car heading −1.2 rad: the reflection
        // across the x axis (the line of sight, sensor at the origin) maps one scene onto the other.
        let lidar = SyntheticLidar::with_resolution(64, 3600);
        let params = FeatureParams::default();
        let patch_of = |y_sign: f64| {
            let car = SceneBox::car(1, [14.0, 0.0], y_sign * 1.2, 6.0);
            let scene = SyntheticScene { boxes: vec![car] };
            let prev = scene.scan(&lidar, [0.0, 0.0], 0.0, 0);
            let curr = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
            let f = SweepFeatures::compute(&prev, &curr, &params).unwrap();
            // The point nearest the car's centre line seen from the sensor.
            let i = (0..f.len())
                .min_by(|&a, &b| {
                    let ya = f.points()[a].y_m.abs();
                    let yb = f.points()[b].y_m.abs();
                    ya.total_cmp(&yb)
                })
                .unwrap();
            let p = f.points()[i];
            let along = f.patch_along(i, 0.0);
            (along, [p.x_m, p.y_m])
        };
        let (left, at_left) = patch_of(1.0);
        let (right, at_right) = patch_of(-1.0);
        assert!((at_left[0] - at_right[0]).abs() < 0.05 && (at_left[1] + at_right[1]).abs() < 0.05);
        let mean_abs_diff = |a: &Patch, b: &Patch| {
            a.values
                .iter()
                .zip(&b.values)
                .map(|(x, y)| (x - y).abs())
                .sum::<f64>()
                / PATCH_LEN as f64
        };
        let mirrored = mean_abs_diff(&left.mirrored(), &right);
        let unmirrored = mean_abs_diff(&left, &right);
        let scale = left.values.iter().map(|v| v.abs()).sum::<f64>() / PATCH_LEN as f64;
        assert!(scale > 0.05, "the patch shows the car ({scale})");
        assert!(
            mirrored < 0.1 * scale,
            "mean |mirror − patch| {mirrored}, mean |patch| {scale}"
        );
        assert!(
            unmirrored > 5.0 * mirrored,
            "{unmirrored} vs {mirrored}: the cars differ"
        );
    }

    #[test]
    fn a_mirror_image_flips_the_sine_target_and_keeps_the_rest() {
        let s = TrainingSample {
            sequence: "t".into(),
            scan: 3,
            point: 9,
            actor: 2,
            weight: 0.4,
            bearing_rad: 0.3,
            sin_rel: 0.6,
            cos_rel: 0.8,
            heading_rad: 0.3 + 0.6f64.atan2(0.8),
            speed_mps: 5.0,
            heading_features: numbered_patch().values.to_vec(),
            speed_features: numbered_patch().values.to_vec(),
        };
        let m = s.mirror_image(FeatureKind::Patch);
        assert_eq!((m.sin_rel, m.cos_rel, m.speed_mps), (-0.6, 0.8, 5.0));
        let relative = m.heading_rad - m.bearing_rad;
        assert!((relative.sin() + 0.6).abs() < 1e-12 && (relative.cos() - 0.8).abs() < 1e-12);
        assert_eq!(
            m.heading_features,
            numbered_patch().mirrored().values.to_vec()
        );
    }
}
