//! DGPOM's pictures: the motion map like the paper's Figure 5 (left, the training run's motion
//! clusters with their velocities; right, the learned velocity field Υ as a quiver plot over the
//! scene, shaded by the error field ε), and the AUC against the time since the last observation
//! like its Figure 10 (mean over start times, ± 1 standard deviation bars).

use std::path::Path;

use patchflow_occupancy::{AheadScores, ClusterKind, MotionField, MotionMap};
use plotters::prelude::*;

use crate::error::EvalError;
use crate::report::png_file::PngFile;
use crate::report::{FONT, ensure_font};

/// Seconds of motion an arrow shows (a 2 m/s car gets a 1.6 m arrow).
const ARROW_SECS: f64 = 0.8;
/// Spacing of the quiver plot's arrows, metres.
const QUIVER_M: f64 = 1.5;

const ARRIVED: RGBColor = RGBColor(215, 48, 39);
const VACATED: RGBColor = RGBColor(69, 117, 180);
const STATIONARY: RGBColor = RGBColor(170, 170, 170);

/// The motion map's file name for one scenario.
pub(crate) fn motion_map_file_name(scenario: &str) -> String {
    format!("occupancy_{scenario}_motion_map.png")
}

/// The predicting-ahead figure's file name for one scenario.
pub(crate) fn ahead_file_name(scenario: &str) -> String {
    format!("occupancy_{scenario}_ahead.png")
}

fn plot_error(path: &Path) -> impl Fn(&dyn std::fmt::Display) -> EvalError + '_ {
    move |e| EvalError::Plot {
        path: path.to_owned(),
        message: e.to_string(),
    }
}

