//! The per-point output of one sweep and how it is assembled without per-point allocation: every
//! ray owns a slot in scratch arrays kept by the lidar from sweep to sweep, each column writes its
//! returns to the front of its slots in parallel, and one copy per field (the fields in parallel)
//! gathers them in column order into exactly sized arrays, so the bytes do not depend on threads.

use std::ops::Range;

use patchflow_dataset::PointLabel;
use rayon::prelude::*;

/// The per-point output of one sweep, parallel arrays in firing order (column by column).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Scan {
    /// Points in the sensor frame at the sweep's reference time, ego motion removed.
    pub points_in_sensor: Vec<[f32; 3]>,
    /// Intensity in [0, 1].
    pub intensities: Vec<f32>,
    /// SemanticKITTI labels.
    pub labels: Vec<PointLabel>,
    /// True velocity of the hit surface point, world frame, m/s.
    pub flow_in_world_mps: Vec<[f32; 3]>,
    /// Seconds since the sweep started at which the point's block was cast.
    pub time_in_sweep_secs: Vec<f32>,
    /// Ring (channel counted from the lowest beam, 0) of each point.
    pub rings: Vec<u16>,
    /// Points per actor (index = actor index, i.e. instance id − 1).
    pub actor_point_counts: Vec<u32>,
}

/// One labelled return.
#[derive(Debug, Clone, Copy)]
pub(super) struct Return {
    pub point_in_sensor: [f32; 3],
    pub intensity: f32,
    pub label: PointLabel,
    pub flow_mps: [f32; 3],
    pub time_in_sweep_secs: f32,
    /// Ring of the beam (0 the lowest).
    pub ring: u16,
    /// Measured range along the beam, metres (for the range image of the mixed-pixel pass).
    pub range_m: f32,
}

/// The slots of one column: its returns go to the front, `len` counts them.
pub(super) struct ColumnSlots<'a> {
    points: &'a mut [[f32; 3]],
    intensities: &'a mut [f32],
    labels: &'a mut [PointLabel],
    flows: &'a mut [[f32; 3]],
    times: &'a mut [f32],
    rings: &'a mut [u16],
    /// The column's range image, one per channel (highest first), NaN where nothing returned.
    ranges: &'a mut [f32],
    len: usize,
}

impl ColumnSlots<'_> {
    /// Appends the column's `returns` (at most one per ray of the column) after those already
    /// written, in order; any beyond the slots are dropped. One pass with the slices in
    /// registers and no bounds checks.
    #[inline]
    pub(super) fn extend(&mut self, returns: impl Iterator<Item = Return>) {
        let start = self.len;
        // Plain slice iterators, so the zip steps them with one index.
        let slots = tail(self.points, start)
            .iter_mut()
            .zip(tail(self.intensities, start))
            .zip(tail(self.labels, start))
            .zip(tail(self.flows, start))
            .zip(tail(self.times, start))
            .zip(tail(self.rings, start));
        let mut len = start;
        let channels = self.ranges.len();
        for (r, (((((point, intensity), label), flow), time), ring)) in returns.zip(slots) {
            *point = r.point_in_sensor;
            *intensity = r.intensity;
            *label = r.label;
            *flow = r.flow_mps;
            *time = r.time_in_sweep_secs;
            *ring = r.ring;
            if let Some(range) = channels
                .checked_sub(1 + usize::from(r.ring))
                .and_then(|c| self.ranges.get_mut(c))
            {
                *range = r.range_m;
            }
            len += 1;
        }
        self.len = len;
    }
}

/// The slots of `slots` from `start` on (none if `start` is past the end).
#[inline]
fn tail<T>(slots: &mut [T], start: usize) -> &mut [T] {
    let start = start.min(slots.len());
    &mut slots[start..]
}

/// The cast returns of a sweep, column by column, for a pass that moves them in place.
pub(super) struct ReturnsView<'a> {
    /// Each column's returns at the front of its `channels` slots.
    pub points: &'a mut [[f32; 3]],
    /// The ring of each slot.
    pub rings: &'a [u16],
    /// Returns per column.
    pub counts: &'a [u32],
    /// The range image (NaN: no return), column by column, highest channel first.
    pub ranges: &'a [f32],
    /// Slots per column.
    pub channels: usize,
}

/// One slot per ray of a sweep, plus the number of returns of each column (scratch space).
#[derive(Debug, Clone, Default)]
pub(super) struct ScanSlots {
    channels: usize,
    points: Vec<[f32; 3]>,
    intensities: Vec<f32>,
    labels: Vec<PointLabel>,
    flows: Vec<[f32; 3]>,
    times: Vec<f32>,
    rings: Vec<u16>,
    /// The range image: one range per ray (NaN where nothing returned).
    pub(super) ranges: Vec<f32>,
    returns_per_column: Vec<u32>,
}

impl ScanSlots {
    /// Slots for `columns` columns of `channels` rays each; reuses the arrays already there.
    pub(super) fn reset(&mut self, columns: usize, channels: usize) {
        let rays = columns * channels;
        self.channels = channels;
        self.points.resize(rays, [0.0; 3]);
        self.intensities.resize(rays, 0.0);
        self.labels.resize(rays, PointLabel::default());
        self.flows.resize(rays, [0.0; 3]);
        self.times.resize(rays, 0.0);
        self.rings.resize(rays, 0);
        self.ranges.clear();
        self.ranges.resize(rays, f32::NAN);
        self.returns_per_column.clear();
        self.returns_per_column.resize(columns, 0);
    }

