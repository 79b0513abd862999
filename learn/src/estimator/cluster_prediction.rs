//! Steps 3 and 4 of thesis Algorithm 3.1 for many clusters at once: per-point GP predictions in
//! parallel row chunks, merged per cluster (thesis 3.1.4).
//!
//! Rows are predicted in chunks of at most [`CHUNK_ROWS`] points of one cluster; a cluster is cut
//! into even pieces of more than five rows, so every row goes through the same matrix product
//! (nalgebra hands products with every dimension above five to matrixmultiply) and gets the
//! prediction a call on its cluster alone would give, bit for bit.

use nalgebra::DMatrix;
use rayon::prelude::*;

use super::cluster_estimate::{ClusterEstimate, ClusterMotion, PointMotion, PredictionTiming};
use super::merge::{Gaussian, HeadingVote, MergeRule, MergedHeading, merge_heading, merge_scalar};
use crate::timing::timed;
use crate::{GpPrediction, MotionEstimator, Patch, Result, SweepFeatures};

/// Most rows in one GP call (a few hundred kB of inputs: stays in cache, balances the cores).
const CHUNK_ROWS: usize = 128;

/// The estimates of the clusters asked for, in their order.
pub(super) struct ClusterPredictions {
    /// Merged estimates, one per cluster.
    pub estimates: Vec<ClusterEstimate>,
    /// Per cluster, per position: the prediction there.
    pub points: Vec<Vec<Option<PointMotion>>>,
    /// What it cost.
    pub timing: PredictionTiming,
}

/// Rows `start..end` of job `job` (a cluster, or a cluster along one heading).
struct RowChunk {
    job: usize,
    start: usize,
    end: usize,
}

/// Cuts jobs of `sizes` rows into chunks: whole if at most [`CHUNK_ROWS`], else even pieces.
fn row_chunks(sizes: impl Iterator<Item = usize>) -> Vec<RowChunk> {
    let mut chunks = Vec::new();
    for (job, n) in sizes.enumerate() {
        let pieces = n.div_ceil(CHUNK_ROWS);
        for p in 0..pieces {
            chunks.push(RowChunk {
                job,
                start: p * n / pieces,
                end: (p + 1) * n / pieces,
            });
        }
    }
    chunks
}

/// Regroups per-chunk rows into one vector per job (chunks come in job order).
fn per_job<T>(jobs: usize, chunks: &[RowChunk], rows: Vec<Vec<T>>) -> Vec<Vec<T>> {
    let mut out: Vec<Vec<T>> = (0..jobs).map(|_| Vec::new()).collect();
    for (chunk, rows) in chunks.iter().zip(rows) {
        out[chunk.job].extend(rows);
    }
    out
}

fn gaussians(prediction: &GpPrediction) -> impl Iterator<Item = Gaussian> + '_ {
    prediction
        .mean
        .iter()
        .zip(prediction.var_y.iter())
        .map(|(&mean, &var)| Gaussian { mean, var })
}

