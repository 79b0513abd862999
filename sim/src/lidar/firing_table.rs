//! The firing pattern of one lidar, computed once: the unit direction of every ray in the sensor
//! frame (column by column, channel fastest) and the azimuth blocks with the instant each is cast.

use std::ops::Range;

use rapier3d::prelude::Vector;

use super::beams::{column_azimuth_rad, elevations_deg};
use crate::scenario::LidarConfig;

/// One azimuth block: its columns and when (after the sweep start) the scene is frozen for it.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct BlockSpan {
    /// Azimuth columns of the block.
    pub columns: Range<usize>,
    /// Instant the block is cast, seconds after the sweep start (0 without rolling shutter).
    pub offset_secs: f64,
}

/// Ray directions and azimuth blocks of a lidar.
#[derive(Debug, Clone)]
pub(super) struct FiringTable {
    channels: usize,
    rays_in_sensor: Vec<Vector>,
    /// The directions the beams really leave in (nominal plus each channel's elevation error);
    /// `None` when they are the nominal ones.
    rays_cast: Option<Vec<Vector>>,
    /// Beams the ego car's own body stops (never cast), per ray; `None` when none is.
    occluded: Option<Vec<bool>>,
    blocks: Vec<BlockSpan>,
    /// Index of the block of every column.
    block_of_column: Vec<u32>,
}

impl FiringTable {
    /// The table for `config`. With the rolling shutter on, block `b` is cast at the middle of its
    /// azimuth span; otherwise one block holds every column and is cast at the sweep start.
    pub(super) fn new(config: &LidarConfig) -> Self {
        let elevation_sin_cos: Vec<(f32, f32)> = elevations_deg(config)
            .into_iter()
            .map(|e| {
                let (s, c) = e.to_radians().sin_cos();
                (s as f32, c as f32)
            })
            .collect();
        let steps = config.azimuth_steps;
        let rays_in_sensor = (0..steps)
            .flat_map(|j| {
                let (sa, ca) = column_azimuth_rad(config, j).sin_cos();
                let (sa, ca) = (sa as f32, ca as f32);
                elevation_sin_cos
                    .iter()
                    .map(move |&(se, ce)| Vector::new(ce * ca, ce * sa, se))
            })
            .collect();
        let blocks = if config.rolling_shutter {
            let n = config.blocks.max(1);
            let period = config.period_secs();
            (0..n)
                .map(|b| {
                    let (first, end) = (b * steps / n, (b + 1) * steps / n);
                    BlockSpan {
                        columns: first as usize..end as usize,
                        offset_secs: period * (f64::from(first) + f64::from(end))
                            / 2.0
                            / f64::from(steps),
                    }
                })
                .collect()
        } else {
            vec![BlockSpan {
                columns: 0..steps as usize,
                offset_secs: 0.0,
            }]
        };
        let block_of_column = blocks
            .iter()
            .enumerate()
            .flat_map(|(b, block)| block.columns.clone().map(move |_| b as u32))
            .collect();
        Self {
            channels: elevation_sin_cos.len(),
            rays_in_sensor,
            rays_cast: None,
            occluded: None,
            blocks,
            block_of_column,
        }
    }

    /// The same table with the beams cast `error_rad(c)` above channel `c`'s nominal elevation
    /// (the points are still written along the nominal directions).
    pub(super) fn with_elevation_errors(
        mut self,
        config: &LidarConfig,
        error_rad: impl Fn(usize) -> f64,
    ) -> Self {
        let elevations = elevations_deg(config);
        if (0..elevations.len()).all(|c| error_rad(c) == 0.0) {
            return self;
        }
        let steps = config.azimuth_steps;
        self.rays_cast = Some(
            (0..steps)
                .flat_map(|j| {
                    let (sa, ca) = column_azimuth_rad(config, j).sin_cos();
                    elevations
                        .iter()
                        .enumerate()
                        .map(move |(c, e)| (c, e, sa, ca))
                        .collect::<Vec<_>>()
                })
                .map(|(c, e, sa, ca)| {
                    let (se, ce) = (e.to_radians() + error_rad(c)).sin_cos();
                    Vector::new((ce * ca) as f32, (ce * sa) as f32, se as f32)
                })
                .collect(),
        );
        self
    }

