//! Map patches (thesis 2.2.2): 11 × 11 samples of the difference map and of the current
//! reflection map on a grid centred on a point and rotated to a reference axis.

use crate::features::difference_map::MapPair;
use crate::features::grid::{GridMap, GridWindow};

/// Cells along each side of a patch (thesis 4.3: 11 × 11 cells of 0.10 m, 1.1 m a side).
pub const PATCH_SIDE: usize = 11;
/// Cells in one map's half of a patch.
pub const PATCH_CELLS: usize = PATCH_SIDE * PATCH_SIDE;
/// Values in a patch: the difference cells, then the reflection cells.
pub const PATCH_LEN: usize = 2 * PATCH_CELLS;

/// A 242-value map patch.
///
/// Value order: first the 121 difference-map values `d_r_c`, then the 121 reflection-map values
/// `m_r_c`, each row-major (`r · 11 + c`). Sample `(r, c)` lies at
/// `centre + (c − 5)·cell·axis + (r − 5)·cell·normal`, where `axis` is the reference direction
/// and `normal` the axis turned 90° counter-clockwise: column `c` runs along the reference axis
/// (`c = 0` half a metre towards the sensor for a heading patch, `c = 10` half a metre beyond),
/// row `r` runs across it (`r = 0` half a metre to the right of the axis). Values between cell
/// centres are interpolated bilinearly.
#[derive(Debug, Clone, PartialEq)]
pub struct Patch {
    /// The 242 values in the order above.
    pub values: [f64; PATCH_LEN],
}

impl Patch {
    /// Samples both maps on the grid centred on `centre_xy` (world) with reference axis
    /// `axis_rad` (counter-clockwise from world +x); sample spacing is the map's cell size.
    pub fn extract(maps: &MapPair, centre_xy: [f64; 2], axis_rad: f64) -> Self {
        let mut values = [0.0; PATCH_LEN];
        Self::extract_into(maps, centre_xy, axis_rad, &mut values);
        Self { values }
    }

    /// [`Patch::extract`] written into `values` (e.g. a row of a GP input buffer, without the
    /// copy a returned patch costs).
    pub fn extract_into(
        maps: &MapPair,
        centre_xy: [f64; 2],
        axis_rad: f64,
        values: &mut [f64; PATCH_LEN],
    ) {
        let window = *maps.reflection.window();
        let (s, c) = axis_rad.sin_cos();
        let half = (PATCH_SIDE / 2) as f64;
        // Sample positions in local cell units (spacing one cell), relative to cell centres.
        let [uc, vc] = window.to_local(centre_xy[0], centre_xy[1]);
        let (uc, vc) = (uc - 0.5, vc - 0.5);
        let shared = maps.difference.window() == &window;
        for r in 0..PATCH_SIDE {
            let across = r as f64 - half;
            for col in 0..PATCH_SIDE {
                let along = col as f64 - half;
                let u = uc + along * c - across * s;
                let v = vc + along * s + across * c;
                let k = r * PATCH_SIDE + col;
                (values[k], values[PATCH_CELLS + k]) = match shared {
                    true => sample_both(maps, &window, u, v),
                    false => {
                        let x = (u + 0.5 + window.origin_col as f64) * window.cell_m;
                        let y = (v + 0.5 + window.origin_row as f64) * window.cell_m;
                        (
                            maps.difference.sample_bilinear(x, y),
                            maps.reflection.sample_bilinear(x, y),
                        )
                    }
                };
            }
        }
    }

    /// The 121 difference-map values.
    pub fn difference(&self) -> &[f64] {
        &self.values[..PATCH_CELLS]
    }

    /// The 121 reflection-map values.
    pub fn reflection(&self) -> &[f64] {
        &self.values[PATCH_CELLS..]
    }

    /// Mean absolute difference-map value: the importance weight of thesis Eq. 3.1.
    pub fn mean_abs_difference(&self) -> f64 {
        self.difference().iter().map(|v| v.abs()).sum::<f64>() / PATCH_CELLS as f64
    }

    /// Column names in value order: `d_0_0 … d_10_10, m_0_0 … m_10_10`.
    pub fn feature_names() -> Vec<String> {
        ["d", "m"]
            .iter()
            .flat_map(|map| {
                (0..PATCH_CELLS)
                    .map(move |k| format!("{map}_{}_{}", k / PATCH_SIDE, k % PATCH_SIDE))
            })
            .collect()
    }
}

