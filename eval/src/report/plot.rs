//! Heading and speed over the scans, true and estimated per method (like thesis Figures 4.3-4.17),
//! drawn to PNG with plotters' pure-Rust bitmap backend and the bundled DejaVu Sans font.
//!
//! Headings are unwrapped along the true curve and every estimate is drawn at the true heading
//! plus its wrapped error, so neither curve jumps at ±180°. Speeds above the top edge
//! (3 × the largest true speed + 2 m/s) are clipped to it, so one wild outlier cannot flatten the plot.

use std::path::Path;
use std::sync::OnceLock;

use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

use crate::error::EvalError;
use crate::result::SituationResult;
use patchflow_dataset::wrap_angle_rad;

/// DejaVu Sans (Bitstream Vera licence, see `assets/DejaVu-LICENSE.txt`).
const FONT_TTF: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
pub(crate) const FONT: &str = "sans-serif";
const SIZE_PX: (u32, u32) = (1000, 560);

/// Colour per canonical method slot (tab10), then a few spares.
const PALETTE: [RGBColor; 12] = [
    RGBColor(31, 119, 180),
    RGBColor(23, 190, 207),
    RGBColor(44, 160, 44),
    RGBColor(188, 189, 34),
    RGBColor(214, 39, 40),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(100, 100, 160),
    RGBColor(160, 100, 100),
];

/// Registers the bundled font once; an error names the PNG that needed it.
pub(crate) fn ensure_font(path: &Path) -> Result<(), EvalError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| register_font(FONT, FontStyle::Normal, FONT_TTF).is_ok());
    if ok {
        Ok(())
    } else {
        Err(EvalError::Plot {
            path: path.to_owned(),
            message: "the bundled DejaVu Sans font could not be loaded".into(),
        })
    }
}

/// One curve: (x, value) runs without gaps, so lines break where a method has no estimate.
pub(crate) struct Curve {
    /// Legend label.
    pub label: String,
    /// Line colour.
    pub colour: RGBColor,
    /// Points; `None` breaks the line.
    pub points: Vec<Option<(f64, f64)>>,
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

/// The colour of a method in every plot.
pub(crate) fn colour_of(method: crate::method::Method) -> RGBColor {
    PALETTE[method.slot() % PALETTE.len()]
}

/// The axes of the plots over the scans, values in whole units.
fn scan_axes(y: &str) -> Axes<'_> {
    Axes {
        x: "scan",
        x_decimals: 0,
        y,
        y_decimals: 0,
        min_pad: 1.0,
    }
}

/// Draws `plots/<situation>_heading.png`: true and estimated heading in degrees over the scans.
pub fn plot_heading(situation: &SituationResult, path: &Path) -> Result<(), EvalError> {
    situation.validate()?;
    // Unwrap the truth along the scans.
    let mut truth_deg = Vec::with_capacity(situation.truth.len());
    let mut previous: Option<f64> = None;
    for t in &situation.truth {
        let unwrapped = match previous {
            Some(p) => p + wrap_angle_rad(t.heading_rad - p),
            None => t.heading_rad,
        };
        previous = Some(unwrapped);
        truth_deg.push(unwrapped);
    }
    let curves = method_curves(situation, |scan, e| {
        let t = truth_deg[scan];
        (t + wrap_angle_rad(e.heading_rad - t)).to_degrees()
    });
    let truth_points = truth_deg
        .iter()
        .enumerate()
        .map(|(i, h)| Some((scan_of(situation, i), h.to_degrees())))
        .collect();
    draw(
        path,
        &format!("{}: heading", situation.name),
        scan_axes("heading (°)"),
        truth_points,
        curves,
        None,
    )
}

