//! Which point of an object a track measures: its centroid, or, while a nearer object hides one
//! of its ends, its visible end plus an offset (an anchor point).
//!
//! The centroid of what the lidar sees moves with the object only while the same part of it is
//! seen. A truck coming out from behind a parked car shows more of itself every scan while its
//! hidden end stays at the parked car's edge, so its centroid moves at about half its speed; a
//! centroid filter reads it slow for as long as the emergence lasts and long after (the unseen
//! crossing truck: 4.4-6.6 m/s for 7, docs/estimator.md "Stop 49"). Lidar trackers measure a
//! point fixed on the object instead, a visible corner or end of a box fitted to it (e.g. the
//! L-shape fit of Zhang et al. 2017, "Efficient L-shape fitting for vehicle detection using
//! laser scanners"). Here, when one end of a cluster is hidden (`RangeProfile::ends`) the track
//! measures the other end plus the offset of its own position from that end in that scan; when
//! the whole object shows again, the track's state moves by the offset between the two points
//! measured in that scan, so the change of reference never reads as motion.

use patchflow_learn::ObjectEnd;

/// The least distance between a cluster's two ends for its track to anchor on one of them,
/// metres. A cluster of a point or two has its ends at its centroid; a track anchored there would
/// take any larger cluster one of whose ends comes near it (a fragment's track taking the whole
/// truck it broke off from).
pub const MIN_ANCHOR_EXTENT_M: f64 = 1.0;

/// The least speed of a track for it to anchor on its object's visible end, m/s. A standing
/// object's centroid moves only as a passing car hides more or less of it, for a scan or two; an
/// anchored track of a parked car would take the passing car's cluster whenever one of its ends
/// came near the parked car's.
pub const MIN_ANCHOR_SPEED_MPS: f64 = 2.0;

/// A track's reference while an end of its object is hidden: the visible end `side` (0 the end of
/// smallest bearing, 1 of largest) plus `offset_xy`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anchor {
    /// Which end of the cluster the track measures: 0 smallest bearing, 1 largest.
    side: usize,
    /// The track's reference point relative to that end, world frame, metres.
    offset_xy: [f64; 2],
    /// Where the centroid lay relative to the reference point in the last scan that showed the
    /// anchored end: what a cluster whose anchored end is hidden is measured by.
    centroid_offset_xy: [f64; 2],
}

impl Anchor {
    /// The anchored end plus the offset, on a cluster with these ends; `None` when the cluster's
    /// ends are not known or that end is hidden now.
    fn point(&self, ends: Option<&[ObjectEnd; 2]>) -> Option<[f64; 2]> {
        let end = ends?[self.side];
        (!end.hidden).then(|| add(end.xy, self.offset_xy))
    }
}

/// The point of a cluster a track with `anchor` measures (and gates): its centroid; for an
/// anchored track its anchored end plus the offset, or, where that end is hidden now, its
/// centroid less the centroid's last offset from the reference.
pub fn measured_point(
    anchor: Option<&Anchor>,
    centroid_xy: [f64; 2],
    ends: Option<&[ObjectEnd; 2]>,
) -> [f64; 2] {
    match anchor {
        None => centroid_xy,
        Some(anchor) => anchor
            .point(ends)
            .unwrap_or_else(|| sub(centroid_xy, anchor.centroid_offset_xy)),
    }
}

/// What the track does after taking a cluster: its reference for the next scan and how far its
/// state's position moves to it (zero but where the reference changes back to the centroid).
///
/// `reference_xy` is the track's state after it measured the cluster ([`measured_point`]).
pub fn next_reference(
    anchor: Option<Anchor>,
    centroid_xy: [f64; 2],
    ends: Option<&[ObjectEnd; 2]>,
    reference_xy: [f64; 2],
) -> (Option<Anchor>, [f64; 2]) {
    if let Some(anchor) = anchor {
        return match anchor.point(ends) {
            // The anchored end is hidden now (the object seen through a gap, or its other end
            // coming out): back to the centroid, by where it lay from the reference last scan.
            None => (None, anchor.centroid_offset_xy),
            Some(point) if ends.is_some_and(|e| !e[0].hidden && !e[1].hidden) => {
                // The whole object shows: back to its centroid, by the offset measured now.
                (None, sub(centroid_xy, point))
            }
            Some(point) => {
                let centroid_offset_xy = sub(centroid_xy, point);
                let anchor = Anchor {
                    centroid_offset_xy,
                    ..anchor
                };
                (Some(anchor), [0.0, 0.0])
            }
        };
    }
    let Some(ends) = ends else {
        return (None, [0.0, 0.0]);
    };
    let extent_m = (ends[1].xy[0] - ends[0].xy[0]).hypot(ends[1].xy[1] - ends[0].xy[1]);
    match (ends[0].hidden, ends[1].hidden) {
        // One end hidden: the track takes the visible end from this scan's reference on.
        (true, false) | (false, true) if extent_m >= MIN_ANCHOR_EXTENT_M => {
            let side = usize::from(ends[0].hidden);
            let anchor = Anchor {
                side,
                offset_xy: sub(reference_xy, ends[side].xy),
                centroid_offset_xy: sub(centroid_xy, reference_xy),
            };
            (Some(anchor), [0.0, 0.0])
        }
        // No end or both hidden (seen through a gap), or a short cluster: the centroid.
        _ => (None, [0.0, 0.0]),
    }
}