impl MotionEstimator {
    /// Heading and speed of every cluster given by the world positions it is predicted at (its
    /// points, or one sample per map cell).
    pub(super) fn predict_clusters(
        &self,
        features: &SweepFeatures,
        clusters: &[&[[f64; 2]]],
    ) -> Result<ClusterPredictions> {
        self.check_features(features)?;
        let mut timing = PredictionTiming {
            clusters: clusters.len(),
            rows: clusters.iter().map(|m| m.len()).sum(),
            ..PredictionTiming::default()
        };
        // 3a: heading patches aligned to each point's bearing (thesis 2.2.2).
        let chunks = row_chunks(clusters.iter().map(|m| m.len()));
        let x = timed(&mut timing.patches_secs, || {
            self.chunk_inputs(features, &chunks, |c| {
                let rows = &clusters[c.job][c.start..c.end];
                rows.iter()
                    .map(|&xy| features.patch_at(xy, features.bearing_at(xy)))
                    .collect()
            })
        })?;
        // 3b: per-point sin and cos of the heading relative to the bearing (thesis 3.1.1).
        let predictions = timed(&mut timing.gp_secs, || {
            x.par_iter()
                .map(|x| Ok((self.heading_sin.predict(x)?, self.heading_cos.predict(x)?)))
                .collect::<Result<Vec<_>>>()
        })?;
        // 3c: the votes turned into the world frame, one heading per cluster and merge rule.
        let (votes, headings) = timed(&mut timing.merge_secs, || {
            let rows = chunks
                .iter()
                .zip(&predictions)
                .map(|(c, (sin, cos))| {
                    let rows = &clusters[c.job][c.start..c.end];
                    rows.iter()
                        .zip(gaussians(sin).zip(gaussians(cos)))
                        .map(|(&xy, (s, c))| {
                            HeadingVote::from_relative(features.bearing_at(xy), s, c)
                        })
                        .collect()
                })
                .collect();
            let votes: Vec<Vec<HeadingVote>> = per_job(clusters.len(), &chunks, rows);
            let headings: Vec<[Option<MergedHeading>; 2]> = votes
                .iter()
                .map(|v| {
                    [
                        merge_heading(v, MergeRule::All),
                        merge_heading(v, MergeRule::Best),
                    ]
                })
                .collect();
            (votes, headings)
        });
        // 4a: speed patches aligned to each merged heading (thesis 2.2.2, 3.1.1).
        let (jobs, job_of) = speed_jobs(&headings);
        let speed_chunks = row_chunks(jobs.iter().map(|&(k, _)| clusters[k].len()));
        let speed_x = timed(&mut timing.patches_secs, || {
            self.chunk_inputs(features, &speed_chunks, |c| {
                let (k, heading_rad) = jobs[c.job];
                let rows = &clusters[k][c.start..c.end];
                rows.iter()
                    .map(|&xy| features.patch_at(xy, heading_rad))
                    .collect()
            })
        })?;
        // 4b: per-point speeds.
        let speed_rows = timed(&mut timing.gp_secs, || {
            speed_x
                .par_iter()
                .map(|x| Ok(gaussians(&self.speed.predict(x)?).collect()))
                .collect::<Result<Vec<Vec<Gaussian>>>>()
        })?;
        // 4c: one speed per cluster and merge rule (thesis 3.1.4).
        let merged = timed(&mut timing.merge_secs, || {
            let speeds = per_job(jobs.len(), &speed_chunks, speed_rows);
            let estimates = headings
                .iter()
                .zip(&job_of)
                .map(|([all, best], [all_job, best_job])| ClusterEstimate {
                    all: cluster_motion(*all, all_job.map(|j| &speeds[j][..]), MergeRule::All),
                    best: cluster_motion(*best, best_job.map(|j| &speeds[j][..]), MergeRule::Best),
                })
                .collect();
            let points = votes
                .iter()
                .zip(&job_of)
                .map(|(votes, [all_job, _])| match all_job {
                    Some(j) => votes
                        .iter()
                        .zip(&speeds[*j])
                        .map(|(vote, speed)| point_motion(vote, speed))
                        .collect(),
                    None => vec![None; votes.len()],
                })
                .collect();
            (estimates, points)
        });
        Ok(ClusterPredictions {
            estimates: merged.0,
            points: merged.1,
            timing,
        })
    }

    /// One input matrix per chunk, from the patches `patches_of` gives for it (in parallel).
    fn chunk_inputs(
        &self,
        features: &SweepFeatures,
        chunks: &[RowChunk],
        patches_of: impl Fn(&RowChunk) -> Vec<Patch> + Sync,
    ) -> Result<Vec<DMatrix<f64>>> {
        chunks
            .par_iter()
            .map(|c| self.feature_matrix(features, &patches_of(c)))
            .collect()
    }
}

