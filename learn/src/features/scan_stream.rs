//! A sequence's scans in order, as a lidar delivers them: each sweep is read and cut to the
//! height slice once, and its slice serves as the previous one of the next scan (thesis 2.1.2
//! differences the maps at t and t − 1).

use std::collections::VecDeque;
use std::time::Instant;

use patchflow_dataset::{SequenceReader, Sweep};

use crate::features::slice::HeightSlice;
use crate::{FeatureParams, FeatureValidParams, Result, SweepFeatures};

/// One step of a [`ScanStream`]: the current sweep and its features for every parameter set
/// asked for (named apart from the simulator's `Scan`, one sweep's raw per-point output).
#[derive(Debug, Clone)]
pub struct FeaturedSweep {
    /// Index of the current sweep in its sequence (at least 1: the first sweep has no predecessor).
    pub index: usize,
    /// The current sweep.
    pub sweep: Sweep,
    /// Its features given the previous sweep, one per parameter set of the stream, in order.
    pub features: Vec<SweepFeatures>,
}

/// Iterates over the scans `1..len` of a sequence in order.
///
/// ```no_run
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// use patchflow_learn::{FeatureParams, ScanStream};
/// let dataset = patchflow_dataset::Dataset::open(std::path::Path::new("data/situations"))?;
/// let sequence = dataset.sequence("situation1")?;
/// for scan in ScanStream::new(&sequence, vec![FeatureParams::default()])? {
///     let scan = scan?;
///     println!("sweep {}: {} clusters", scan.index, scan.features[0].clusters().len());
/// }
/// # Ok(())
/// # }
/// ```
#[derive(Debug)]
pub struct ScanStream<'a> {
    sequence: &'a SequenceReader,
    params: Vec<FeatureValidParams>,
    next: usize,
    previous: Vec<HeightSlice>,
    /// The first parameter set's slices of the last `history_len` sweeps, oldest first; the last
    /// is the current sweep's once [`Self::features_of`] has run.
    history: VecDeque<HeightSlice>,
}

/// Slices kept for [`ScanStream::slice_back`]: the current sweep's and the five before it.
const HISTORY_LEN: usize = 6;

impl<'a> ScanStream<'a> {
    /// A stream over `sequence` computing features once per parameter set (usually one; several
    /// when estimators were trained with different map parameters). Parameters are checked here.
    pub fn new(sequence: &'a SequenceReader, params: Vec<FeatureParams>) -> Result<Self> {
        let params = params
            .iter()
            .map(FeatureParams::check)
            .collect::<Result<Vec<_>>>()?;
        Ok(Self {
            sequence,
            params,
            next: 0,
            previous: Vec::new(),
            history: VecDeque::with_capacity(HISTORY_LEN),
        })
    }

    /// Scans still to come.
    pub fn remaining(&self) -> usize {
        self.sequence.len().saturating_sub(self.next.max(1))
    }

    fn cut(&self, sweep: &Sweep) -> Result<Vec<HeightSlice>> {
        self.params
            .iter()
            .map(|p| HeightSlice::cut(sweep, p))
            .collect()
    }

    /// Reads the next sweep to process with its index (`None` at the end). The first call also
    /// reads and cuts sweep 0, the first scan's predecessor. Hand the sweep to
    /// [`Self::features_of`] before reading the next one; the iterator does both.
    pub fn read_next(&mut self) -> Result<Option<(usize, Sweep)>> {
        if self.next == 0 {
            if self.sequence.is_empty() {
                return Ok(None);
            }
            self.previous = self.cut(&self.sequence.read_sweep(0)?)?;
            self.remember();
            self.next = 1;
        }
        if self.next >= self.sequence.len() {
            return Ok(None);
        }
        let index = self.next;
        self.next += 1;
        Ok(Some((index, self.sequence.read_sweep(index)?)))
    }

    /// The features of the sweep [`Self::read_next`] returned, given the previous one, one per
    /// parameter set; its slice becomes the previous one of the next scan.
    pub fn features_of(&mut self, sweep: &Sweep) -> Result<Vec<SweepFeatures>> {
        let start = Instant::now();
        // 2.1.1: only the new sweep is cut; the previous slice comes from the last scan.
        let current = self.cut(sweep)?;
        let slice_secs = start.elapsed().as_secs_f64();
        let features = self
            .params
            .iter()
            .zip(self.previous.iter().zip(&current))
            .map(|(params, (prev, curr))| {
                let mut features = SweepFeatures::from_slices(prev, curr, params)?;
                features.set_slice_secs(slice_secs);
                Ok(features)
            })
            .collect::<Result<Vec<_>>>()?;
        self.previous = current;
        self.remember();
        Ok(features)
    }

    /// Keeps the first parameter set's newest slice in the history.
    fn remember(&mut self) {
        if let Some(slice) = self.previous.first() {
            if self.history.len() == HISTORY_LEN {
                self.history.pop_front();
            }
            self.history.push_back(slice.clone());
        }
    }

