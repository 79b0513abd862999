//! The perception cost of a benchmark run, summed up per sequence and stage: median and worst scan
//! (SPEC §8: a whole scan under 100 ms on 2 cores, the sensor's 10 Hz).

use serde::Serialize;

use crate::scene::perception_timing::{ScanTiming, Spread, StepTiming};
use crate::scene::result::SceneResult;

/// How to read one stage's seconds from a [`ScanTiming`].
pub type StageOf = fn(&ScanTiming) -> f64;

/// The stages of one scan, in pipeline order, with how to read each from a [`ScanTiming`].
pub const STAGES: [(&str, StageOf); 9] = [
    ("height slice", |t| t.slice_secs),
    ("reflection and difference maps", |t| t.maps_secs),
    ("clusters", |t| t.clusters_secs),
    ("maps and clusters (in parallel)", |t| {
        t.maps_and_clusters_secs
    }),
    ("object hypotheses and map cells", |t| {
        sum(t, |s| s.hypotheses_secs)
    }),
    ("patches", |t| sum(t, |s| s.patches_secs)),
    ("GP prediction", |t| sum(t, |s| s.gp_secs)),
    ("merging", |t| sum(t, |s| s.merge_secs)),
    ("whole scan, every estimator", ScanTiming::whole_scan_secs),
];

fn sum(t: &ScanTiming, stage: fn(&StepTiming) -> f64) -> f64 {
    t.estimators.iter().map(stage).sum()
}

/// The perception of one sequence (or of all, pooled).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PerceptionSummary {
    /// Sequence name, or `all` for every scan of the run.
    pub name: String,
    /// Scans timed.
    pub scans: usize,
    /// Estimators run per scan.
    pub estimators: usize,
    /// Each stage of `STAGES`, in order.
    pub stages: Vec<(String, Spread)>,
    /// The whole scan for one estimator (features plus the mean estimator's step).
    pub one_estimator: Spread,
    /// CPU time of the whole scan, all threads, when the system reports it.
    pub whole_scan_cpu: Option<Spread>,
    /// The baselines over every cluster.
    pub baselines: Spread,
    /// Median map-cell samples the first estimator predicted at.
    pub median_samples: f64,
    /// Median points in the hypotheses.
    pub median_points: f64,
    /// Thesis-protocol target estimate (all its points), per estimator; not in the whole scan.
    pub target: Spread,
    /// Mean sliced points of the target's cluster, when the sequence has a target.
    pub mean_target_points: Option<f64>,
    /// The moving classifier on every hypothesis (issue 27).
    pub segmentation: Spread,
    /// GP-KF over every cluster.
    pub gp_kf: Spread,
    /// GP-ICP on the hypotheses.
    pub gp_icp: Spread,
    /// The whole learned perception with one estimator: features, its GP step, the classifier,
    /// GP-KF and GP-ICP (`ScanTiming::learned_scan_secs`).
    pub learned_scan: Spread,
    /// CPU time of the whole learned scan, all threads (`ScanTiming::learned_scan_cpu_secs`).
    pub learned_scan_cpu: Option<Spread>,
}

impl PerceptionSummary {
    /// The summary of some scans under a name.
    pub fn of(name: &str, scans: &[&ScanTiming]) -> Self {
        let spread = |f: &dyn Fn(&ScanTiming) -> f64| Spread::of(scans.iter().map(|t| f(t)));
        // A timing only some runs take (CPU time): its spread when every scan has it.
        let every_scan = |f: &dyn Fn(&ScanTiming) -> Option<f64>| {
            scans
                .iter()
                .map(|t| f(t))
                .collect::<Option<Vec<f64>>>()
                .filter(|v| !v.is_empty())
                .map(|v| Spread::of(v.into_iter()))
        };
        let first_step = |f: fn(&StepTiming) -> usize| {
            let values = scans
                .iter()
                .filter_map(|t| t.estimators.first().map(|s| f(s) as f64));
            Spread::of(values).median_secs
        };
        let with_target: Vec<f64> = scans
            .iter()
            .filter(|t| t.target_secs > 0.0)
            .map(|t| t.target_points as f64)
            .collect();
        Self {
            name: name.to_owned(),
            scans: scans.len(),
            estimators: scans.first().map_or(0, |t| t.estimators.len()),
            stages: STAGES
                .iter()
                .map(|(label, f)| ((*label).to_owned(), spread(f)))
                .collect(),
            one_estimator: spread(&ScanTiming::one_estimator_secs),
            whole_scan_cpu: every_scan(&|t| t.whole_scan_cpu_secs),
            baselines: spread(&|t| t.baselines_secs),
            median_samples: first_step(|s| s.samples),
            median_points: first_step(|s| s.points),
            target: spread(&|t| t.target_secs),
            mean_target_points: (!with_target.is_empty())
                .then(|| with_target.iter().sum::<f64>() / with_target.len() as f64),
            segmentation: spread(&|t| t.segmentation_secs),
            gp_kf: spread(&|t| t.gp_kf_secs),
            gp_icp: spread(&|t| t.gp_icp_secs),
            learned_scan: spread(&ScanTiming::learned_scan_secs),
            learned_scan_cpu: every_scan(&|t| t.learned_scan_cpu_secs),
        }
    }