/// Draws `plots/<situation>_speed.png`: true and estimated speed in m/s over the scans.
pub fn plot_speed(situation: &SituationResult, path: &Path) -> Result<(), EvalError> {
    situation.validate()?;
    let max_truth = situation
        .truth
        .iter()
        .map(|t| t.speed_mps)
        .fold(0.0, f64::max);
    let top = 3.0 * max_truth + 2.0;
    let curves = method_curves(situation, |_, e| e.speed_mps.min(top));
    let truth_points = situation
        .truth
        .iter()
        .enumerate()
        .map(|(i, t)| Some((scan_of(situation, i), t.speed_mps)))
        .collect();
    draw(
        path,
        &format!("{}: speed", situation.name),
        scan_axes("speed (m/s)"),
        truth_points,
        curves,
        Some(0.0),
    )
}

fn scan_of(situation: &SituationResult, index: usize) -> f64 {
    situation
        .truth
        .get(index)
        .map_or(index as f64, |t| t.scan as f64)
}

fn method_curves(
    situation: &SituationResult,
    value: impl Fn(usize, &crate::estimate::MotionEstimate) -> f64,
) -> Vec<Curve> {
    situation
        .methods
        .iter()
        .map(|(method, estimates)| {
            let points = estimates
                .iter()
                .enumerate()
                .map(|(i, e)| e.as_ref().map(|e| (scan_of(situation, i), value(i, e))))
                .filter(|p| p.is_none_or(|(_, v)| v.is_finite()))
                .collect();
            Curve {
                colour: colour_of(*method),
                label: method.name().to_owned(),
                points,
            }
        })
        .collect()
}

/// Draws curves (and a black truth curve, if any) to a PNG.
pub(crate) fn draw(
    path: &Path,
    title: &str,
    axes: Axes<'_>,
    truth: Vec<Option<(f64, f64)>>,
    curves: Vec<Curve>,
    y_floor: Option<f64>,
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
    let (mut x_min, mut x_max) = (0.0f64, 1.0f64);
    let (mut y_min, mut y_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for (x, y) in all {
        x_min = x_min.min(*x);
        x_max = x_max.max(*x);
        y_min = y_min.min(*y);
        y_max = y_max.max(*y);
    }
    if !y_min.is_finite() {
        (y_min, y_max) = (0.0, 1.0);
    }
    // Extra room at the top keeps the legend (upper right) off the curves.
    let pad = ((y_max - y_min) * 0.08).max(axes.min_pad);
    let legend_room = (y_max - y_min).max(axes.min_pad) * 0.35;
    let y_range = y_floor.map_or(y_min - pad, |f| f.min(y_min))..(y_max + pad + legend_room);

    let root = BitMapBackend::new(path, SIZE_PX).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_err(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, (FONT, 24))
        .margin(14)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x_min.min(0.0)..x_max + 1.0, y_range)
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

    let truth_curve = Curve {
        label: "truth".into(),
        colour: BLACK,
        points: truth,
    };
    if truth_curve.points.iter().any(Option::is_some) {
        draw_curve(&mut chart, &truth_curve, 3).map_err(|e| plot_err(&e))?;
    }
    for curve in &curves {
        draw_curve(&mut chart, curve, 2).map_err(|e| plot_err(&e))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, 14))
        .draw()
        .map_err(|e| plot_err(&e))?;
    root.present().map_err(|e| plot_err(&e))
}

type Chart<'a> = ChartContext<
    'a,
    BitMapBackend<'a>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

fn draw_curve(
    chart: &mut Chart<'_>,
    curve: &Curve,
    width: u32,
) -> Result<(), DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>> {
    let style = ShapeStyle {
        color: curve.colour.to_rgba(),
        filled: true,
        stroke_width: width,
    };
    // Lines over runs without gaps.
    for run in curve.points.split(Option::is_none) {
        let run: Vec<(f64, f64)> = run.iter().flatten().copied().collect();
        if run.len() >= 2 {
            chart.draw_series(LineSeries::new(run, style))?;
        }
    }
    // Markers (and the legend entry) on every point.
    let points: Vec<(f64, f64)> = curve.points.iter().flatten().copied().collect();
    let colour = curve.colour;
    chart
        .draw_series(
            points
                .into_iter()
                .map(move |p| Circle::new(p, width + 1, colour.filled())),
        )?
        .label(curve.label.clone())
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 22, y)], colour.stroke_width(3)));
    Ok(())
}
