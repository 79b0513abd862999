//! Heading and speed over time, true and estimated per method (like thesis Figures 4.3-4.17),
//! drawn to PNG with plotters' pure-Rust bitmap backend and the bundled DejaVu Sans font: the
//! key beside the data, BEST and AUTO variants dashed over their originals, scans without a GP
//! estimate shaded, the target's range in a strip under the chart.
//!
//! Headings are unwrapped along the true curve and every estimate is drawn at the true heading
//! plus its wrapped error, so neither curve jumps at ±180°. Speeds above the top edge
//! (3 × the largest true speed + 2 m/s) are clipped to it, so one wild outlier cannot flatten the plot.

use std::path::Path;

use plotters::prelude::*;

use crate::error::EvalError;
use crate::methods::method::Method;
use crate::report::chart::{Axes, Curve, Decor, draw};
use crate::scene::result::SituationResult;
use patchflow_dataset::wrap_angle_rad;

/// Colour per canonical method slot (tab10), then a few spares.
const PALETTE: [RGBColor; 19] = [
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
    RGBColor(0, 90, 50),
    RGBColor(200, 0, 120),
    RGBColor(90, 60, 0),
    RGBColor(0, 60, 140),
    RGBColor(120, 180, 60),
    RGBColor(230, 170, 0),
    RGBColor(60, 60, 60),
];

/// The colour of a method in every plot.
pub(crate) fn colour_of(method: Method) -> RGBColor {
    palette_colour(method.slot())
}

/// The `k`-th colour of the one palette of every plot (cycling).
pub(crate) fn palette_colour(k: usize) -> RGBColor {
    PALETTE[k % PALETTE.len()]
}

/// Seconds between scans: the situations' lidar turns at 10 Hz (SPEC §3).
const SCAN_PERIOD_SECS: f64 = 0.1;

/// The axes of the plots over time, values in whole units.
fn time_axes(y: &str) -> Axes<'_> {
    Axes {
        x: "time (s, scans at 10 Hz)",
        x_decimals: 0,
        y,
        y_decimals: 0,
        min_pad: 1.0,
    }
}

/// Whether a method is a variant drawn dashed over its original (BEST over ALL, AUTO over the
/// oracle association).
pub(crate) fn is_variant(method: Method) -> bool {
    let name = method.name();
    name.ends_with("-BEST") || name.ends_with("-AUTO")
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
        time_axes("heading (°)"),
        truth_points,
        curves,
        None,
        &decor(situation),
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
        time_axes("speed (m/s)"),
        truth_points,
        curves,
        Some(0.0),
        &decor(situation),
    )
}

/// Seconds since scan 0 of the truth entry `index`.
fn scan_of(situation: &SituationResult, index: usize) -> f64 {
    let scan = situation
        .truth
        .get(index)
        .map_or(index as f64, |t| t.scan as f64);
    scan * SCAN_PERIOD_SECS
}

/// Grey bands over the scans without an estimate of the headline GP method, and the target's
/// range in a strip under the chart.
fn decor(situation: &SituationResult) -> Decor {
    let headline = [Method::SpgpHetAll, Method::SpgpAll, Method::FullGpAll]
        .into_iter()
        .find(|m| situation.methods.contains_key(m));
    let half = SCAN_PERIOD_SECS / 2.0;
    let bands = match headline.and_then(|m| situation.methods.get(&m)) {
        Some(estimates) => estimates
            .iter()
            .enumerate()
            .filter(|(_, e)| e.is_none())
            .map(|(i, _)| scan_of(situation, i))
            .map(|x| (x - half, x + half))
            .collect(),
        None => Vec::new(),
    };
    let range: Vec<(f64, f64)> = situation
        .truth
        .iter()
        .enumerate()
        .filter_map(|(i, t)| t.range_m.map(|r| (scan_of(situation, i), r)))
        .collect();
    Decor {
        bands,
        band_label: headline.map_or_else(String::new, |m| format!("no {m} estimate")),
        strip: (!range.is_empty()).then(|| ("target range (m)".to_owned(), range)),
    }
}

fn method_curves(
    situation: &SituationResult,
    value: impl Fn(usize, &crate::methods::estimate::MotionEstimate) -> f64,
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
                dashed: is_variant(*method),
            }
        })
        .collect()
}
