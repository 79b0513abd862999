//! A picture of one sweep's features, like thesis Figure 2.4: the reflection map (grey) and the
//! difference map (red loss, green gain) side by side, with clusters and true boxes drawn on both.

use std::path::Path;

use patchflow_dataset::Sweep;

use crate::features::line::bresenham;
use crate::features::sweep_features::SweepFeatures;
use crate::{LearnError, Result};

/// Cluster colours, cycled by cluster id (no red or green: those mean loss and gain).
const PALETTE: [[u8; 3]; 6] = [
    [30, 90, 255],
    [255, 140, 0],
    [0, 190, 210],
    [150, 60, 200],
    [200, 170, 0],
    [120, 70, 30],
];
/// Outline colour of the true boxes.
const BOX: [u8; 3] = [255, 0, 255];
/// Width of the dark bar between the panels, pixels.
const GAP: usize = 4;

/// An RGB image, row 0 at the top.
struct Canvas {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

impl Canvas {
    fn put(&mut self, x: i64, y: i64, colour: [u8; 3]) {
        if x >= 0 && y >= 0 && (x as usize) < self.width && (y as usize) < self.height {
            let k = 3 * (y as usize * self.width + x as usize);
            self.rgb[k..k + 3].copy_from_slice(&colour);
        }
    }
}

/// Renders the features of `sweep` (one pixel per map cell, north up) as PNG bytes.
pub fn render_png(features: &SweepFeatures, sweep: &Sweep) -> Result<Vec<u8>> {
    let window = *features.reflection_map().window();
    let (w, h) = (window.cols, window.rows);
    let mut canvas = Canvas {
        width: 2 * w + GAP,
        height: h,
        rgb: vec![40; 3 * (2 * w + GAP) * h],
    };
    let (refl, diff) = (
        features.reflection_map().values(),
        features.difference_map().values(),
    );
    for row in 0..h {
        let y = (h - 1 - row) as i64;
        for col in 0..w {
            let k = window.index(col, row);
            let grey = (255.0 * (1.0 - refl[k].clamp(0.0, 1.0))).round() as u8;
            canvas.put(col as i64, y, [grey; 3]);
            canvas.put((w + GAP + col) as i64, y, diverging(diff[k]));
        }
    }
    // Each panel: pixel of a world point.
    let to_pixel = |x_m: f64, y_m: f64, panel: usize| {
        let [u, v] = window.to_local(x_m, y_m);
        (
            u.floor() as i64 + (panel * (w + GAP)) as i64,
            h as i64 - 1 - v.floor() as i64,
        )
    };
    for panel in 0..2 {
        for (i, p) in features.points().iter().enumerate() {
            let colour = PALETTE[features.cluster_of(i) % PALETTE.len()];
            let (x, y) = to_pixel(p.x_m, p.y_m, panel);
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                canvas.put(x + dx, y + dy, colour);
            }
        }
        for object in &sweep.objects {
            let corners = box_corners(object.centre_m, object.size_m, object.yaw_rad);
            for k in 0..4 {
                let (a, b) = (corners[k], corners[(k + 1) % 4]);
                let (x0, y0) = to_pixel(a[0], a[1], panel);
                let (x1, y1) = to_pixel(b[0], b[1], panel);
                bresenham(x0, y0, x1, y1, |x, y, _| canvas.put(x, y, BOX));
            }
        }
        let [sx, sy] = features.sensor_xy();
        let (x, y) = to_pixel(sx, sy, panel);
        for d in -4..=4 {
            canvas.put(x + d, y, [0, 0, 0]);
            canvas.put(x, y + d, [0, 0, 0]);
        }
    }
    encode(&canvas)
}

/// Writes `render_png` to `path`.
pub fn write_png(features: &SweepFeatures, sweep: &Sweep, path: &Path) -> Result<()> {
    let bytes = render_png(features, sweep)?;
    Ok(patchflow_dataset::write_atomic(path, &bytes)?)
}

/// White at 0, red towards −1 (loss), green towards +1 (gain).
fn diverging(v: f64) -> [u8; 3] {
    let fade = (255.0 * (1.0 - v.abs().min(1.0))).round() as u8;
    if v < 0.0 {
        [255, fade, fade]
    } else {
        [fade, 255, fade]
    }
}

/// Footprint corners of a box, world x, y, counter-clockwise.
fn box_corners(centre: [f64; 3], size: [f64; 3], yaw_rad: f64) -> [[f64; 2]; 4] {
    let (s, c) = yaw_rad.sin_cos();
    let (hl, hw) = (size[0] / 2.0, size[1] / 2.0);
    [(hl, hw), (-hl, hw), (-hl, -hw), (hl, -hw)]
        .map(|(a, b)| [centre[0] + a * c - b * s, centre[1] + a * s + b * c])
}

fn encode(canvas: &Canvas) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    let failed = |e: png::EncodingError| LearnError::degenerate_data(format!("PNG encoding: {e}"));
    let mut encoder = png::Encoder::new(&mut bytes, canvas.width as u32, canvas.height as u32);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(failed)?;
    writer.write_image_data(&canvas.rgb).map_err(failed)?;
    writer.finish().map_err(failed)?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::FeatureParams;
    use crate::features::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};

    fn demo() -> (SweepFeatures, Sweep) {
        let scene = SyntheticScene {
            boxes: vec![
                SceneBox::car(1, [8.0, 5.0], 0.0, 8.0),
                SceneBox::car(2, [-9.0, -3.0], 2.0, 5.0),
                SceneBox::wall([0.0, -9.0], 0.0, [24.0, 0.5, 2.5]),
            ],
        };
        let lidar = SyntheticLidar::with_resolution(64, 1800);
        let prev = scene.scan(&lidar, [-0.4, 0.0], 0.0, 0);
        let curr = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
        let params = FeatureParams {
            half_extent_m: 15.0,
            ..FeatureParams::default()
        };
        (SweepFeatures::compute(&prev, &curr, &params).unwrap(), curr)
    }

    #[test]
    fn the_png_shows_both_maps_side_by_side_with_red_loss_green_gain_and_box_outlines() {
        let (features, sweep) = demo();
        let bytes = render_png(&features, &sweep).unwrap();
        if let Ok(path) = std::env::var("PATCHFLOW_RENDER_DEMO") {
            std::fs::write(path, &bytes).unwrap();
        }
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height), (2 * 300 + GAP as u32, 300));
        let pixels: Vec<[u8; 3]> = buf.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        let count = |c: [u8; 3]| pixels.iter().filter(|&&p| p == c).count();
        assert!(count(BOX) > 100, "box outlines");
        assert!(
            count([255, 0, 0]) + count([0, 255, 0]) > 0,
            "saturated loss or gain cells"
        );
        assert!(pixels.iter().any(|p| p[0] > 200 && p[1] < 150), "some loss");
        assert!(pixels.iter().any(|p| p[1] > 200 && p[0] < 150), "some gain");
    }

    #[test]
    fn writing_into_a_missing_folder_names_the_file() {
        let (features, sweep) = demo();
        let err = write_png(&features, &sweep, Path::new("/no-such-dir/x.png")).unwrap_err();
        assert!(err.to_string().contains("/no-such-dir/x.png"), "{err}");
    }
}
