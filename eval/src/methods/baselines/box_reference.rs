//! Which point of a moving object a `GP-KF` track measures while the whole of it is in view: the
//! centre of a box aligned with the track's heading, placed by the faces the sensor sees.
//!
//! The centroid of a cluster is weighted by the density of its points, and a lidar samples the
//! nearest part of an object most densely: as a bus passes beside the sensor the nearest part runs
//! back along it at the closing speed and drags the centroid with it; a car seen from behind shows
//! more of its side as it drives away, and its centroid slides along it (docs/estimator.md, "Stop
//! 57"). Lidar trackers measure a point fixed on the object instead, a corner or face of a box
//! fitted to it (the L-shape fit of Zhang et al. 2017, "Efficient L-shape fitting for vehicle
//! detection using laser scanners"). Here the box is aligned with the track's heading; along each
//! of its two axes the face the sensor faces places it (the rear of a car driving away, the front
//! of one coming towards the sensor, or, where the sensor is level with the object and sees the
//! whole of that side, the middle of both ends), and the box's centre lies half the largest extent
//! seen on that axis beyond it. The centre rather than the face, because a point away from the
//! centre moves faster or slower than the object where it turns (a van's front 2.5 m ahead of its
//! middle at 0.5 rad/s: 1.2 m/s). Where the face or the extent changes, the tracker moves the
//! track's state by the offset between the two points measured in that scan (`tracker`), so the
//! change of reference never reads as motion, as `reference_point`'s anchor does.

/// Which face of the box along one axis places it: its low end, the middle of both, its high end.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Face {
    /// The smallest coordinate along the axis faces the sensor.
    Low,
    /// The sensor is level with the object on this axis: the middle of both ends.
    Middle,
    /// The largest coordinate faces the sensor.
    High,
}

/// The box a track measures its object by: which face places it along and across its heading, and
/// how large it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxReference {
    /// The face the sensor sees along the heading and across it (to its left).
    faces: [Face; 2],
    /// The largest extent seen along and across, metres.
    extent_m: [f64; 2],
}

/// A box's two axes for a heading: along it and to its left.
fn axes(heading_rad: f64) -> [[f64; 2]; 2] {
    let (sin, cos) = heading_rad.sin_cos();
    [[cos, sin], [-sin, cos]]
}

fn dot(p: [f64; 2], axis: [f64; 2]) -> f64 {
    p[0] * axis[0] + p[1] * axis[1]
}

/// The smallest and largest coordinate of the points on `axis`; `None` for no points.
fn span(points_xy: &[[f64; 2]], axis: [f64; 2]) -> Option<[f64; 2]> {
    let first = dot(*points_xy.first()?, axis);
    Some(points_xy[1..].iter().fold([first, first], |[lo, hi], &p| {
        [lo.min(dot(p, axis)), hi.max(dot(p, axis))]
    }))
}

impl BoxReference {
    /// The box of `points_xy` seen from `sensor_xy` with its axes along `heading_rad`, after
    /// `previous` (the track's box last scan, whose extents it keeps); `None` for no points.
    pub fn facing(
        points_xy: &[[f64; 2]],
        sensor_xy: [f64; 2],
        heading_rad: f64,
        previous: Option<&Self>,
    ) -> Option<Self> {
        let mut faces = [Face::Middle; 2];
        let mut now = [0.0; 2];
        for (k, axis) in axes(heading_rad).into_iter().enumerate() {
            let [lo, hi] = span(points_xy, axis)?;
            let sensor = dot(sensor_xy, axis);
            faces[k] = if sensor < lo {
                Face::Low
            } else if sensor > hi {
                Face::High
            } else {
                Face::Middle
            };
            now[k] = hi - lo;
        }
        let seen = previous.map_or([0.0; 2], |p| p.extent_m);
        Some(Self {
            faces,
            extent_m: [seen[0].max(now[0]), seen[1].max(now[1])],
        })
    }

    /// The centre of this box on `points_xy` with its axes along `heading_rad`, world frame:
    /// along each axis the face it is placed by, plus or minus half its extent; `None` for no
    /// points.
    pub fn point(&self, points_xy: &[[f64; 2]], heading_rad: f64) -> Option<[f64; 2]> {
        let axes = axes(heading_rad);
        let mut xy = [0.0; 2];
        for (k, axis) in axes.into_iter().enumerate() {
            let [lo, hi] = span(points_xy, axis)?;
            let centre = match self.faces[k] {
                Face::Low => lo + 0.5 * self.extent_m[k],
                Face::Middle => 0.5 * (lo + hi),
                Face::High => hi - 0.5 * self.extent_m[k],
            };
            xy = [xy[0] + centre * axis[0], xy[1] + centre * axis[1]];
        }
        Some(xy)
    }
}

/// How far from `centroid_xy` the farthest of `points_xy` lies, metres (0 for no points).
pub fn reach_m(points_xy: &[[f64; 2]], centroid_xy: [f64; 2]) -> f64 {
    let far_sq = points_xy.iter().fold(0.0, |far: f64, p| {
        let (dx, dy) = (p[0] - centroid_xy[0], p[1] - centroid_xy[1]);
        far.max(dx * dx + dy * dy)
    });
    far_sq.sqrt()
}

/// How far from a cluster's centroid the point [`measured_centre`] gives can lie, for a cluster
/// whose points lie within `cluster_reach_m` of its centroid ([`reach_m`]): along each of the
/// box's axes its centre lies within half the box's extent beyond the cluster's span, and the
/// span within the reach of the centroid; without a box (or heading) the point is the centroid.
pub fn measured_reach_m(reference: Option<&BoxReference>, cluster_reach_m: f64) -> f64 {
    reference.map_or(0.0, |r| {
        let [along, across] = r.extent_m.map(|e| cluster_reach_m + 0.5 * e);
        (along * along + across * across).sqrt()
    })
}

/// The point of a cluster a track with the box `reference` measures: the box's centre on the
/// cluster's points `outline_xy` with its axes along `heading_rad`; without a box, a heading or
/// points, the cluster's centroid.
pub fn measured_centre(
    reference: Option<&BoxReference>,
    heading_rad: Option<f64>,
    outline_xy: &[[f64; 2]],
    centroid_xy: [f64; 2],
) -> [f64; 2] {
    reference
        .zip(heading_rad)
        .and_then(|(r, h)| r.point(outline_xy, h))
        .unwrap_or(centroid_xy)
}

/// The box a track measures its object by from the next scan on, fitted to this scan's cluster
/// (`outline_xy`, `centroid_xy`) with its axes along `heading_rad` after the track's box so far
/// (`previous`), and the point it measures on this cluster: the box's centre, or without a
/// heading (an object that does not move) or points, no box and the centroid. The tracker moves
/// the track's state by that point less the one it measured this scan.
pub fn next_box(
    previous: Option<&BoxReference>,
    heading_rad: Option<f64>,
    outline_xy: &[[f64; 2]],
    sensor_xy: [f64; 2],
    centroid_xy: [f64; 2],
) -> (Option<BoxReference>, [f64; 2]) {
    let next = heading_rad.and_then(|h| BoxReference::facing(outline_xy, sensor_xy, h, previous));
    let centre = measured_centre(next.as_ref(), heading_rad, outline_xy, centroid_xy);
    (next, centre)
}

#[cfg(test)]
#[path = "box_reference_tests.rs"]
mod tests;