    /// Runs `cast(j, slots)` for every column `j` in `columns`, columns in parallel (one rayon
    /// task per column at the finest).
    pub(super) fn fill_columns<F>(&mut self, columns: Range<usize>, cast: F)
    where
        F: Fn(usize, &mut ColumnSlots<'_>) + Sync,
    {
        let ch = self.channels;
        let rays = columns.start * ch..columns.end * ch;
        self.points[rays.clone()]
            .par_chunks_mut(ch)
            .zip(self.intensities[rays.clone()].par_chunks_mut(ch))
            .zip(self.labels[rays.clone()].par_chunks_mut(ch))
            .zip(self.flows[rays.clone()].par_chunks_mut(ch))
            .zip(self.times[rays.clone()].par_chunks_mut(ch))
            .zip(self.rings[rays.clone()].par_chunks_mut(ch))
            .zip(self.ranges[rays].par_chunks_mut(ch))
            .zip(self.returns_per_column[columns.clone()].par_iter_mut())
            .enumerate()
            .for_each(
                |(k, (((((((points, intensities), labels), flows), times), rings), ranges), n))| {
                    let mut slots = ColumnSlots {
                        points,
                        intensities,
                        labels,
                        flows,
                        times,
                        rings,
                        ranges,
                        len: 0,
                    };
                    cast(columns.start + k, &mut slots);
                    *n = slots.len as u32;
                },
            );
    }

    /// The points, rings and returns per column, for passes that rework the returns in place.
    pub(super) fn returns_mut(&mut self) -> ReturnsView<'_> {
        ReturnsView {
            points: &mut self.points,
            rings: &self.rings,
            counts: &self.returns_per_column,
            ranges: &self.ranges,
            channels: self.channels,
        }
    }

    /// Gathers the returns in column order (each field by its own task, the tasks paired so two
    /// threads copy about as many bytes each) and counts the points of each of `actor_count`
    /// actors from the instance ids (instance id = actor index + 1).
    pub(super) fn gather(&self, actor_count: usize) -> Scan {
        let (ch, counts) = (self.channels, self.returns_per_column.as_slice());
        let (
            (points_in_sensor, (labels, actor_point_counts)),
            (flow_in_world_mps, (intensities, (time_in_sweep_secs, rings))),
        ) = rayon::join(
            || {
                rayon::join(
                    || gather(&self.points, counts, ch),
                    || {
                        let labels = gather(&self.labels, counts, ch);
                        let per_actor = count_per_actor(&labels, actor_count);
                        (labels, per_actor)
                    },
                )
            },
            || {
                rayon::join(
                    || gather(&self.flows, counts, ch),
                    || {
                        rayon::join(
                            || gather(&self.intensities, counts, ch),
                            || {
                                (
                                    gather(&self.times, counts, ch),
                                    gather(&self.rings, counts, ch),
                                )
                            },
                        )
                    },
                )
            },
        );
        Scan {
            points_in_sensor,
            intensities,
            labels,
            flow_in_world_mps,
            time_in_sweep_secs,
            rings,
            actor_point_counts,
        }
    }
}

/// The first `counts[j]` slots of every column `j` (of `channels` slots), in column order.
fn gather<T: Copy>(slots: &[T], counts: &[u32], channels: usize) -> Vec<T> {
    let total = counts.iter().map(|&n| n as usize).sum();
    let mut out = Vec::with_capacity(total);
    for (column, &n) in slots.chunks(channels).zip(counts) {
        out.extend_from_slice(&column[..n as usize]);
    }
    out
}

/// Points per actor from the labels' instance ids (0 is the static world).
fn count_per_actor(labels: &[PointLabel], actor_count: usize) -> Vec<u32> {
    let mut counts = vec![0; actor_count];
    for label in labels {
        let actor = usize::from(label.instance()).wrapping_sub(1);
        if let Some(count) = counts.get_mut(actor) {
            *count += 1;
        }
    }
    counts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gathering_keeps_each_columns_returns_in_column_order() {
        let slots = [1, 2, 0, 3, 0, 0, 4, 5, 6];
        assert_eq!(gather(&slots, &[2, 1, 3], 3), vec![1, 2, 3, 4, 5, 6]);
    }

    #[test]
    fn returns_land_in_column_order_whatever_the_parallel_split() {
        let mut slots = ScanSlots::default();
        slots.reset(50, 4);
        slots.fill_columns(0..50, |j, column| {
            // Column j returns j % 5 points (at most the 4 channels) tagged with its index.
            column.extend((0..(j % 5)).map(|c| Return {
                point_in_sensor: [j as f32, c as f32, 0.0],
                intensity: 0.5,
                label: PointLabel::from_parts(40, u16::from(j % 2 == 0)),
                flow_mps: [0.0; 3],
                time_in_sweep_secs: j as f32,
                ring: c as u16,
                range_m: 1.0,
            }));
        });
        let scan = slots.gather(1);
        let expected: Vec<[f32; 3]> = (0..50)
            .flat_map(|j| (0..(j % 5).min(4)).map(move |c| [j as f32, c as f32, 0.0]))
            .collect();
        assert_eq!(scan.points_in_sensor, expected);
        assert_eq!(scan.time_in_sweep_secs.len(), expected.len());
        let on_actor = scan.labels.iter().filter(|l| l.instance() == 1).count();
        assert_eq!(scan.actor_point_counts, vec![on_actor as u32]);
    }
}
