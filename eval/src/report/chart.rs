//! The line chart every report plot is drawn with: curves over a shared x axis, the key in its
//! own panel right of the data (so it never covers a curve), variants of one method (BEST, AUTO)
//! dashed with hollow markers over the solid original so both stay visible where they agree,
//! optional grey bands over x ranges to mark (e.g. scans where the target is not seen) and an
//! optional strip under the chart (e.g. the target's range over time).

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::error::EvalError;
use crate::report::font::{FONT, ensure_font};
use crate::report::png_file::PngFile;

/// Canvas size: chart and key panel.
const SIZE_PX: (u32, u32) = (1200, 620);
/// Canvas size with a strip under the chart.
const SIZE_WITH_STRIP_PX: (u32, u32) = (1200, 780);
/// Width of the key panel.
const KEY_PX: u32 = 230;

/// One curve: (x, value) runs without gaps, so lines break where a method has no estimate.
pub(crate) struct Curve {
    /// Key label.
    pub label: String,
    /// Line colour.
    pub colour: RGBColor,
    /// Points; `None` breaks the line.
    pub points: Vec<Option<(f64, f64)>>,
    /// A variant drawn over its original: dashed, thinner, hollow markers.
    pub dashed: bool,
}

/// Axis descriptions and the resolution of the value axis.
pub(crate) struct Axes<'a> {
    /// Description of the x axis.
    pub x: &'a str,
    /// Decimals of the x tick labels.
    pub x_decimals: usize,
    /// Description of the y axis.
    pub y: &'a str,
    /// Decimals of the y tick labels.
    pub y_decimals: usize,
    /// Smallest padding above and below the data, in y units.
    pub min_pad: f64,
}

/// What a chart shows beside its curves.
#[derive(Default)]
pub(crate) struct Decor {
    /// x ranges shaded grey, and what the shading means (for the key).
    pub bands: Vec<(f64, f64)>,
    /// The key's text for the bands.
    pub band_label: String,
    /// A strip under the chart on the same x axis: its y description and points.
    pub strip: Option<(String, Vec<(f64, f64)>)>,
}

type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;

/// Draws curves (and a black truth curve, if any) to a PNG.
pub(crate) fn draw(
    path: &Path,
    title: &str,
    axes: Axes<'_>,
    truth: Vec<Option<(f64, f64)>>,
    curves: Vec<Curve>,
    y_floor: Option<f64>,
    decor: &Decor,
) -> Result<(), EvalError> {
    ensure_font(path)?;
    let plot_err = |e: &dyn std::fmt::Display| EvalError::Plot {
        path: path.to_owned(),
        message: e.to_string(),
    };
    let all = truth
        .iter()
        .chain(curves.iter().flat_map(|c| c.points.iter()))
        .flatten();
    let (mut x_min, mut x_max) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut y_min, mut y_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for (x, y) in all {
        x_min = x_min.min(*x);
        x_max = x_max.max(*x);
        y_min = y_min.min(*y);
        y_max = y_max.max(*y);
    }
    if !x_min.is_finite() {
        (x_min, x_max) = (0.0, 1.0);
    }
    if !y_min.is_finite() {
        (y_min, y_max) = (0.0, 1.0);
    }
    let x_pad = ((x_max - x_min) * 0.02).max(1e-6);
    let x_range = x_min.min(0.0)..x_max + x_pad;
    let pad = ((y_max - y_min) * 0.08).max(axes.min_pad);
    let y_range = y_floor.map_or(y_min - pad, |f| f.min(y_min))..(y_max + pad);

    let size = if decor.strip.is_some() {
        SIZE_WITH_STRIP_PX
    } else {
        SIZE_PX
    };
    let png = PngFile::new(path);
    let png_path = png.drawing_path().to_path_buf();
    let root = BitMapBackend::new(&png_path, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_err(&e))?;
    let root = root.titled(title, (FONT, 24)).map_err(|e| plot_err(&e))?;
    let (left, key) = root.split_horizontally(size.0 - KEY_PX);
    let (main, strip) = if decor.strip.is_some() {
        let (main, strip) = left.split_vertically(size.1 - 60 - 190);
        (main, Some(strip))
    } else {
        (left, None)
    };
    let mut chart = ChartBuilder::on(&main)
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(70)
        .build_cartesian_2d(x_range.clone(), y_range.clone())
        .map_err(|e| plot_err(&e))?;
    chart
        .configure_mesh()
        .x_desc(axes.x)
        .y_desc(axes.y)
        .x_label_formatter(&|x| format!("{x:.*}", axes.x_decimals))
        .y_label_formatter(&|y| format!("{y:.*}", axes.y_decimals))
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 17))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|e| plot_err(&e))?;
    let band_style = RGBColor(215, 215, 215).mix(0.6).filled();
    chart
        .draw_series(
            decor
                .bands
                .iter()
                .map(|&(a, b)| Rectangle::new([(a, y_range.start), (b, y_range.end)], band_style)),
        )
        .map_err(|e| plot_err(&e))?;
    let truth_curve = Curve {
        label: "truth".into(),
        colour: BLACK,
        points: truth,
        dashed: false,
    };
    let mut keyed = Vec::new();
    if truth_curve.points.iter().any(Option::is_some) {
        draw_curve(&mut chart, &truth_curve, 3).map_err(|e| plot_err(&e))?;
        keyed.push(&truth_curve);
    }
    // Originals first, variants dashed on top of them.
    for dashed in [false, true] {
        for curve in curves.iter().filter(|c| c.dashed == dashed) {
            draw_curve(&mut chart, curve, 2).map_err(|e| plot_err(&e))?;
        }
    }
    keyed.extend(&curves);
    if let (Some(area), Some((label, points))) = (strip, &decor.strip) {
        draw_strip(&area, label, points, x_range, &axes).map_err(|e| plot_err(&e))?;
    }
    draw_key(&key, &keyed, decor).map_err(|e| plot_err(&e))?;
    root.present().map_err(|e| plot_err(&e))?;
    png.commit()
}

