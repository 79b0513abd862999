//! One plot per measure of a study: the measure (the situations pooled) of every method against
//! the varied factor, drawn with plotters' bitmap backend and the bundled font.

use std::path::{Path, PathBuf};

use plotters::prelude::*;

use crate::error::EvalError;
use crate::report::png_file::PngFile;
use crate::report::{FONT, create_dir, ensure_font, palette_colour};
use crate::study::measures::{MEASURES, study_methods};
use crate::study::study_report::StudyReport;

const SIZE_PX: (u32, u32) = (900, 520);

/// Draws `plots/study_<name>_<measure>.png` for every measure; returns the files.
pub(crate) fn plot_study(report: &StudyReport, dir: &Path) -> Result<Vec<PathBuf>, EvalError> {
    create_dir(dir)?;
    MEASURES
        .iter()
        .map(|(title, stem, _, value)| {
            let path = dir.join(format!("study_{}_{stem}.png", report.study));
            draw(report, &path, title, *value).map_err(|message| EvalError::Plot {
                path: path.clone(),
                message,
            })?;
            Ok(path)
        })
        .collect()
}

fn draw(
    report: &StudyReport,
    path: &Path,
    title: &str,
    value: fn(&crate::study::point_result::Scores) -> Option<f64>,
) -> Result<(), String> {
    ensure_font(path).map_err(|e| e.to_string())?;
    let methods = study_methods(report);
    // x is the point's position: rungs have no numeric value, and rates and channels double.
    let curves: Vec<(String, Vec<(f64, f64)>)> = methods
        .iter()
        .map(|m| {
            let points = report
                .points
                .iter()
                .enumerate()
                .filter_map(|(k, p)| {
                    let v = p.pooled.get(m).and_then(value)?;
                    v.is_finite().then_some((k as f64, v))
                })
                .collect();
            (m.clone(), points)
        })
        .collect();
    let top = curves
        .iter()
        .flat_map(|(_, c)| c.iter().map(|p| p.1))
        .fold(0.0_f64, f64::max)
        * 1.1
        + 1e-9;
    let labels: Vec<String> = report.points.iter().map(|p| p.label.clone()).collect();
    let n = labels.len().max(1) as f64;
    let png = PngFile::new(path);
    let png_path = png.drawing_path().to_path_buf();
    let root = BitMapBackend::new(&png_path, SIZE_PX).into_drawing_area();
    let e = |e: &dyn std::fmt::Display| e.to_string();
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("{title} against {} (situations pooled)", report.study),
            (FONT, 20),
        )
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(52)
        .build_cartesian_2d(-0.3..(n - 0.7), 0.0..top)
        .map_err(|x| e(&x))?;
    chart
        .configure_mesh()
        .x_labels(labels.len())
        .x_label_formatter(&|x| {
            let k = x.round();
            if (x - k).abs() < 1e-6 && k >= 0.0 {
                labels.get(k as usize).cloned().unwrap_or_default()
            } else {
                String::new()
            }
        })
        .y_desc(title)
        .label_style((FONT, 13))
        .draw()
        .map_err(|x| e(&x))?;
    for (k, (method, points)) in curves.iter().enumerate() {
        let colour = palette_colour(k);
        chart
            .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))
            .map_err(|x| e(&x))?
            .label(method.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
            });
        chart
            .draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
            .map_err(|x| e(&x))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, 12))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|x| e(&x))?;
    root.present().map_err(|x| e(&x))?;
    png.commit().map_err(|e| e.to_string())
}