/// Draws Figure 5 of `map` (learned on `scenario`'s training run) to `path`.
pub fn plot_motion_map(scenario: &str, map: &MotionMap, path: &Path) -> Result<(), EvalError> {
    ensure_font(path)?;
    let err = plot_error(path);
    let raster = &map.raster;
    let x = (
        raster.origin_m[0],
        raster.origin_m[0] + (raster.size[0] - 1) as f64 * raster.step_m,
    );
    let y = (
        raster.origin_m[1],
        raster.origin_m[1] + (raster.size[1] - 1) as f64 * raster.step_m,
    );
    let panel_w = 760u32;
    let panel_h = ((panel_w as f64 - 50.0) * (y.1 - y.0) / (x.1 - x.0)) as u32 + 70;
    let png = PngFile::new(path);
    let png_path = png.drawing_path().to_path_buf();
    let root = BitMapBackend::new(&png_path, (2 * panel_w, panel_h + 40)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let (title, body) = root.split_vertically(40);
    title
        .titled(
            &format!("{scenario}: DGPOM motion map from the training run"),
            (FONT, 24),
        )
        .map_err(|e| err(&e))?;
    let (left, right) = body.split_horizontally(panel_w);
    // (a) Motion clusters: cells coloured by kind, an arrow per moving cluster.
    let mut a = scene_chart(
        &left,
        (x, y),
        "motion clusters: arrived (red), vacated (blue), stationary (grey); velocity arrows",
    )
    .map_err(|e| err(&e))?;
    let half = 0.25;
    for c in &map.clusters {
        let colour = match c.kind {
            ClusterKind::Arrived => ARRIVED,
            ClusterKind::Vacated => VACATED,
            ClusterKind::Stationary => STATIONARY,
        };
        a.draw_series(c.cells_m.iter().map(|p| {
            Rectangle::new(
                [(p[0] - half, p[1] - half), (p[0] + half, p[1] + half)],
                colour.mix(0.5).filled(),
            )
        }))
        .map_err(|e| err(&e))?;
    }
    for c in map
        .clusters
        .iter()
        .filter(|c| c.kind != ClusterKind::Stationary)
    {
        a.draw_series(arrow(c.centroid_m, c.velocity_mps, BLACK))
            .map_err(|e| err(&e))?;
    }
    // (b) Υ as arrows on a lattice, over ε as grey shading (darker = larger error).
    let mut b = scene_chart(
        &right,
        (x, y),
        "learned velocity field Υ (arrows: 0.8 s of motion) over its error ε (grey)",
    )
    .map_err(|e| err(&e))?;
    let nodes = raster.nodes();
    let eps_max = nodes.iter().map(|&p| map.error_mps(p)).fold(1e-9, f64::max);
    let h = raster.step_m / 2.0;
    b.draw_series(nodes.iter().map(|&p| {
        let shade = 255.0 - 120.0 * (map.error_mps(p) / eps_max);
        let g = shade.round().clamp(0.0, 255.0) as u8;
        Rectangle::new(
            [(p[0] - h, p[1] - h), (p[0] + h, p[1] + h)],
            RGBColor(g, g, g).filled(),
        )
    }))
    .map_err(|e| err(&e))?;
    let columns = ((x.1 - x.0) / QUIVER_M) as usize + 1;
    let rows = ((y.1 - y.0) / QUIVER_M) as usize + 1;
    for r in 0..rows {
        for c in 0..columns {
            let p = [x.0 + c as f64 * QUIVER_M, y.0 + r as f64 * QUIVER_M];
            let v = map.velocity_mps(p);
            b.draw_series(arrow(p, v, RGBColor(20, 40, 160)))
                .map_err(|e| err(&e))?;
        }
    }
    root.present().map_err(|e| err(&e))?;
    png.commit()
}

/// Draws the AUC against the time since the last observation (Figure 10) to `path`.
pub fn plot_ahead(scenario: &str, scores: &AheadScores, path: &Path) -> Result<(), EvalError> {
    ensure_font(path)?;
    let err = plot_error(path);
    let stats = scores.mean_std();
    let x_max = scores.seconds_ahead.last().copied().unwrap_or(1.0).max(1.0) + 0.5;
    let png = PngFile::new(path);
    let png_path = png.drawing_path().to_path_buf();
    let root = BitMapBackend::new(&png_path, (720, 480)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!(
                "{scenario}: {} predicting ahead (start scans {:?})",
                scores.method, scores.start_scans
            ),
            (FONT, 18),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(-0.5..x_max, 0.5..1.0)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc("time since the last observation (s)")
        .y_desc("ROC AUC")
        .label_style((FONT, 13))
        .draw()
        .map_err(|e| err(&e))?;
    let points: Vec<(f64, f64, f64)> = scores
        .seconds_ahead
        .iter()
        .zip(&stats)
        .map(|(&t, &(m, s))| (t, m, s))
        .collect();
    chart
        .draw_series(LineSeries::new(points.iter().map(|p| (p.0, p.1)), &BLUE))
        .map_err(|e| err(&e))?;
    chart
        .draw_series(points.iter().flat_map(|&(t, m, s)| {
            let (lo, hi) = ((m - s).max(0.5), (m + s).min(1.0));
            let w = 0.08;
            [
                PathElement::new(vec![(t, lo), (t, hi)], BLUE),
                PathElement::new(vec![(t - w, lo), (t + w, lo)], BLUE),
                PathElement::new(vec![(t - w, hi), (t + w, hi)], BLUE),
            ]
        }))
        .map_err(|e| err(&e))?;
    chart
        .draw_series(
            points
                .iter()
                .map(|&(t, m, _)| Circle::new((t, m), 4, BLUE.filled())),
        )
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    png.commit()
}

type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;
type SceneChart<'a, 'b> = ChartContext<
    'a,
    BitMapBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;
type DrawResult<T> =
    Result<T, DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>>;

/// A panel over the scene's extent, metres on both axes.
fn scene_chart<'a, 'b>(
    area: &'a Area<'b>,
    (x, y): ((f64, f64), (f64, f64)),
    caption: &str,
) -> DrawResult<SceneChart<'a, 'b>> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 17))
        .margin(8)
        .x_label_area_size(28)
        .y_label_area_size(36)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .label_style((FONT, 12))
        .draw()?;
    Ok(chart)
}

/// An arrow from `p` along `v_mps` (ARROW_SECS of motion), or a dot where `v` is tiny.
fn arrow(p: [f64; 2], v_mps: [f64; 2], colour: RGBColor) -> Vec<PathElement<(f64, f64)>> {
    let (dx, dy) = (v_mps[0] * ARROW_SECS, v_mps[1] * ARROW_SECS);
    let len = dx.hypot(dy);
    let style = ShapeStyle::from(colour).stroke_width(1);
    if len < 0.08 {
        return vec![PathElement::new(
            vec![(p[0] - 0.04, p[1]), (p[0] + 0.04, p[1])],
            style,
        )];
    }
    let tip = (p[0] + dx, p[1] + dy);
    let (ux, uy) = (dx / len, dy / len);
    let head = (0.35 * len).min(0.4);
    let wing = |s: f64| {
        (
            tip.0 - head * (ux * 0.866 - s * uy * 0.5),
            tip.1 - head * (uy * 0.866 + s * ux * 0.5),
        )
    };
    vec![
        PathElement::new(vec![(p[0], p[1]), tip], style),
        PathElement::new(vec![wing(1.0), tip, wing(-1.0)], style),
    ]
}