    /// The first parameter set's slice of the sweep `n` before the last one handed to
    /// [`Self::features_of`] (`n = 0`: that sweep), or the oldest kept when the sequence or the
    /// history (the last five sweeps) does not reach that far; `None` before the first sweep.
    pub fn slice_back(&self, n: usize) -> Option<&HeightSlice> {
        let newest = self.history.len().checked_sub(1)?;
        self.history.get(newest.saturating_sub(n))
    }

    /// The first parameter set, checked.
    pub fn first_params(&self) -> Option<&FeatureValidParams> {
        self.params.first()
    }

    fn advance(&mut self) -> Result<Option<FeaturedSweep>> {
        let Some((index, sweep)) = self.read_next()? else {
            return Ok(None);
        };
        let features = self.features_of(&sweep)?;
        Ok(Some(FeaturedSweep {
            index,
            sweep,
            features,
        }))
    }
}

impl Iterator for ScanStream<'_> {
    type Item = Result<FeaturedSweep>;

    fn next(&mut self) -> Option<Self::Item> {
        match self.advance() {
            Ok(scan) => scan.map(Ok),
            Err(err) => {
                // A broken sweep ends the stream after reporting it once.
                self.next = usize::MAX;
                Some(Err(err))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
    use patchflow_dataset::{Dataset, Pose, SequenceWriter};

    fn sequence(root: &std::path::Path, sweeps: u32) -> SequenceReader {
        let lidar = SyntheticLidar::with_resolution(24, 720);
        let mut scene = SyntheticScene {
            boxes: vec![SceneBox::car(3, [10.0, 2.0], 0.4, 6.0)],
        };
        let writer = SequenceWriter::open(root, "stream").unwrap();
        let (mut poses, mut stamps) = (Vec::new(), Vec::new());
        for i in 0..sweeps {
            let sweep = scene.scan(&lidar, [0.2 * f64::from(i), 0.0], 0.0, i);
            writer.write_sweep(&sweep).unwrap();
            poses.push(sweep.world_from_sensor);
            stamps.push(sweep.stamp_secs);
            scene = scene.advanced(0.1);
        }
        let poses: Vec<Pose> = poses;
        writer
            .finish("synthetic", 0, 10.0, &poses, &stamps, "test")
            .unwrap();
        Dataset::open(root).unwrap().sequence("stream").unwrap()
    }

    #[test]
    fn streamed_features_equal_features_computed_pair_by_pair() {
        let dir = tempfile::tempdir().unwrap();
        let reader = sequence(dir.path(), 4);
        let params = FeatureParams {
            half_extent_m: 20.0,
            ..FeatureParams::default()
        };
        let stream = ScanStream::new(&reader, vec![params.clone()]).unwrap();
        assert_eq!(stream.remaining(), 3);
        let scans: Vec<FeaturedSweep> = stream.map(Result::unwrap).collect();
        assert_eq!(scans.iter().map(|s| s.index).collect::<Vec<_>>(), [1, 2, 3]);
        for scan in &scans {
            let prev = reader.read_sweep(scan.index - 1).unwrap();
            let pair = SweepFeatures::compute(&prev, &scan.sweep, &params).unwrap();
            let streamed = &scan.features[0];
            assert_eq!(streamed.points(), pair.points());
            assert_eq!(streamed.clusters(), pair.clusters());
            assert_eq!(streamed.difference_map(), pair.difference_map());
            assert_eq!(streamed.reflection_map(), pair.reflection_map());
        }
    }

    #[test]
    fn a_sequence_of_one_sweep_has_no_scan() {
        let dir = tempfile::tempdir().unwrap();
        let reader = sequence(dir.path(), 1);
        let mut stream = ScanStream::new(&reader, vec![FeatureParams::default()]).unwrap();
        assert_eq!(stream.remaining(), 0);
        assert!(stream.next().is_none());
    }

    #[test]
    fn slice_back_reaches_five_sweeps_and_no_further() {
        let dir = tempfile::tempdir().unwrap();
        let reader = sequence(dir.path(), 9);
        let params = FeatureParams::default();
        let valid = params.check().unwrap();
        let mut stream = ScanStream::new(&reader, vec![params]).unwrap();
        assert!(stream.slice_back(0).is_none());
        let cut = |k: usize| HeightSlice::cut(&reader.read_sweep(k).unwrap(), &valid).unwrap();
        while let Some((index, sweep)) = stream.read_next().unwrap() {
            stream.features_of(&sweep).unwrap();
            assert_eq!(stream.slice_back(0), Some(&cut(index)), "scan {index}");
            let oldest = index.saturating_sub(5);
            assert_eq!(stream.slice_back(5), Some(&cut(oldest)), "scan {index}");
            assert_eq!(stream.slice_back(9), Some(&cut(oldest)), "scan {index}");
        }
    }
}
