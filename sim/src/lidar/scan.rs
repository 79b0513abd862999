//! The per-point output of one sweep and how it is assembled without per-point allocation: every
//! ray owns a slot in preallocated arrays, each column writes its returns to the front of its
//! slots in parallel, and one in-place compaction (one field per task) closes the gaps in column
//! order, so the bytes do not depend on the number of threads.

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
}

/// The slots of one column: its returns go to the front, `len` counts them.
pub(super) struct ColumnSlots<'a> {
    points: &'a mut [[f32; 3]],
    intensities: &'a mut [f32],
    labels: &'a mut [PointLabel],
    flows: &'a mut [[f32; 3]],
    times: &'a mut [f32],
    len: usize,
}

impl ColumnSlots<'_> {
    /// Appends a return (at most one per ray of the column).
    #[inline]
    pub(super) fn push(&mut self, r: Return) {
        let i = self.len;
        self.points[i] = r.point_in_sensor;
        self.intensities[i] = r.intensity;
        self.labels[i] = r.label;
        self.flows[i] = r.flow_mps;
        self.times[i] = r.time_in_sweep_secs;
        self.len += 1;
    }
}

/// One slot per ray of a sweep, plus the number of returns of each column.
pub(super) struct ScanSlots {
    channels: usize,
    scan: Scan,
    returns_per_column: Vec<u32>,
}

impl ScanSlots {
    /// Slots for `columns` columns of `channels` rays each.
    pub(super) fn new(columns: usize, channels: usize) -> Self {
        let rays = columns * channels;
        Self {
            channels,
            scan: Scan {
                points_in_sensor: vec![[0.0; 3]; rays],
                intensities: vec![0.0; rays],
                labels: vec![PointLabel::default(); rays],
                flow_in_world_mps: vec![[0.0; 3]; rays],
                time_in_sweep_secs: vec![0.0; rays],
                actor_point_counts: Vec::new(),
            },
            returns_per_column: vec![0; columns],
        }
    }

    /// Runs `cast(j, slots)` for every column `j` in `columns`, columns in parallel (one rayon
    /// task per column at the finest).
    pub(super) fn fill_columns<F>(&mut self, columns: Range<usize>, cast: F)
    where
        F: Fn(usize, &mut ColumnSlots<'_>) + Sync,
    {
        let ch = self.channels;
        let rays = columns.start * ch..columns.end * ch;
        let s = &mut self.scan;
        s.points_in_sensor[rays.clone()]
            .par_chunks_mut(ch)
            .zip(s.intensities[rays.clone()].par_chunks_mut(ch))
            .zip(s.labels[rays.clone()].par_chunks_mut(ch))
            .zip(s.flow_in_world_mps[rays.clone()].par_chunks_mut(ch))
            .zip(s.time_in_sweep_secs[rays].par_chunks_mut(ch))
            .zip(self.returns_per_column[columns.clone()].par_iter_mut())
            .enumerate()
            .for_each(
                |(k, (((((points, intensities), labels), flows), times), n))| {
                    let mut slots = ColumnSlots {
                        points,
                        intensities,
                        labels,
                        flows,
                        times,
                        len: 0,
                    };
                    cast(columns.start + k, &mut slots);
                    *n = slots.len as u32;
                },
            );
    }

    /// Closes the gaps between columns (each field compacted by its own task) and counts the
    /// points of each of `actor_count` actors from the instance ids (instance id = index + 1).
    pub(super) fn into_scan(self, actor_count: usize) -> Scan {
        let Self {
            channels,
            mut scan,
            returns_per_column: counts,
        } = self;
        let counts = &counts;
        let mut actor_point_counts = vec![0; actor_count];
        rayon::join(
            || {
                rayon::join(
                    || compact(&mut scan.points_in_sensor, counts, channels),
                    || compact(&mut scan.flow_in_world_mps, counts, channels),
                )
            },
            || {
                rayon::join(
                    || {
                        compact(&mut scan.labels, counts, channels);
                        for label in &scan.labels {
                            let actor = usize::from(label.instance()).wrapping_sub(1);
                            if let Some(count) = actor_point_counts.get_mut(actor) {
                                *count += 1;
                            }
                        }
                    },
                    || {
                        compact(&mut scan.intensities, counts, channels);
                        compact(&mut scan.time_in_sweep_secs, counts, channels);
                    },
                )
            },
        );
        scan.actor_point_counts = actor_point_counts;
        scan
    }
}

/// Moves the first `counts[j]` slots of every column `j` (of `channels` slots) together, in order.
fn compact<T: Copy>(slots: &mut Vec<T>, counts: &[u32], channels: usize) {
    let mut end = 0;
    for (j, &n) in counts.iter().enumerate() {
        let (start, n) = (j * channels, n as usize);
        if start != end {
            slots.copy_within(start..start + n, end);
        }
        end += n;
    }
    slots.truncate(end);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compaction_keeps_each_columns_returns_in_column_order() {
        let mut slots = vec![1, 2, 0, 3, 0, 0, 4, 5, 6];
        compact(&mut slots, &[2, 1, 3], 3);
        assert_eq!(slots, vec![1, 2, 3, 4, 5, 6]);
    }

    #[test]
    fn returns_land_in_column_order_whatever_the_parallel_split() {
        let mut slots = ScanSlots::new(50, 4);
        slots.fill_columns(0..50, |j, column| {
            // Column j returns j % 5 points (at most the 4 channels) tagged with its index.
            for c in 0..(j % 5).min(4) {
                column.push(Return {
                    point_in_sensor: [j as f32, c as f32, 0.0],
                    intensity: 0.5,
                    label: PointLabel::from_parts(40, u16::from(j % 2 == 0)),
                    flow_mps: [0.0; 3],
                    time_in_sweep_secs: j as f32,
                });
            }
        });
        let scan = slots.into_scan(1);
        let expected: Vec<[f32; 3]> = (0..50)
            .flat_map(|j| (0..(j % 5).min(4)).map(move |c| [j as f32, c as f32, 0.0]))
            .collect();
        assert_eq!(scan.points_in_sensor, expected);
        assert_eq!(scan.time_in_sweep_secs.len(), expected.len());
        let on_actor = scan.labels.iter().filter(|l| l.instance() == 1).count();
        assert_eq!(scan.actor_point_counts, vec![on_actor as u32]);
    }
}