    /// The same table with the beams for which `occluded(directions)` (the directions they are
    /// really cast in, sensor frame, every ray) says true never cast.
    pub(super) fn with_occlusion(mut self, occluded: impl Fn(&[Vector]) -> Vec<bool>) -> Self {
        let mask = occluded(self.rays_cast.as_deref().unwrap_or(&self.rays_in_sensor));
        self.occluded = mask.contains(&true).then_some(mask);
        self
    }

    /// Whether each ray of column `j` is stopped by the ego car's body; `None` if none is.
    #[inline]
    pub(super) fn occluded_column(&self, j: usize) -> Option<&[bool]> {
        let mask = self.occluded.as_ref()?;
        Some(&mask[j * self.channels..(j + 1) * self.channels])
    }

    /// Share of the rays the ego car's body stops.
    pub(super) fn occluded_share(&self) -> f64 {
        self.occluded.as_ref().map_or(0.0, |m| {
            m.iter().filter(|&&o| o).count() as f64 / m.len().max(1) as f64
        })
    }

    /// Directions the rays of column `j` are really cast in, sensor frame.
    #[inline]
    pub(super) fn cast_column(&self, j: usize) -> &[Vector] {
        match &self.rays_cast {
            Some(rays) => &rays[j * self.channels..(j + 1) * self.channels],
            None => self.column(j),
        }
    }

    /// Rays per column.
    pub(super) fn channels(&self) -> usize {
        self.channels
    }

    /// Unit directions of the rays of column `j`, sensor frame, highest channel first.
    #[inline]
    pub(super) fn column(&self, j: usize) -> &[Vector] {
        &self.rays_in_sensor[j * self.channels..(j + 1) * self.channels]
    }

    /// Every ray direction, sensor frame, column by column.
    pub(super) fn rays_in_sensor(&self) -> &[Vector] {
        &self.rays_in_sensor
    }

    /// The azimuth blocks in firing order.
    pub(super) fn blocks(&self) -> &[BlockSpan] {
        &self.blocks
    }

    /// Index in [`FiringTable::blocks`] of the block holding column `j`.
    #[inline]
    pub(super) fn block_of(&self, j: usize) -> usize {
        self.block_of_column[j] as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_blocks_partition_the_columns_in_firing_order() {
        let config = LidarConfig {
            azimuth_steps: 100,
            blocks: 7,
            ..LidarConfig::default()
        };
        let table = FiringTable::new(&config);
        let blocks = table.blocks();
        assert_eq!(blocks.len(), 7);
        assert_eq!(blocks[0].columns.start, 0);
        assert_eq!(blocks[6].columns.end, 100);
        assert!(
            blocks
                .windows(2)
                .all(|w| w[0].columns.end == w[1].columns.start
                    && w[0].offset_secs < w[1].offset_secs)
        );
        assert!(blocks[6].offset_secs < config.period_secs());
    }

    #[test]
    fn every_column_knows_the_block_that_holds_it() {
        let config = LidarConfig {
            azimuth_steps: 100,
            blocks: 7,
            ..LidarConfig::default()
        };
        let table = FiringTable::new(&config);
        for (b, block) in table.blocks().iter().enumerate() {
            assert!(block.columns.clone().all(|j| table.block_of(j) == b));
        }
    }

    #[test]
    fn every_ray_is_a_unit_vector_and_the_first_column_looks_backwards() {
        let table = FiringTable::new(&LidarConfig::default());
        assert_eq!(table.rays_in_sensor().len(), 64 * 1800);
        assert!(
            table
                .rays_in_sensor()
                .iter()
                .all(|d| (d.length() - 1.0).abs() < 1e-6)
        );
        assert!(
            table
                .column(0)
                .iter()
                .all(|d| d.x < 0.0 && d.y.abs() < 1e-6)
        );
    }
}
