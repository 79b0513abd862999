//! The bird's-eye view of a sequence: static structures, the ego path, every actor's path with
//! the target highlighted, the actors' boxes and range rings around the ego car at one sweep.

use std::collections::BTreeMap;

use patchflow_dataset::{StaticObstacle, Sweep};
use plotters::prelude::*;

use crate::report::font::FONT;
use crate::report::world_chart::{ActorPath, Area, DrawResult, RINGS_M, WorldChart, footprint};

/// Colour of the target.
pub(crate) const TARGET: RGBColor = RGBColor(214, 39, 40);
const EGO: RGBColor = RGBColor(20, 20, 20);
const ACTOR: RGBColor = RGBColor(31, 119, 180);
const STRUCTURE: RGBColor = RGBColor(150, 150, 150);

/// Draws the view onto `chart` and its key onto `key`.
pub(crate) fn draw_birds_eye(
    chart: &mut WorldChart<'_>,
    key: &Area<'_>,
    structures: &[StaticObstacle],
    ego: &[(f64, f64)],
    paths: &BTreeMap<u16, ActorPath>,
    shown: &Sweep,
) -> DrawResult {
    chart.draw_series(structures.iter().map(|o| {
        Polygon::new(
            footprint(o.centre_m, o.size_m, o.yaw_rad),
            STRUCTURE.mix(0.7).filled(),
        )
    }))?;
    let centre = (
        shown.world_from_sensor.translation.x,
        shown.world_from_sensor.translation.y,
    );
    for r in RINGS_M {
        let ring: Vec<(f64, f64)> = (0..=96)
            .map(|k| {
                let a = k as f64 / 96.0 * std::f64::consts::TAU;
                (centre.0 + r * a.cos(), centre.1 + r * a.sin())
            })
            .collect();
        chart.draw_series(DashedLineSeries::new(
            ring,
            6,
            5,
            RGBColor(120, 120, 120).stroke_width(1),
        ))?;
        chart.draw_series(std::iter::once(Text::new(
            format!("{r:.0} m"),
            (centre.0 + r * 0.71, centre.1 + r * 0.71),
            (FONT, 13).into_font().color(&RGBColor(90, 90, 90)),
        )))?;
    }
    for path in paths.values().filter(|p| !p.target) {
        chart.draw_series(LineSeries::new(path.points.clone(), ACTOR.stroke_width(2)))?;
    }
    chart.draw_series(LineSeries::new(ego.to_vec(), EGO.stroke_width(3)))?;
    for path in paths.values().filter(|p| p.target) {
        chart.draw_series(LineSeries::new(path.points.clone(), TARGET.stroke_width(4)))?;
        if let Some(&start) = path.points.first() {
            chart.draw_series(std::iter::once(Circle::new(start, 5, TARGET.filled())))?;
        }
    }
    for o in &shown.objects {
        let colour = if o.target { TARGET } else { ACTOR };
        let mut corners = footprint(o.centre_m, o.size_m, o.yaw_rad);
        corners.push(corners[0]);
        chart.draw_series(std::iter::once(PathElement::new(
            corners,
            colour.stroke_width(2),
        )))?;
    }
    chart.draw_series(std::iter::once(TriangleMarker::new(
        centre,
        8,
        EGO.filled(),
    )))?;
    let rows: [(&str, RGBColor, u32); 5] = [
        ("ego path (▲ at the sweep)", EGO, 3),
        ("target path (● start)", TARGET, 4),
        ("other actors' paths", ACTOR, 2),
        ("range rings 10/20/40 m", RGBColor(120, 120, 120), 1),
        ("static structures", STRUCTURE, 10),
    ];
    draw_line_key(key, &rows)
}

/// Key rows of a line (or a filled block for width ≥ 10) and a text each.
pub(crate) fn draw_line_key(key: &Area<'_>, rows: &[(&str, RGBColor, u32)]) -> DrawResult {
    let text = TextStyle::from((FONT, 14)).color(&BLACK);
    for (k, (label, colour, width)) in rows.iter().enumerate() {
        let y = 50 + 26 * k as i32;
        if *width >= 10 {
            key.draw(&Rectangle::new(
                [(10, y - 6), (40, y + 6)],
                colour.mix(0.7).filled(),
            ))?;
        } else {
            key.draw(&PathElement::new(
                vec![(10, y), (40, y)],
                colour.stroke_width(*width),
            ))?;
        }
        key.draw(&Text::new(label.to_string(), (48, y - 8), text.clone()))?;
    }
    Ok(())
}
