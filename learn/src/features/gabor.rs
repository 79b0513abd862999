//! The Gabor filter bank (thesis 2.2.3): 16 oriented odd Gabor filters whose dot products with a
//! difference patch form a 16-value feature.

use crate::GaborParams;
use crate::features::patch::{PATCH_CELLS, PATCH_SIDE, Patch};

/// Number of filters in the bank.
pub const GABOR_FILTERS: usize = 16;

/// A bank of `GABOR_FILTERS` Gabor filters sampled on the patch grid.
///
/// Filter `k` has orientation `θ_k = 2πk/16` (the full circle: with phase π/2 the filters at θ
/// and θ + π are each other's negatives, so the sign of a response tells loss-then-gain from
/// gain-then-loss) and is
/// `g(x, y) = exp(−(x'² + γ²y'²) / (2σ²)) · cos(2π x'/λ + π/2)` with
/// `x' = x cos θ + y sin θ`, `y' = −x sin θ + y cos θ` (thesis Eq. 2.15-2.17, with the product
/// the text describes rather than the sum its Eq. 2.15 prints), where `(x, y)` is a cell's
/// position in the patch frame in metres (x along the patch axis, y across it, see [`Patch`]).
/// Each filter is scaled to unit length so the bank is a set of unit basis vectors and every
/// response is a projection (thesis: "dot product … basis vectors").
#[derive(Debug, Clone, PartialEq)]
pub struct GaborBank {
    filters: Vec<[f64; PATCH_CELLS]>,
    orientations_rad: Vec<f64>,
}

impl GaborBank {
    /// Builds the bank for patch cells of side `cell_m`.
    ///
    /// ```
    /// use patchflow_learn::{GaborBank, GaborParams};
    /// let bank = GaborBank::new(&GaborParams::default(), 0.1);
    /// assert_eq!(bank.orientations_rad().len(), 16);
    /// ```
    pub fn new(params: &GaborParams, cell_m: f64) -> Self {
        let half = (PATCH_SIDE / 2) as f64;
        let orientations_rad: Vec<f64> = (0..GABOR_FILTERS)
            .map(|k| std::f64::consts::TAU * k as f64 / GABOR_FILTERS as f64)
            .collect();
        let filters = orientations_rad
            .iter()
            .map(|&theta| {
                let (s, c) = theta.sin_cos();
                let mut f = [0.0; PATCH_CELLS];
                for (k, value) in f.iter_mut().enumerate() {
                    let x = ((k % PATCH_SIDE) as f64 - half) * cell_m;
                    let y = ((k / PATCH_SIDE) as f64 - half) * cell_m;
                    let (xr, yr) = (x * c + y * s, -x * s + y * c);
                    let envelope = (-(xr * xr + params.gamma.powi(2) * yr * yr)
                        / (2.0 * params.sigma_m.powi(2)))
                    .exp();
                    let phase = std::f64::consts::TAU * xr / params.wavelength_m
                        + std::f64::consts::FRAC_PI_2;
                    *value = envelope * phase.cos();
                }
                let norm = f.iter().map(|v| v * v).sum::<f64>().sqrt();
                if norm > 0.0 {
                    f.iter_mut().for_each(|v| *v /= norm);
                }
                f
            })
            .collect();
        Self {
            filters,
            orientations_rad,
        }
    }

    /// Orientation θ of every filter, radians.
    pub fn orientations_rad(&self) -> &[f64] {
        &self.orientations_rad
    }

    /// The sampled filters, row-major like the patch's difference values.
    pub fn filters(&self) -> &[[f64; PATCH_CELLS]] {
        &self.filters
    }

    /// Dot products of the patch's difference values with every filter.
    pub fn responses(&self, patch: &Patch) -> [f64; GABOR_FILTERS] {
        let d = patch.difference();
        let mut out = [0.0; GABOR_FILTERS];
        for (o, f) in out.iter_mut().zip(&self.filters) {
            *o = f.iter().zip(d).map(|(a, b)| a * b).sum();
        }
        out
    }