/// Bilinear samples of the difference and reflection maps (which share `window`) at local
/// position `(u, v)` measured from cell centres: indices and weights are computed once.
#[inline(always)]
fn sample_both(maps: &MapPair, window: &GridWindow, u: f64, v: f64) -> (f64, f64) {
    let (c0, r0) = (floor(u), floor(v));
    let inside =
        c0 >= 0.0 && r0 >= 0.0 && c0 + 1.0 < window.cols as f64 && r0 + 1.0 < window.rows as f64;
    let (tu, tv) = (u - c0, v - r0);
    let weights = [
        (1.0 - tu) * (1.0 - tv),
        tu * (1.0 - tv),
        (1.0 - tu) * tv,
        tu * tv,
    ];
    if !inside {
        let (c, r) = (c0 as i64, r0 as i64);
        let corners = [(c, r), (c + 1, r), (c, r + 1), (c + 1, r + 1)];
        let blend = |map: &GridMap| {
            corners
                .iter()
                .zip(&weights)
                .map(|(&(c, r), w)| map.get(c, r) * w)
                .sum()
        };
        return (blend(&maps.difference), blend(&maps.reflection));
    }
    let k = r0 as usize * window.cols + c0 as usize;
    let cells = [k, k + 1, k + window.cols, k + window.cols + 1];
    let blend = |values: &[f64]| {
        cells
            .iter()
            .zip(&weights)
            .map(|(&c, w)| values[c] * w)
            .sum()
    };
    (
        blend(maps.difference.values()),
        blend(maps.reflection.values()),
    )
}

/// 2⁵²: from this magnitude on every f64 is a whole number.
const WHOLE_FROM: f64 = 4_503_599_627_370_496.0;

