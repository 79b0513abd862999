//! `plots/summary_rmse.png`: heading RMSE (top) and speed RMSE (bottom) of every method in every
//! situation as grouped bars, one group per situation, the key beside the bars; the one picture
//! of the whole per-target comparison (thesis Tables 4.6-4.15 at a glance).

use std::path::Path;

use plotters::prelude::*;

use crate::error::EvalError;
use crate::methods::method::Method;
use crate::report::font::{FONT, ensure_font};
use crate::report::plot::{colour_of, is_variant};
use crate::report::png_file::PngFile;
use crate::report::scores::SituationMetrics;
use crate::scene::metrics::MethodMetrics;

const SIZE_PX: (u32, u32) = (1200, 760);
const KEY_PX: u32 = 230;

/// The figure a panel shows.
type Figure = fn(&MethodMetrics) -> Option<f64>;

/// Draws the summary figure of `metrics` (situations in report order) to `path`.
pub(crate) fn plot_summary(metrics: &[SituationMetrics], path: &Path) -> Result<(), EvalError> {
    ensure_font(path)?;
    let plot_err = |e: &dyn std::fmt::Display| EvalError::Plot {
        path: path.to_owned(),
        message: e.to_string(),
    };
    let methods: Vec<Method> = {
        let mut all: Vec<Method> = metrics
            .iter()
            .flat_map(|(_, _, m)| {
                m.iter()
                    .filter(|(_, x)| x.coverage > 0.0 || x.heading_rmse_deg.is_some())
                    .map(|(k, _)| *k)
            })
            .collect();
        all.sort();
        all.dedup();
        all
    };
    let png = PngFile::new(path);
    let png_path = png.drawing_path().to_path_buf();
    let root = BitMapBackend::new(&png_path, SIZE_PX).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_err(&e))?;
    let root = root
        .titled(
            "Target heading and speed RMSE per method and situation",
            (FONT, 24),
        )
        .map_err(|e| plot_err(&e))?;
    let (left, key) = root.split_horizontally(SIZE_PX.0 - KEY_PX);
    let (top, bottom) = left.split_vertically((SIZE_PX.1 - 40) / 2);
    let names: Vec<&str> = metrics.iter().map(|(n, _, _)| n.as_str()).collect();
    let panels: [(_, &str, Figure); 2] = [
        (&top, "heading RMSE (°)", |m| m.heading_rmse_deg),
        (&bottom, "speed RMSE (m/s)", |m| m.speed_rmse_mps),
    ];
    for (area, label, value) in panels {
        let bars: Vec<(usize, usize, f64)> = metrics
            .iter()
            .enumerate()
            .flat_map(|(s, (_, _, by_method))| {
                methods
                    .iter()
                    .enumerate()
                    .filter_map(move |(k, m)| by_method.get(m).and_then(value).map(|v| (s, k, v)))
            })
            .filter(|(_, _, v)| v.is_finite())
            .collect();
        let top_value = bars.iter().map(|b| b.2).fold(0.0f64, f64::max).max(1e-3) * 1.1;
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..names.len().max(1) as f64, 0.0..top_value)
            .map_err(|e| plot_err(&e))?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(names.len().max(1) * 2 + 1)
            .x_label_formatter(&|x| {
                let i = x.floor() as usize;
                let centred = (x - i as f64 - 0.5).abs() < 0.01;
                match names.get(i) {
                    Some(n) if centred => (*n).to_owned(),
                    _ => String::new(),
                }
            })
            .y_desc(label)
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 17))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(|e| plot_err(&e))?;
        let width = 0.8 / methods.len().max(1) as f64;
        chart
            .draw_series(bars.iter().map(|&(s, k, v)| {
                let x0 = s as f64 + 0.1 + k as f64 * width;
                let colour = colour_of(methods[k]);
                let style = if is_variant(methods[k]) {
                    colour.mix(0.45).filled()
                } else {
                    colour.filled()
                };
                Rectangle::new([(x0, 0.0), (x0 + width * 0.9, v)], style)
            }))
            .map_err(|e| plot_err(&e))?;
    }
    let text = TextStyle::from((FONT, 15)).color(&BLACK);
    for (k, method) in methods.iter().enumerate() {
        let y = 40 + 24 * k as i32;
        let colour = colour_of(*method);
        let style = if is_variant(*method) {
            colour.mix(0.45).filled()
        } else {
            colour.filled()
        };
        key.draw(&Rectangle::new([(10, y - 7), (38, y + 7)], style))
            .map_err(|e| plot_err(&e))?;
        key.draw(&Text::new(method.name(), (46, y - 8), text.clone()))
            .map_err(|e| plot_err(&e))?;
    }
    root.present().map_err(|e| plot_err(&e))?;
    png.commit()
}
