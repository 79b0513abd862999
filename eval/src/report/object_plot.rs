//! The scene-flow error on every moving object against its range and against its number of
//! sliced points (`plots/objects_epe_by_range.png`, `plots/objects_epe_by_points.png`): per
//! method the mean point EPE of the object scans in each bin.

use std::collections::BTreeMap;
use std::path::Path;

use crate::error::EvalError;
use crate::methods::method::Method;
use crate::report::chart::{Axes, Curve, Decor, draw};
use crate::report::plot::{colour_of, is_variant};
use crate::scene::metrics::MIN_SCORED_SPEED_MPS;
use crate::scene::objects::ObjectScan;

/// The methods drawn: one GP variant of each kind and readout, the baselines, zero flow.
const DRAWN: [Method; 9] = [
    Method::SpgpAll,
    Method::SpgpHetAll,
    Method::SpgpHetPoint,
    Method::Kf,
    Method::Icp,
    Method::KfAuto,
    Method::IcpAuto,
    Method::FullGpAll,
    Method::ZeroFlow,
];

/// What the x axis shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ObjectAxis {
    /// Distance sensor → object centre, 5 m bins.
    Range,
    /// Sliced points on the object, bins of a quarter decade (log10 on the axis).
    Points,
}

impl ObjectAxis {
    /// The bin's centre on the axis for an object scan.
    fn bin(self, object: &ObjectScan) -> Option<f64> {
        match self {
            Self::Range => {
                let range = object.truth.range_m?;
                Some((range / 5.0).floor() * 5.0 + 2.5)
            }
            Self::Points => {
                let points = object.truth.target_points? as f64;
                Some(((points.log10() * 4.0).floor() + 0.5) / 4.0)
            }
        }
    }
}

/// Draws the mean point EPE of the moving objects per bin of `axis`, one curve per method.
pub(crate) fn plot_object_epe(
    objects: &[ObjectScan],
    axis: ObjectAxis,
    path: &Path,
) -> Result<(), EvalError> {
    let mut bins: BTreeMap<Method, BTreeMap<i64, (f64, usize)>> = BTreeMap::new();
    for object in objects {
        if object.truth.speed_mps < MIN_SCORED_SPEED_MPS {
            continue;
        }
        let Some(x) = axis.bin(object) else { continue };
        for (&method, &epe) in &object.point_epe_m {
            if !DRAWN.contains(&method) {
                continue;
            }
            // Keyed by x in thousandths, so bins sort along the axis.
            let bin = bins
                .entry(method)
                .or_default()
                .entry((x * 1e3).round() as i64);
            let (sum, n) = bin.or_default();
            *sum += epe;
            *n += 1;
        }
    }
    let curves = bins
        .into_iter()
        .map(|(method, bins)| Curve {
            label: method.name().to_owned(),
            colour: colour_of(method),
            points: bins
                .into_iter()
                .map(|(x, (sum, n))| Some((x as f64 / 1e3, sum / n as f64)))
                .collect(),
            dashed: is_variant(method),
        })
        .collect();
    let (title, x, x_decimals) = match axis {
        ObjectAxis::Range => (
            "Moving objects: point EPE by range",
            "range of the object (m), 5 m bins",
            0,
        ),
        ObjectAxis::Points => (
            "Moving objects: point EPE by sliced points",
            "log10 of the object's sliced points (1 = 10, 2 = 100, 3 = 1,000)",
            1,
        ),
    };
    let axes = Axes {
        x,
        x_decimals,
        y: "mean point EPE (m per sweep)",
        y_decimals: 2,
        min_pad: 0.02,
    };
    draw(
        path,
        title,
        axes,
        Vec::new(),
        curves,
        Some(0.0),
        &Decor::default(),
    )
}