/// The speed predictions to make: (cluster, heading) along every merged heading, and per cluster
/// the job of its ALL and BEST speeds. BEST shares ALL's job when both headings are equal.
#[allow(clippy::type_complexity)]
fn speed_jobs(
    headings: &[[Option<MergedHeading>; 2]],
) -> (Vec<(usize, f64)>, Vec<[Option<usize>; 2]>) {
    let mut jobs = Vec::new();
    let mut job_of = Vec::with_capacity(headings.len());
    for (k, [all, best]) in headings.iter().enumerate() {
        let all_job = all.map(|h| {
            jobs.push((k, h.heading_rad));
            jobs.len() - 1
        });
        let best_job = best.map(|b| match (all, all_job) {
            (Some(a), Some(j)) if a.heading_rad == b.heading_rad => j,
            _ => {
                jobs.push((k, b.heading_rad));
                jobs.len() - 1
            }
        });
        job_of.push([all_job, best_job]);
    }
    (jobs, job_of)
}

/// A cluster's motion under one rule: its merged heading and the merge of the speeds along it.
fn cluster_motion(
    heading: Option<MergedHeading>,
    speeds: Option<&[Gaussian]>,
    rule: MergeRule,
) -> Option<ClusterMotion> {
    let (heading, speeds) = (heading?, speeds?);
    merge_scalar(speeds, rule).map(|s| ClusterMotion {
        heading_rad: heading.heading_rad,
        heading_var: heading.var_rad2,
        speed_mps: s.mean.max(0.0),
        speed_var: s.var,
        heading_votes: heading.votes,
    })
}

/// A point's own heading (its vote) and speed (along the cluster's ALL heading).
fn point_motion(vote: &HeadingVote, speed: &Gaussian) -> Option<PointMotion> {
    let (heading_rad, heading_var) = vote.heading()?;
    Some(PointMotion {
        heading_rad,
        heading_var,
        speed_mps: speed.mean.max(0.0),
        speed_var: speed.var,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_jobs_stay_whole_and_large_ones_split_into_even_pieces_above_five_rows() {
        let chunks = row_chunks([3, CHUNK_ROWS, CHUNK_ROWS + 1, 0, 5 * CHUNK_ROWS - 1].into_iter());
        let sizes: Vec<(usize, usize)> = chunks.iter().map(|c| (c.job, c.end - c.start)).collect();
        assert_eq!(sizes[..4], [(0, 3), (1, CHUNK_ROWS), (2, 64), (2, 65)]);
        let last: Vec<usize> = sizes.iter().filter(|s| s.0 == 4).map(|s| s.1).collect();
        assert_eq!(last.len(), 5);
        assert_eq!(last.iter().sum::<usize>(), 5 * CHUNK_ROWS - 1);
        assert!(last.iter().all(|&n| n > 5 && n <= CHUNK_ROWS));
    }

    #[test]
    fn rows_are_regrouped_per_job_in_order() {
        let chunks = row_chunks([2, 0, 300].into_iter());
        let rows: Vec<Vec<usize>> = chunks.iter().map(|c| (c.start..c.end).collect()).collect();
        let jobs = per_job(3, &chunks, rows);
        assert_eq!(jobs[0], [0, 1]);
        assert!(jobs[1].is_empty());
        assert_eq!(jobs[2], (0..300).collect::<Vec<_>>());
    }

    #[test]
    fn best_shares_the_all_speed_job_only_when_the_headings_agree() {
        let h = |heading_rad| MergedHeading {
            heading_rad,
            var_rad2: 0.1,
            votes: 3,
        };
        let (jobs, job_of) = speed_jobs(&[
            [Some(h(0.5)), Some(h(0.5))],
            [Some(h(0.5)), Some(h(0.7))],
            [None, None],
        ]);
        assert_eq!(jobs, [(0, 0.5), (1, 0.5), (1, 0.7)]);
        assert_eq!(
            job_of,
            [[Some(0), Some(0)], [Some(1), Some(2)], [None, None]]
        );
    }
}
