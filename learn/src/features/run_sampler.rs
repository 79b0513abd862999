//! One task of the training-sample draw (thesis 3.1.1-3.1.2): a run of consecutive sweep pairs,
//! each sweep read and sliced once, each pair's beams traced once for every prior, every
//! candidate offered to each prior's draw.

use std::cmp::Reverse;

use patchflow_dataset::{SequenceReader, Sweep};

use crate::features::difference_map::MapPair;
use crate::features::feature_kind::FeatureKind;
use crate::features::gabor::GaborBank;
use crate::features::importance_sampling::{DrawKey, candidate_key, hashed_normal, name_hash};
use crate::features::patch::Patch;
use crate::features::slice::HeightSlice;
use crate::features::sweep_features::SweepFeatures;
use crate::features::top_n::TopN;
use crate::features::training_sample::TrainingSample;
use crate::{FeatureParams, LearnError, Result};

/// Consecutive sweep pairs of one sequence handled by one task: sequence number and the range of
/// current sweep indices. Neighbouring pairs share a sweep, which is read and sliced once.
pub(crate) type Run = (usize, std::ops::Range<usize>);
/// Where a candidate lies in the dataset: sequence number, sweep, point. Ties of draw keys go to
/// the earlier candidate.
type Position = (usize, u32, usize);
/// The rank of a candidate in a draw.
pub(crate) type Rank = (DrawKey, Reverse<Position>);
/// How many candidates were seen and, per draw, the best of them so far.
pub(crate) type Draws = (usize, Vec<TopN<Rank, TrainingSample>>);

/// Both tasks' candidate counts and, per prior, the `n` best of both.
pub(crate) fn merge((na, a): Draws, (nb, b): Draws) -> Draws {
    (
        na + nb,
        a.into_iter().zip(b).map(|(a, b)| a.merge(b)).collect(),
    )
}

/// What every task of one collection shares.
pub(crate) struct RunSampler<'a> {
    pub(crate) readers: &'a [SequenceReader],
    pub(crate) params: &'a FeatureParams,
    /// The distinct priors, whose maps are built once per sweep pair.
    pub(crate) priors: &'a [f64],
    /// The draws: index into `priors` and seed of each.
    pub(crate) draws: &'a [(usize, u64)],
    pub(crate) kind: FeatureKind,
    pub(crate) gabor: GaborBank,
}

impl RunSampler<'_> {
    /// Offers every candidate of a run of sweep pairs to the draws.
    pub(crate) fn run(
        &self,
        (seq, range): &Run,
        mut draws: Draws,
        tick: &impl Fn(),
    ) -> Result<Draws> {
        let reader = &self.readers[*seq];
        let name = &reader.info().name;
        let name_key = name_hash(name);
        let (_, mut prev) = self.slice(reader, range.start - 1)?;
        for t in range.clone() {
            let (curr_sweep, curr) = self.slice(reader, t)?;
            // 2.1.1-2.1.2 for every prior, the beams traced once.
            let window = self.params.map_window(curr.sensor_xy);
            let maps =
                MapPair::build_for_priors(&prev, &curr, window, self.params.spread, self.priors);
            let features: Vec<SweepFeatures> = maps
                .into_iter()
                .zip(self.priors)
                .map(|(m, &prior)| {
                    let params = FeatureParams {
                        prior,
                        ..self.params.clone()
                    };
                    SweepFeatures::without_clusters(&curr, m, params, self.gabor.clone())
                })
                .collect();
            let Some(first) = features.first() else {
                break;
            };
            for (i, _) in moving_points(first, &curr_sweep) {
                draws.0 += 1;
                let point = first.points()[i].index;
                let position = (*seq, curr_sweep.index, point);
                // 3.1.2: the weight is the motion the heading patch shows (Eq. 3.1), per prior.
                let headings: Vec<(Patch, f64)> = features
                    .iter()
                    .map(|f| {
                        let heading = f.heading_patch(i);
                        let weight = heading.mean_abs_difference();
                        (heading, weight)
                    })
                    .collect();
                for (&(p, seed), draw) in self.draws.iter().zip(&mut draws.1) {
                    let (Some(f), Some((heading, weight))) = (features.get(p), headings.get(p))
                    else {
                        continue;
                    };
                    let key = candidate_key(seed, name_key, curr_sweep.index, point, *weight);
                    let rank = (key, Reverse(position));
                    if draw.accepts(&rank)
                        && let Some(sample) =
                            sample_at(f, &curr_sweep, i, (heading, *weight), seed, self, name)
                    {
                        draw.push(rank, sample);
                    }
                }
            }
            prev = curr;
            tick();
        }
        Ok(draws)
    }

    /// Reads sweep `t` of a sequence and cuts it to the height slice (thesis 2.1.1).
    fn slice(&self, reader: &SequenceReader, t: usize) -> Result<(Sweep, HeightSlice)> {
        let sweep = reader.read_sweep(t)?;
        let slice = HeightSlice::cut(&sweep, self.params).map_err(|e| {
            let file = reader.dir().join("velodyne").join(format!("{t:06}.bin"));
            LearnError::degenerate_data(format!("{}: {e}", file.display()))
        })?;
        Ok((sweep, slice))
    }
}

