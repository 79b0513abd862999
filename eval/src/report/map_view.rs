//! One sweep's reflection map and difference map (thesis 2.1, Figure 2.4) side by side on world
//! metre axes, with the clusters' points, the true boxes, a title and a colour key for each map:
//! reflection probability (white 0 → black 1) and difference (red: cell lost reflection, green:
//! cell gained it).

use std::path::Path;

use patchflow_dataset::Sweep;
use patchflow_learn::{GridMap, SweepFeatures};
use plotters::coord::ReverseCoordTranslate;
use plotters::prelude::*;

use crate::error::EvalError;
use crate::report::font::{FONT, ensure_font};
use crate::report::png_file::PngFile;
use crate::report::world_chart::{Area, DrawResult, footprint};

const SIZE_PX: (u32, u32) = (1500, 800);
/// Height of the colour-key strip under the panels.
const KEY_PX: u32 = 90;

/// One panel: its area, its key's area, the map, its label, its colours and their value range.
type Panel<'a, 'b> = (
    &'a Area<'b>,
    &'a Area<'b>,
    &'a GridMap,
    &'static str,
    fn(f64) -> RGBColor,
    (f64, f64),
);

/// Grey of a reflection probability: white at 0, black at 1.
fn reflection_colour(p: f64) -> RGBColor {
    let grey = (255.0 * (1.0 - p.clamp(0.0, 1.0))).round() as u8;
    RGBColor(grey, grey, grey)
}

/// White at 0, red towards −1 (loss), green towards +1 (gain).
fn difference_colour(d: f64) -> RGBColor {
    let fade = (255.0 * (1.0 - d.abs().min(1.0))).round() as u8;
    if d < 0.0 {
        RGBColor(255, fade, fade)
    } else {
        RGBColor(fade, 255, fade)
    }
}

/// Writes the two maps of `features` (computed for `sweep`) to `path`; `title` heads the figure.
pub fn write_map_figure(
    features: &SweepFeatures,
    sweep: &Sweep,
    title: &str,
    path: &Path,
) -> Result<(), EvalError> {
    ensure_font(path)?;
    let plot_err = |e: &dyn std::fmt::Display| EvalError::Plot {
        path: path.to_owned(),
        message: e.to_string(),
    };
    let png = PngFile::new(path);
    let png_path = png.drawing_path().to_path_buf();
    let root = BitMapBackend::new(&png_path, SIZE_PX).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_err(&e))?;
    let root = root.titled(title, (FONT, 20)).map_err(|e| plot_err(&e))?;
    let (panels, keys) = root.split_vertically(SIZE_PX.1 - 30 - KEY_PX);
    let (left, right) = panels.split_horizontally(SIZE_PX.0 / 2);
    let (left_key, right_key) = keys.split_horizontally(SIZE_PX.0 / 2);
    let maps: [Panel<'_, '_>; 2] = [
        (
            &left,
            &left_key,
            features.reflection_map(),
            "reflection map m_t",
            reflection_colour,
            (0.0, 1.0),
        ),
        (
            &right,
            &right_key,
            features.difference_map(),
            "difference map m_t − m_(t−1)",
            difference_colour,
            (-1.0, 1.0),
        ),
    ];
    for (area, key, map, label, colour, (lo, hi)) in maps {
        draw_map(area, map, label, colour, features, sweep).map_err(|e| plot_err(&e))?;
        draw_colour_key(key, label, colour, lo, hi).map_err(|e| plot_err(&e))?;
    }
    root.present().map_err(|e| plot_err(&e))?;
    png.commit()
}

fn draw_map(
    area: &Area<'_>,
    map: &GridMap,
    label: &str,
    colour: fn(f64) -> RGBColor,
    features: &SweepFeatures,
    sweep: &Sweep,
) -> DrawResult {
    let window = *map.window();
    let [x0, y0] = window.centre_of(0, 0);
    let half = window.cell_m / 2.0;
    let (x_range, y_range) = (
        x0 - half..x0 - half + window.cols as f64 * window.cell_m,
        y0 - half..y0 - half + window.rows as f64 * window.cell_m,
    );
    let mut chart = ChartBuilder::on(area)
        .caption(label, (FONT, 17))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(56)
        .build_cartesian_2d(x_range, y_range)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("x (m, world frame)")
        .y_desc("y (m, world frame)")
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_label_formatter(&|y| format!("{y:.0}"))
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 14))
        .draw()?;
    // One value per screen pixel: the cell under its centre.
    let plotting = chart.plotting_area();
    let (px, py) = plotting.get_pixel_range();
    let values = map.values();
    for x in px.clone() {
        for y in py.clone() {
            let Some((wx, wy)) = chart.as_coord_spec().reverse_translate((x, y)) else {
                continue;
            };
            if let Some((c, r)) = window.cell_of(wx, wy) {
                plotting.draw_pixel((wx, wy), &colour(values[window.index(c, r)]))?;
            }
        }
    }
    let cluster = RGBColor(30, 90, 255);
    chart.draw_series(
        features
            .points()
            .iter()
            .map(|p| Circle::new((p.x_m, p.y_m), 1, cluster.filled())),
    )?;
    for o in &sweep.objects {
        let mut corners = footprint(o.centre_m, o.size_m, o.yaw_rad);
        corners.push(corners[0]);
        let colour = if o.target {
            RGBColor(214, 39, 40)
        } else {
            RGBColor(200, 0, 200)
        };
        chart.draw_series(std::iter::once(PathElement::new(
            corners,
            colour.stroke_width(2),
        )))?;
    }
    let [sx, sy] = features.sensor_xy();
    chart.draw_series(std::iter::once(TriangleMarker::new(
        (sx, sy),
        7,
        BLACK.filled(),
    )))?;
    Ok(())
}

/// A horizontal colour bar from `lo` to `hi` with its ends and middle labelled, and the legend of
/// the marks drawn on the maps.
fn draw_colour_key(
    key: &Area<'_>,
    label: &str,
    colour: fn(f64) -> RGBColor,
    lo: f64,
    hi: f64,
) -> DrawResult {
    let text = TextStyle::from((FONT, 13)).color(&BLACK);
    let (x0, width, y) = (70, 320, 14);
    for k in 0..width {
        let v = lo + (hi - lo) * f64::from(k) / f64::from(width - 1);
        key.draw(&Rectangle::new(
            [(x0 + k, y), (x0 + k + 1, y + 18)],
            colour(v).filled(),
        ))?;
    }
    key.draw(&Rectangle::new(
        [(x0, y), (x0 + width, y + 18)],
        BLACK.stroke_width(1),
    ))?;
    for (v, x) in [
        (lo, x0),
        ((lo + hi) / 2.0, x0 + width / 2),
        (hi, x0 + width),
    ] {
        key.draw(&Text::new(format!("{v:.1}"), (x - 8, y + 22), text.clone()))?;
    }
    key.draw(&Text::new(
        label.to_owned(),
        (x0 + width + 14, y + 2),
        text.clone(),
    ))?;
    key.draw(&Text::new(
        "blue dots: sliced points of the clusters; magenta boxes: actors (red: target); ▲ sensor",
        (x0, y + 44),
        text,
    ))?;
    Ok(())
}