    /// Column names `g00 … g15`.
    pub fn feature_names() -> Vec<String> {
        (0..GABOR_FILTERS).map(|k| format!("g{k:02}")).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::FeatureParams;
    use crate::features::difference_map::MapPair;
    use crate::features::slice::HeightSlice;
    use crate::features::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};

    /// Sum of squared responses: how strongly the bank answers a patch.
    fn bank_energy(responses: &[f64]) -> f64 {
        responses.iter().map(|r| r * r).sum()
    }

    /// Mean bank energy over the heading patches of the points on `scene`'s box 0, with the ego
    /// driving 0.5 m along +x between the sweeps (so static structure is seen from two places).
    pub(crate) fn mean_energy_on_box(scene: &SyntheticScene, params: &GaborParams) -> f64 {
        let lidar = SyntheticLidar::with_resolution(64, 1800);
        let fp = FeatureParams {
            half_extent_m: 20.0,
            ..FeatureParams::default()
        };
        let prev = HeightSlice::cut(&scene.scan(&lidar, [-0.5, 0.0], 0.0, 0), &fp).unwrap();
        let sweep = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
        let curr = HeightSlice::cut(&sweep, &fp).unwrap();
        let maps = MapPair::build(&prev, &curr, fp.map_window(curr.sensor_xy), &fp);
        let bank = GaborBank::new(params, fp.cell_m);
        let b = &scene.advanced(0.1).boxes[0];
        let (mut sum, mut n) = (0.0, 0.0);
        for p in &curr.points {
            if (p.x_m - b.centre_xy[0]).hypot(p.y_m - b.centre_xy[1]) > 3.0 {
                continue;
            }
            let patch = Patch::extract(&maps, [p.x_m, p.y_m], p.y_m.atan2(p.x_m));
            sum += bank_energy(&bank.responses(&patch));
            n += 1.0;
        }
        assert!(n > 10.0, "{n} points on the box");
        sum / n
    }

    fn approaching_car() -> SyntheticScene {
        SyntheticScene {
            boxes: vec![SceneBox::car(1, [14.0, 3.0], 3.0, 5.0)],
        }
    }

    #[test]
    fn orientations_cover_the_full_circle_with_odd_filters() {
        let bank = GaborBank::new(&GaborParams::default(), 0.1);
        let o = bank.orientations_rad();
        assert!((o[8] - std::f64::consts::PI).abs() < 1e-12 && o[15] > 5.8);
        for k in 0..8 {
            let (a, b) = (&bank.filters()[k], &bank.filters()[k + 8]);
            assert!(
                a.iter().zip(b).all(|(x, y)| (x + y).abs() < 1e-9),
                "θ + π negates filter {k}"
            );
        }
        // Phase π/2: the filter is odd about the centre and sums to zero.
        let f = &bank.filters()[0];
        assert!(f.iter().sum::<f64>().abs() < 1e-9);
        assert!((f[60] - 0.0).abs() < 1e-12, "zero at the centre");
        assert!(f[61] < 0.0 && f[59] > 0.0, "cos(x + π/2) = −sin x");
    }

    #[test]
    fn a_moving_box_patch_excites_the_bank_far_more_than_a_static_wall() {
        let params = GaborParams::default();
        let moving = mean_energy_on_box(&approaching_car(), &params);
        let wall = SyntheticScene {
            boxes: vec![SceneBox::wall([14.0, 3.0], 3.0, [4.5, 1.8, 1.5])],
        };
        let still = mean_energy_on_box(&wall, &params);
        assert!(moving > 10.0 * still, "moving {moving} vs static {still}");
    }

    #[test]
    fn the_chosen_wavelength_is_near_the_best_for_a_half_metre_move() {
        let energy = |wavelength_m: f64| {
            let params = GaborParams {
                wavelength_m,
                ..GaborParams::default()
            };
            mean_energy_on_box(&approaching_car(), &params)
        };
        let chosen = energy(GaborParams::default().wavelength_m);
        let best = [0.6, 0.8, 2.0, 3.0]
            .map(energy)
            .into_iter()
            .fold(chosen, f64::max);
        assert!(chosen >= 0.9 * best, "chosen {chosen} vs best {best}");
        assert!(
            chosen > 3.0 * energy(0.4),
            "a too short wavelength answers much less"
        );
    }
}