/// Keys the speed-alignment errors apart from the draw's own uniforms.
const SPEED_JITTER_STREAM: u64 = 0x5eed_a119_e5e5;

/// Sliced points on a moving actor whose truth is in the sweep: `(point, actor id)`.
fn moving_points<'a>(
    features: &'a SweepFeatures,
    curr: &'a Sweep,
) -> impl Iterator<Item = (usize, u16)> + 'a {
    features.points().iter().enumerate().filter_map(|(i, p)| {
        let label = curr.labels.get(p.index)?;
        let actor = label.instance();
        (label.is_moving() && curr.objects.iter().any(|o| o.id == actor)).then_some((i, actor))
    })
}

/// The sample of sliced point `i` with its heading patch (thesis 3.1.1 targets, 2.2.2 patches).
fn sample_at(
    features: &SweepFeatures,
    curr: &Sweep,
    i: usize,
    (heading, weight): (&Patch, f64),
    seed: u64,
    sampler: &RunSampler<'_>,
    sequence: &str,
) -> Option<TrainingSample> {
    let kind = sampler.kind;
    let point = features.points()[i].index;
    let actor = curr.labels.get(point)?.instance();
    let truth = curr.objects.iter().find(|o| o.id == actor)?;
    let bearing_rad = features.bearing_rad(i);
    let relative = truth.heading_rad - bearing_rad;
    // The speed patch follows the true heading give or take the error of an estimated one
    // (FeatureParams::speed_jitter_deg), so the speed GP learns patches as it will meet them.
    let alignment_error_rad = sampler.params.speed_jitter_deg.to_radians()
        * hashed_normal(
            seed ^ SPEED_JITTER_STREAM,
            &[name_hash(sequence), u64::from(curr.index), point as u64],
        );
    Some(TrainingSample {
        sequence: sequence.to_owned(),
        scan: curr.index,
        point,
        actor,
        weight,
        bearing_rad,
        sin_rel: relative.sin(),
        cos_rel: relative.cos(),
        heading_rad: truth.heading_rad,
        speed_mps: truth.speed_mps,
        heading_features: features.feature_of(heading, kind),
        speed_features: features.feature_of(
            &features.speed_patch(i, truth.heading_rad + alignment_error_rad),
            kind,
        ),
    })
}

#[cfg(test)]
mod tests {
    use crate::features::sample_set::tests::write_dataset;
    use crate::{FeatureKind, FeatureParams, SampleSet};
    use patchflow_dataset::Dataset;

    fn draw(jitter_deg: f64) -> SampleSet {
        let dir = tempfile::tempdir().unwrap();
        write_dataset(dir.path(), 3);
        let dataset = Dataset::open(dir.path()).unwrap();
        let params = FeatureParams {
            speed_jitter_deg: jitter_deg,
            ..FeatureParams::default()
        };
        SampleSet::collect(&dataset, &params, FeatureKind::Patch, 40, 3).unwrap()
    }

    #[test]
    fn the_speed_alignment_error_moves_only_the_speed_patches() {
        let (exact, jittered) = (draw(0.0), draw(25.0));
        assert_eq!(exact.samples.len(), jittered.samples.len());
        let mut moved = 0;
        for (a, b) in exact.samples.iter().zip(&jittered.samples) {
            assert_eq!(
                (a.point, a.scan),
                (b.point, b.scan),
                "the same samples are drawn"
            );
            assert_eq!(a.heading_features, b.heading_features);
            assert_eq!((a.speed_mps, a.heading_rad), (b.speed_mps, b.heading_rad));
            moved += usize::from(a.speed_features != b.speed_features);
        }
        assert!(
            moved * 10 >= exact.samples.len() * 9,
            "{moved} of {} moved",
            exact.samples.len()
        );
    }
}
