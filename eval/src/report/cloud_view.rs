//! One sweep's point cloud from above, in the world frame: static points coloured by their
//! SemanticKITTI class, moving points (classes 252-259) by the direction of their true flow on a
//! colour wheel shown in the key, so the motion the estimators should find is visible.

use patchflow_dataset::{StaticObstacle, Sweep};
use plotters::prelude::*;

use crate::report::font::FONT;
use crate::report::world_chart::{Area, DrawResult, WorldChart, footprint};

/// Class colours: (SemanticKITTI ids, colour, key label).
const CLASSES: [(&[u16], RGBColor, &str); 8] = [
    (
        &[40, 44, 48, 49, 72],
        RGBColor(215, 215, 215),
        "road, sidewalk, terrain",
    ),
    (&[50, 51, 52], RGBColor(150, 110, 80), "buildings, walls"),
    (&[70, 71], RGBColor(80, 160, 80), "vegetation"),
    (
        &[80, 81, 99],
        RGBColor(40, 40, 40),
        "poles, signs, other objects",
    ),
    (
        &[10, 13, 15, 18, 20],
        RGBColor(90, 140, 210),
        "parked vehicles",
    ),
    (
        &[30, 31, 32],
        RGBColor(170, 90, 200),
        "standing people, cyclists",
    ),
    (&[0, 1], RGBColor(175, 175, 175), "unlabelled"),
    (&[], RGBColor(120, 120, 120), "other"),
];

/// The hue of a flow direction (world frame, radians): a full turn of the colour wheel.
pub(crate) fn direction_colour(direction_rad: f64) -> RGBColor {
    let hue = direction_rad.rem_euclid(std::f64::consts::TAU) / std::f64::consts::TAU;
    let (r, g, b) = hsv(hue, 0.9, 0.85);
    RGBColor(r, g, b)
}

fn hsv(h: f64, s: f64, v: f64) -> (u8, u8, u8) {
    let i = (h * 6.0).floor();
    let f = h * 6.0 - i;
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - f * s), v * (1.0 - (1.0 - f) * s));
    let (r, g, b) = match (i as i64).rem_euclid(6) {
        0 => (v, t, p),
        1 => (q, v, p),
        2 => (p, v, t),
        3 => (p, q, v),
        4 => (t, p, v),
        _ => (v, p, q),
    };
    let byte = |x: f64| (x * 255.0).round().clamp(0.0, 255.0) as u8;
    (byte(r), byte(g), byte(b))
}

fn class_colour(semantic: u16) -> RGBColor {
    CLASSES
        .iter()
        .find(|(ids, _, _)| ids.contains(&semantic))
        .map_or(CLASSES[7].1, |c| c.1)
}

/// Draws the sweep's points (static ones first, moving ones larger on top), the static
/// structures' outlines, and the key with the class colours and the flow-direction wheel.
pub(crate) fn draw_cloud(
    chart: &mut WorldChart<'_>,
    key: &Area<'_>,
    sweep: &Sweep,
    structures: &[StaticObstacle],
) -> DrawResult {
    let (x_range, y_range) = (chart.x_range(), chart.y_range());
    let inside = |p: &(f64, f64)| x_range.contains(&p.0) && y_range.contains(&p.1);
    let mut still = Vec::new();
    let mut moving = Vec::new();
    for i in 0..sweep.len() {
        let p = sweep.point_in_world(i);
        let xy = (p.x, p.y);
        if !inside(&xy) {
            continue;
        }
        let label = sweep.labels[i];
        if label.is_moving() {
            let [vx, vy, _] = sweep.flow_in_world_mps[i];
            moving.push((xy, direction_colour(f64::from(vy).atan2(f64::from(vx)))));
        } else {
            still.push((xy, class_colour(label.semantic())));
        }
    }
    chart.draw_series(still.into_iter().map(|(p, c)| Pixel::new(p, c)))?;
    for o in structures {
        let mut corners = footprint(o.centre_m, o.size_m, o.yaw_rad);
        corners.push(corners[0]);
        chart.draw_series(std::iter::once(PathElement::new(
            corners,
            RGBColor(150, 110, 80).mix(0.5).stroke_width(1),
        )))?;
    }
    chart.draw_series(
        moving
            .into_iter()
            .map(|(p, c)| Circle::new(p, 2, c.filled())),
    )?;
    let ego = (
        sweep.world_from_sensor.translation.x,
        sweep.world_from_sensor.translation.y,
    );
    chart.draw_series(std::iter::once(TriangleMarker::new(ego, 8, BLACK.filled())))?;
    draw_key(key)
}

fn draw_key(key: &Area<'_>) -> DrawResult {
    let text = TextStyle::from((FONT, 14)).color(&BLACK);
    let mut y = 50;
    for (_, colour, label) in CLASSES.iter().take(7) {
        key.draw(&Rectangle::new([(10, y - 6), (30, y + 6)], colour.filled()))?;
        key.draw(&Text::new(label.to_string(), (38, y - 8), text.clone()))?;
        y += 24;
    }
    key.draw(&TriangleMarker::new((20, y), 7, BLACK.filled()))?;
    key.draw(&Text::new("ego car (sensor)", (38, y - 8), text.clone()))?;
    y += 40;
    key.draw(&Text::new(
        "moving points: true flow",
        (10, y - 8),
        text.clone(),
    ))?;
    key.draw(&Text::new(
        "direction (world frame)",
        (10, y + 10),
        text.clone(),
    ))?;
    // The colour wheel: direction → colour, +x to the right, +y up.
    let (cx, cy, r) = (110, y + 100, 55);
    for k in 0..72 {
        let a = k as f64 / 72.0 * std::f64::consts::TAU;
        for radius in (r - 16)..=r {
            let p = (
                cx + (f64::from(radius) * a.cos()).round() as i32,
                cy - (f64::from(radius) * a.sin()).round() as i32,
            );
            key.draw(&Circle::new(p, 2, direction_colour(a).filled()))?;
        }
    }
    for (label, dx, dy) in [
        ("+x", r + 8, -8),
        ("+y", -8, -r - 26),
        ("−x", -r - 30, -8),
        ("−y", -8, r + 6),
    ] {
        key.draw(&Text::new(label, (cx + dx, cy + dy), text.clone()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn opposite_flow_directions_get_clearly_different_colours() {
        let (a, b) = (
            direction_colour(0.0),
            direction_colour(std::f64::consts::PI),
        );
        let distance = (i32::from(a.0) - i32::from(b.0)).abs()
            + (i32::from(a.1) - i32::from(b.1)).abs()
            + (i32::from(a.2) - i32::from(b.2)).abs();
        assert!(distance > 200, "{a:?} vs {b:?}");
        assert_eq!(
            direction_colour(0.0),
            direction_colour(std::f64::consts::TAU)
        );
    }

    #[test]
    fn parked_cars_and_buildings_have_their_own_colours() {
        assert_ne!(class_colour(10), class_colour(50));
        assert_eq!(class_colour(4242), CLASSES[7].1);
    }
}