fn add(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn end(x: f64, hidden: bool) -> ObjectEnd {
        ObjectEnd {
            xy: [x, 10.0],
            hidden,
        }
    }

    fn anchored(side: usize, offset_x: f64, centroid_offset_x: f64) -> Anchor {
        Anchor {
            side,
            offset_xy: [offset_x, 0.0],
            centroid_offset_xy: [centroid_offset_x, 0.0],
        }
    }

    #[test]
    fn a_track_without_an_anchor_measures_the_centroid() {
        let ends = [end(0.0, true), end(4.0, false)];
        assert_eq!(measured_point(None, [2.0, 10.0], Some(&ends)), [2.0, 10.0]);
    }

    #[test]
    fn a_hidden_end_anchors_the_track_on_the_visible_one_at_this_scans_reference() {
        let ends = [end(0.0, true), end(4.0, false)];
        let (anchor, shift) = next_reference(None, [2.0, 10.0], Some(&ends), [2.1, 10.0]);
        let a = anchor.unwrap();
        assert_eq!(a.side, 1);
        assert!((a.offset_xy[0] + 1.9).abs() < 1e-12 && a.offset_xy[1].abs() < 1e-12);
        let c = a.centroid_offset_xy;
        assert!((c[0] + 0.1).abs() < 1e-12 && c[1].abs() < 1e-12, "{c:?}");
        assert_eq!(shift, [0.0, 0.0]);
        // The next scan's visible end moved 0.7 m; so does the point measured.
        let later = [end(0.0, true), end(4.7, false)];
        let point = measured_point(anchor.as_ref(), [2.35, 10.0], Some(&later));
        assert!((point[0] - 2.8).abs() < 1e-12 && (point[1] - 10.0).abs() < 1e-12);
    }

    #[test]
    fn an_object_coming_out_from_behind_another_moves_its_measured_point_at_its_own_speed() {
        // A truck emerges at 0.7 m per scan: its hidden end stays at the occluder's edge (x = 0),
        // its visible end advances. The centroid moves 0.35 m per scan, the measured point 0.7 m.
        let mut anchor = None;
        let mut points = Vec::new();
        for k in 0..5 {
            let front = 2.0 + 0.7 * k as f64;
            let ends = [end(0.0, true), end(front, false)];
            let centroid = [front / 2.0, 10.0];
            let point = measured_point(anchor.as_ref(), centroid, Some(&ends));
            points.push(point[0]);
            anchor = next_reference(anchor, centroid, Some(&ends), point).0;
        }
        for pair in points.windows(2) {
            assert!((pair[1] - pair[0] - 0.7).abs() < 1e-12, "{points:?}");
        }
    }

    #[test]
    fn the_whole_object_in_view_returns_the_track_to_its_centroid_by_the_measured_offset() {
        // Anchored on the front end 1 m behind it; now whole, 8 m long, front at 8.0: the
        // measured point is 7.0, the centroid 4.0.
        let ends = [end(0.0, false), end(8.0, false)];
        let anchor = Some(anchored(1, -1.0, -0.5));
        assert_eq!(
            measured_point(anchor.as_ref(), [4.0, 10.0], Some(&ends)),
            [7.0, 10.0]
        );
        let (anchor, shift) = next_reference(anchor, [4.0, 10.0], Some(&ends), [7.0, 10.0]);
        assert_eq!(anchor, None);
        assert!((shift[0] + 3.0).abs() < 1e-12 && shift[1].abs() < 1e-12);
    }

    #[test]
    fn a_cluster_whose_anchored_end_is_hidden_is_measured_by_its_centroid_and_last_offset() {
        // Last scan the centroid lay 2 m behind the reference; now the front is hidden as well.
        let anchor = Some(anchored(1, -1.0, -2.0));
        let ends = [end(0.0, true), end(3.0, true)];
        assert_eq!(
            measured_point(anchor.as_ref(), [1.5, 10.0], Some(&ends)),
            [3.5, 10.0]
        );
        let (anchor, shift) = next_reference(anchor, [1.5, 10.0], Some(&ends), [3.5, 10.0]);
        assert_eq!((anchor, shift), (None, [-2.0, 0.0]));
    }

    #[test]
    fn a_cluster_seen_through_a_gap_or_too_short_does_not_anchor_its_track() {
        let gap = [end(0.0, true), end(3.0, true)];
        assert_eq!(
            next_reference(None, [1.5, 10.0], Some(&gap), [1.5, 10.0]).0,
            None
        );
        let short = [end(0.0, true), end(0.5, false)];
        assert_eq!(
            next_reference(None, [0.2, 10.0], Some(&short), [0.2, 10.0]).0,
            None
        );
        assert_eq!(
            next_reference(None, [1.0, 1.0], None, [1.0, 1.0]),
            (None, [0.0, 0.0])
        );
    }
}