/// `x.floor()`, bit for bit (signed zeros included), without the library call `f64::floor`
/// costs on baseline x86-64 (a fifth of a patch's time); NaN and whole magnitudes go to the
/// library.
#[inline(always)]
fn floor(x: f64) -> f64 {
    if x.is_nan() || x.abs() >= WHOLE_FROM {
        return x.floor();
    }
    let t = x as i64 as f64; // towards zero, exact below 2⁵²
    let t = if t > x { t - 1.0 } else { t };
    if t == 0.0 { t.copysign(x) } else { t }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::FeatureParams;
    use crate::features::slice::HeightSlice;
    use crate::features::synthetic::{SceneBox, SyntheticLidar, SyntheticScene, rotate_about};

    fn maps(scene: &SyntheticScene, sensor_xy: [f64; 2], yaw: f64) -> (MapPair, HeightSlice) {
        let lidar = SyntheticLidar::with_resolution(64, 1800);
        // The flat ground: the rotation test needs the slice itself to rotate exactly, and the
        // ground estimate's world-aligned cells do not.
        let params = FeatureParams {
            half_extent_m: 20.0,
            ground: crate::GroundMode::Flat,
            ..FeatureParams::default()
        };
        let prev = HeightSlice::cut(&scene.scan(&lidar, sensor_xy, yaw, 0), &params).unwrap();
        let curr_sweep = scene.advanced(0.1).scan(&lidar, sensor_xy, yaw, 1);
        let curr = HeightSlice::cut(&curr_sweep, &params).unwrap();
        (
            MapPair::build(&prev, &curr, params.map_window(curr.sensor_xy), &params),
            curr,
        )
    }

    #[test]
    fn the_inline_floor_gives_the_bits_of_the_library_floor() {
        let mut values = vec![
            0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 2.5e15, -2.5e15, 1e300, -1e300,
        ];
        values.extend([
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
        ]);
        values.extend([
            WHOLE_FROM - 0.5,
            -(WHOLE_FROM - 0.5),
            WHOLE_FROM,
            -WHOLE_FROM,
        ]);
        values.extend((0..20_000).map(|i| (i as f64 - 10_000.0) * 0.037_3));
        values.extend((0..2_000).map(|i| f64::from_bits(0x3ff0_0000_0000_0000 + i * 0x1234_5678)));
        for x in values.iter().flat_map(|&v| [v, -v]) {
            assert_eq!(floor(x).to_bits(), x.floor().to_bits(), "floor({x:e})");
        }
        assert!(floor(f64::NAN).is_nan());
    }

    #[test]
    fn a_patch_on_the_axis_reads_the_map_in_the_documented_order() {
        let w = GridWindow::centred([0.0, 0.0], 2.0, 0.1);
        let mut difference = GridMap::filled(w, 0.0);
        let (col, row) = w.cell_of(0.25, 0.05).unwrap();
        difference.values_mut()[w.index(col, row)] = 1.0;
        let maps = MapPair {
            reflection: GridMap::filled(w, 0.5),
            difference,
        };
        // Axis +y: the marked cell 0.2 m along +x lies to the right of the axis: row 3, column 5.
        let patch = Patch::extract(&maps, [0.05, 0.05], std::f64::consts::FRAC_PI_2);
        assert!((patch.values[3 * PATCH_SIDE + 5] - 1.0).abs() < 1e-9);
        assert!((patch.difference().iter().sum::<f64>() - 1.0).abs() < 1e-9);
        assert!(patch.reflection().iter().all(|&v| (v - 0.5).abs() < 1e-12));
        assert_eq!(Patch::feature_names()[PATCH_CELLS + 12], "m_1_1");
    }

    #[test]
    fn samples_beyond_the_window_read_the_prior_and_zero_change() {
        let w = GridWindow::centred([0.0, 0.0], 2.0, 0.1);
        let maps = MapPair {
            reflection: GridMap::from_values(w, vec![0.0; w.len()], 0.5).unwrap(),
            difference: GridMap::from_values(w, vec![1.0; w.len()], 0.0).unwrap(),
        };
        // Centred on the window's right edge: columns 6..=10 lie outside, column 5 on the edge.
        let patch = Patch::extract(&maps, [2.0, 0.0], 0.0);
        assert!((patch.values[5 * PATCH_SIDE + 10] - 0.0).abs() < 1e-12);
        assert!((patch.values[PATCH_CELLS + 5 * PATCH_SIDE + 10] - 0.5).abs() < 1e-12);
        assert!((patch.values[5 * PATCH_SIDE] - 1.0).abs() < 1e-12);
        assert!((patch.values[PATCH_CELLS + 5 * PATCH_SIDE] - 0.0).abs() < 1e-12);
    }

    #[test]
    fn patches_of_a_rotated_scene_agree_after_rotating_their_axes() {
        let scene = SyntheticScene {
            boxes: vec![
                SceneBox::car(1, [9.0, 4.0], 2.2, 6.0),
                SceneBox::wall([4.0, -8.0], 0.3, [10.0, 0.4, 2.0]),
            ],
        };
        let sensor = [0.5, -0.5];
        let (maps_a, slice_a) = maps(&scene, sensor, 0.1);
        for angle in [0.4_f64, 1.9, -2.7] {
            let pivot = [3.0, 1.0];
            let rotated = scene.rotated(pivot, angle);
            let sensor_b = rotate_about(sensor, pivot, angle);
            let (maps_b, slice_b) = maps(&rotated, sensor_b, 0.1 + angle);
            let (mut err, mut wrong, mut size, mut n) = (0.0, 0.0, 0.0, 0.0);
            for (pa, pb) in slice_a.points.iter().zip(&slice_b.points) {
                assert_eq!(pa.index, pb.index, "the same rays hit the rotated scene");
                let xy_a = [pa.x_m, pa.y_m];
                if (xy_a[0] - 9.0).hypot(xy_a[1] - 4.0) > 3.0 {
                    continue;
                }
                let bearing_a = (xy_a[1] - sensor[1]).atan2(xy_a[0] - sensor[0]);
                let a = Patch::extract(&maps_a, xy_a, bearing_a);
                let b = Patch::extract(&maps_b, [pb.x_m, pb.y_m], bearing_a + angle);
                let unrotated = Patch::extract(&maps_b, [pb.x_m, pb.y_m], bearing_a);
                let mad = |p: &Patch, q: &Patch| {
                    p.values
                        .iter()
                        .zip(&q.values)
                        .map(|(x, y)| (x - y).abs())
                        .sum::<f64>()
                        / PATCH_LEN as f64
                };
                err += mad(&a, &b);
                wrong += mad(&a, &unrotated);
                size += a.mean_abs_difference();
                n += 1.0;
            }
            assert!(n > 20.0, "{n} car points");
            let (err, wrong, size) = (err / n, wrong / n, size / n);
            assert!(err < 0.05, "angle {angle}: mean |a − b| {err}");
            assert!(
                wrong > 3.0 * err,
                "angle {angle}: unrotated {wrong} vs rotated {err}"
            );
            assert!(size > 0.03, "the patches carry motion: {size}");
        }
    }
}
