//! Pictures like the DGPOM paper's Figure 6, one PNG per scenario and method
//! (`plots/occupancy_<scenario>_<method>.png`): one column per figure query time (t = 3 and 5),
//! rows ground truth with the scan's beams, probability of occupancy, and predictive variance,
//! each query point drawn as a square cell of the lattice.

use std::path::Path;

use patchflow_occupancy::{MapFigure, MapMethodId, SequenceScores};
use plotters::prelude::*;

use crate::error::EvalError;
use crate::report::png_file::PngFile;
use crate::report::{FONT, ensure_font};

/// Size of one panel, pixels.
const PANEL_PX: (u32, u32) = (640, 380);

/// Occupied and free cells of the truth, and the beams over it.
const OCCUPIED: RGBColor = RGBColor(31, 80, 180);
const FREE: RGBColor = RGBColor(236, 236, 236);
const BEAM: RGBColor = RGBColor(220, 30, 30);

/// The figure's file name for one scenario and method.
pub(crate) fn figure_file_name(scenario: &str, method: MapMethodId) -> String {
    format!("occupancy_{scenario}_{}.png", method.name().to_lowercase())
}

/// Draws Figure 6 of `method` on `scores`' kept query times to `path`.
pub fn plot_occupancy_figure(
    scores: &SequenceScores,
    method: MapMethodId,
    path: &Path,
) -> Result<(), EvalError> {
    ensure_font(path)?;
    let err = |e: &dyn std::fmt::Display| EvalError::Plot {
        path: path.to_owned(),
        message: e.to_string(),
    };
    let figures: Vec<&MapFigure> = scores
        .figures
        .iter()
        .filter(|f| f.maps.contains_key(&method))
        .collect();
    if figures.is_empty() {
        return Err(EvalError::BadResult {
            situation: scores.name.clone(),
            reason: format!("no map of {method} was kept for figures"),
        });
    }
    let size = (PANEL_PX.0 * figures.len() as u32, PANEL_PX.1 * 3 + 40);
    let png = PngFile::new(path);
    let png_path = png.drawing_path().to_path_buf();
    let root = BitMapBackend::new(&png_path, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let (title, body) = root.split_vertically(40);
    title
        .titled(&format!("{}: {method}", scores.name), (FONT, 24))
        .map_err(|e| err(&e))?;
    let panels = body.split_evenly((3, figures.len()));
    for (column, figure) in figures.iter().enumerate() {
        let map = &figure.maps[&method];
        let t = figure.scan.stamp_secs;
        let truth: Vec<f64> = figure
            .truth
            .iter()
            .map(|&o| f64::from(u8::from(o)))
            .collect();
        draw_panel(
            &panels[column],
            figure,
            &format!("t = {t:.0} s: ground truth and scan"),
            &truth,
            Shade::Truth,
        )
        .map_err(|e| err(&e))?;
        draw_panel(
            &panels[figures.len() + column],
            figure,
            &format!("t = {t:.0} s: probability of occupancy"),
            &map.probability,
            Shade::Scale(0.0, 1.0),
        )
        .map_err(|e| err(&e))?;
        let variance_panel = &panels[2 * figures.len() + column];
        match &map.variance {
            Some(variance) => {
                let lo = variance.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = variance.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                let caption = format!("t = {t:.0} s: predictive variance ({lo:.3} to {hi:.3})");
                draw_panel(
                    variance_panel,
                    figure,
                    &caption,
                    variance,
                    Shade::Scale(lo, hi.max(lo + 1e-12)),
                )
                .map_err(|e| err(&e))?;
            }
            None => {
                variance_panel
                    .titled(
                        &format!("t = {t:.0} s: {method} has no predictive variance"),
                        (FONT, 17),
                    )
                    .map_err(|e| err(&e))?;
            }
        }
    }
    root.present().map_err(|e| err(&e))?;
    png.commit()
}

/// How values become colours.
#[derive(Clone, Copy)]
enum Shade {
    /// 1 occupied (blue), 0 free (light grey); the scan's beams drawn on top.
    Truth,
    /// Viridis from the low to the high end of the range.
    Scale(f64, f64),
}

type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

fn draw_panel(
    area: &Area<'_>,
    figure: &MapFigure,
    caption: &str,
    values: &[f64],
    shade: Shade,
) -> Result<(), DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>> {
    let grid = &figure.grid;
    let half = grid.spacing_m / 2.0;
    let xs = grid.points_m.iter().map(|p| p[0]);
    let ys = grid.points_m.iter().map(|p| p[1]);
    let (x0, x1) = (
        xs.clone().fold(f64::INFINITY, f64::min) - half,
        xs.fold(f64::NEG_INFINITY, f64::max) + half,
    );
    let (y0, y1) = (
        ys.clone().fold(f64::INFINITY, f64::min) - half,
        ys.fold(f64::NEG_INFINITY, f64::max) + half,
    );
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 17))
        .margin(8)
        .x_label_area_size(28)
        .y_label_area_size(36)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .label_style((FONT, 12))
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_label_formatter(&|y| format!("{y:.0}"))
        .draw()?;
    chart.draw_series(grid.points_m.iter().zip(values).map(|(p, &v)| {
        let colour = match shade {
            Shade::Truth if v > 0.5 => OCCUPIED,
            Shade::Truth => FREE,
            Shade::Scale(lo, hi) => viridis((v - lo) / (hi - lo)),
        };
        Rectangle::new(
            [(p[0] - half, p[1] - half), (p[0] + half, p[1] + half)],
            colour.filled(),
        )
    }))?;
    if matches!(shade, Shade::Truth) {
        let [sx, sy] = figure.scan.sensor_m;
        chart.draw_series(figure.scan.beams.iter().map(|b| {
            let colour = if b.hit {
                BEAM.to_rgba()
            } else {
                BEAM.mix(0.35)
            };
            PathElement::new(
                vec![(b.start_m[0], b.start_m[1]), (b.end_m[0], b.end_m[1])],
                ShapeStyle::from(colour).stroke_width(1),
            )
        }))?;
        chart.draw_series(
            figure
                .scan
                .beams
                .iter()
                .filter(|b| b.hit)
                .map(|b| Circle::new((b.end_m[0], b.end_m[1]), 2, BEAM.filled())),
        )?;
        chart.draw_series(std::iter::once(TriangleMarker::new(
            (sx, sy),
            7,
            BLACK.filled(),
        )))?;
    }
    Ok(())
}

/// The viridis colour map at `f` in [0, 1] (five stops, linear between them).
fn viridis(f: f64) -> RGBColor {
    const STOPS: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let f = if f.is_finite() {
        f.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = f * (STOPS.len() - 1) as f64;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let w = x - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    let mix = |p: f64, q: f64| (p + w * (q - p)).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}