    /// One summary per sequence, then one over every scan (`all`).
    pub fn of_scenes(scenes: &[SceneResult]) -> Vec<Self> {
        let mut out: Vec<Self> = scenes
            .iter()
            .map(|s| Self::of(&s.name, &s.timing.iter().collect::<Vec<_>>()))
            .collect();
        let all: Vec<&ScanTiming> = scenes.iter().flat_map(|s| &s.timing).collect();
        out.push(Self::of("all", &all));
        out
    }

    /// The whole scan for every estimator.
    pub fn whole_scan(&self) -> Spread {
        self.stages.last().map_or_else(Spread::default, |s| s.1)
    }

    /// One line for the console: whole scan median and worst, per estimator and in total.
    pub fn line(&self) -> String {
        let ms = |s: f64| s * 1e3;
        let cpu = self.whole_scan_cpu.map_or(String::new(), |c| {
            format!(
                " (CPU {:.1} ms median, {:.1} ms worst)",
                ms(c.median_secs),
                ms(c.worst_secs)
            )
        });
        format!(
            "{} scans: whole scan {:.1} ms median, {:.1} ms worst{cpu} ({} estimators); one estimator {:.1} ms median, {:.1} ms worst; {:.0} map-cell samples of {:.0} points in the hypotheses (median)",
            self.scans,
            ms(self.whole_scan().median_secs),
            ms(self.whole_scan().worst_secs),
            self.estimators,
            ms(self.one_estimator.median_secs),
            ms(self.one_estimator.worst_secs),
            self.median_samples,
            self.median_points,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_summary_pools_every_scan_and_reads_each_stage() {
        let step = StepTiming {
            gp_secs: 0.02,
            samples: 300,
            points: 1200,
            ..StepTiming::default()
        };
        let scan = |maps: f64| ScanTiming {
            slice_secs: 0.001,
            maps_secs: maps,
            maps_and_clusters_secs: maps,
            estimators: vec![step],
            ..ScanTiming::default()
        };
        let scenes = [SceneResult {
            name: "s".into(),
            scans: 3,
            timing: vec![scan(0.01), scan(0.03), scan(0.02)],
            ..SceneResult::default()
        }];
        let all = PerceptionSummary::of_scenes(&scenes);
        assert_eq!(all.len(), 2);
        assert_eq!(all[1].name, "all");
        let whole = all[1].whole_scan();
        assert!((whole.median_secs - 0.041).abs() < 1e-12);
        assert!((whole.worst_secs - 0.051).abs() < 1e-12);
        assert_eq!(all[0].median_samples, 300.0);
        assert!(all[0].line().contains("41.0 ms median"));
        assert!(all[0].mean_target_points.is_none());
        assert!(all[0].learned_scan_cpu.is_none(), "no scan has a CPU time");
    }

    #[test]
    fn the_learned_scans_cpu_time_is_summarised_only_when_every_scan_has_one() {
        let scan = |cpu: Option<f64>| ScanTiming {
            learned_scan_cpu_secs: cpu,
            ..ScanTiming::default()
        };
        let timed = [scan(Some(0.09)), scan(Some(0.15)), scan(Some(0.12))];
        let spread = PerceptionSummary::of("s", &timed.iter().collect::<Vec<_>>())
            .learned_scan_cpu
            .expect("every scan has a CPU time");
        assert!((spread.median_secs - 0.12).abs() < 1e-12);
        assert!((spread.worst_secs - 0.15).abs() < 1e-12);
        let partly = [scan(Some(0.09)), scan(None)];
        let summary = PerceptionSummary::of("s", &partly.iter().collect::<Vec<_>>());
        assert!(summary.learned_scan_cpu.is_none());
    }
}