type Chart<'a> = ChartContext<
    'a,
    BitMapBackend<'a>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;
type DrawResult =
    Result<(), DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>>;

fn draw_curve(chart: &mut Chart<'_>, curve: &Curve, width: u32) -> DrawResult {
    let width = if curve.dashed {
        1.max(width - 1)
    } else {
        width
    };
    let style = curve.colour.stroke_width(width);
    // Lines over runs without gaps.
    for run in curve.points.split(Option::is_none) {
        let run: Vec<(f64, f64)> = run.iter().flatten().copied().collect();
        if run.len() < 2 {
            continue;
        }
        if curve.dashed {
            chart.draw_series(DashedLineSeries::new(run, 7, 4, style))?;
        } else {
            chart.draw_series(LineSeries::new(run, style))?;
        }
    }
    // Markers on every point: filled for originals, hollow for variants.
    let points: Vec<(f64, f64)> = curve.points.iter().flatten().copied().collect();
    let colour = curve.colour;
    if curve.dashed {
        chart.draw_series(
            points
                .into_iter()
                .map(move |p| TriangleMarker::new(p, width + 3, colour.stroke_width(1))),
        )?;
    } else {
        chart.draw_series(
            points
                .into_iter()
                .map(move |p| Circle::new(p, width + 1, colour.filled())),
        )?;
    }
    Ok(())
}

/// The key: one row per curve (line style and marker as drawn), then the bands' meaning.
fn draw_key(area: &Area<'_>, curves: &[&Curve], decor: &Decor) -> DrawResult {
    let text = TextStyle::from((FONT, 15)).color(&BLACK);
    let mut y = 40;
    for curve in curves {
        let colour = curve.colour;
        if curve.dashed {
            for k in 0..3 {
                let x = 10 + k * 11;
                area.draw(&PathElement::new(
                    vec![(x, y), (x + 7, y)],
                    colour.stroke_width(2),
                ))?;
            }
            area.draw(&TriangleMarker::new((24, y), 5, colour.stroke_width(1)))?;
        } else {
            area.draw(&PathElement::new(
                vec![(10, y), (42, y)],
                colour.stroke_width(3),
            ))?;
            area.draw(&Circle::new((26, y), 3, colour.filled()))?;
        }
        area.draw(&Text::new(curve.label.clone(), (50, y - 8), text.clone()))?;
        y += 24;
    }
    if !decor.bands.is_empty() {
        y += 8;
        let grey = RGBColor(215, 215, 215).filled();
        area.draw(&Rectangle::new([(10, y - 8), (42, y + 8)], grey))?;
        area.draw(&Text::new(decor.band_label.clone(), (50, y - 8), text))?;
    }
    Ok(())
}

/// A strip on the chart's x axis: one quantity over x (e.g. the target's range).
fn draw_strip(
    area: &Area<'_>,
    label: &str,
    points: &[(f64, f64)],
    x_range: std::ops::Range<f64>,
    axes: &Axes<'_>,
) -> DrawResult {
    let top = points.iter().map(|p| p.1).fold(1.0f64, f64::max) * 1.1;
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x_range, 0.0..top)?;
    chart
        .configure_mesh()
        .x_desc(axes.x)
        .y_desc(label)
        .y_labels(4)
        .x_label_formatter(&|x| format!("{x:.*}", axes.x_decimals))
        .y_label_formatter(&|y| format!("{y:.0}"))
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 14))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()?;
    chart.draw_series(LineSeries::new(
        points.iter().copied(),
        RGBColor(90, 90, 90).stroke_width(2),
    ))?;
    Ok(())
}
