//! Steps 3 and 4 of thesis Algorithm 3.1 for many clusters at once: per-point GP predictions for
//! all clusters in one batch per GP, merged per cluster (thesis 3.1.4).
//!
//! The positions of every cluster go one after another into one row-major input buffer per step
//! (patches built in parallel tasks of [`TASK_ROWS`] rows), and each GP predicts the whole buffer
//! in one [`GpModel::predict_row_groups`](crate::GpModel::predict_row_groups) call, which spreads
//! it over the cores and gives every cluster, bit for bit, what `GpModel::predict` on its own
//! positions would give, whatever the other clusters and the threads.

use rayon::prelude::*;

use super::cluster_estimate::{ClusterEstimate, ClusterMotion, PointMotion, PredictionTiming};
use super::merge::{Gaussian, HeadingVote, MergeRule, MergedHeading, merge_heading, merge_scalar};
use super::regressor::Regressor;
use crate::timing::timed;
use crate::{
    FeatureKind, GpPrediction, LearnError, MotionEstimator, PATCH_LEN, Result, SweepFeatures,
};

/// Rows per parallel task when building the GP inputs (a few hundred kB of patches).
const TASK_ROWS: usize = 64;

/// The estimates of the clusters asked for, in their order.
pub(super) struct ClusterPredictions {
    /// Merged estimates, one per cluster.
    pub estimates: Vec<ClusterEstimate>,
    /// Per cluster, per position: the prediction there.
    pub points: Vec<Vec<Option<PointMotion>>>,
    /// What it cost.
    pub timing: PredictionTiming,
}

/// Cuts `values`, one per row of consecutive jobs of `sizes` rows, into one vector per job.
fn per_job<T>(sizes: impl Iterator<Item = usize>, values: Vec<T>) -> Vec<Vec<T>> {
    let mut rest = values.into_iter();
    sizes.map(|n| rest.by_ref().take(n).collect()).collect()
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
        let positions: Vec<[f64; 2]> = clusters.iter().flat_map(|m| m.iter().copied()).collect();
        let sizes: Vec<usize> = clusters.iter().map(|m| m.len()).collect();
        // 3a: heading patches aligned to each point's bearing (thesis 2.2.2).
        let x = timed(&mut timing.patches_secs, || {
            self.input_rows(features, positions.len(), |r| {
                let xy = positions[r];
                (xy, features.bearing_at(xy))
            })
        })?;
        // 3b: per-point sin and cos of the heading relative to the bearing (thesis 3.1.1).
        let (sin, cos) = timed(&mut timing.gp_secs, || {
            let pair = [&self.heading_sin, &self.heading_cos];
            let mut both = Regressor::predict_together(&pair, &x, &sizes)?.into_iter();
            match (both.next(), both.next()) {
                (Some(sin), Some(cos)) => Ok((sin, cos)),
                _ => Err(LearnError::invalid_params(
                    "the heading GPs did not predict both".into(),
                )),
            }
        })?;
        drop(x);
        // 3c: the votes turned into the world frame, one heading per cluster and merge rule.
        let (votes, headings) = timed(&mut timing.merge_secs, || {
            let rows: Vec<HeadingVote> = positions
                .iter()
                .zip(gaussians(&sin).zip(gaussians(&cos)))
                .map(|(&xy, (s, c))| HeadingVote::from_relative(features.bearing_at(xy), s, c))
                .collect();
            let votes = per_job(sizes.iter().copied(), rows);
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
        let speed_sizes: Vec<usize> = jobs.iter().map(|&(k, _)| clusters[k].len()).collect();
        let speed_rows: Vec<([f64; 2], f64)> = jobs
            .iter()
            .flat_map(|&(k, heading_rad)| clusters[k].iter().map(move |&xy| (xy, heading_rad)))
            .collect();
        let speed_x = timed(&mut timing.patches_secs, || {
            self.input_rows(features, speed_rows.len(), |r| speed_rows[r])
        })?;
        // 4b: per-point speeds.
        let speed = timed(&mut timing.gp_secs, || {
            self.speed.predict_row_groups(&speed_x, &speed_sizes)
        })?;
        drop(speed_x);
        // 4c: one speed per cluster and merge rule (thesis 3.1.4).
        let merged = timed(&mut timing.merge_secs, || {
            let speeds = per_job(speed_sizes.iter().copied(), gaussians(&speed).collect());
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

    /// The GP inputs of `n` rows one after another (row-major): the features of the patch
    /// centred on the position and aligned to the axis that `patch_of` gives for each row
    /// (thesis 2.2.2), built in parallel tasks; patch values go straight into their row.
    pub(super) fn input_rows(
        &self,
        features: &SweepFeatures,
        n: usize,
        patch_of: impl Fn(usize) -> ([f64; 2], f64) + Sync,
    ) -> Result<Vec<f64>> {
        let d = self.feature.names().len();
        let mut x = vec![0.0; n * d];
        if d == 0 {
            return Ok(x);
        }
        x.par_chunks_mut(TASK_ROWS * d)
            .enumerate()
            .try_for_each(|(task, out)| {
                for (j, row) in out.chunks_exact_mut(d).enumerate() {
                    let (xy, axis_rad) = patch_of(task * TASK_ROWS + j);
                    let values = match self.feature {
                        FeatureKind::Patch => match <&mut [f64; PATCH_LEN]>::try_from(&mut *row) {
                            Ok(values) => {
                                features.patch_values_at(xy, axis_rad, values);
                                continue;
                            }
                            Err(_) => Vec::new(), // a length error below
                        },
                        kind => features.feature_of(&features.patch_at(xy, axis_rad), kind),
                    };
                    if values.len() != d {
                        return Err(LearnError::degenerate_data(format!(
                            "a {:?} feature row has {} values, expected {d}",
                            self.feature,
                            values.len()
                        )));
                    }
                    row.copy_from_slice(&values);
                }
                Ok(())
            })?;
        Ok(x)
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
    fn rows_are_cut_per_job_in_order() {
        let jobs = per_job([2, 0, 3].into_iter(), (0..5).collect());
        assert_eq!(jobs, [vec![0, 1], vec![], vec![2, 3, 4]]);
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
