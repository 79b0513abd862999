//! What a study's point was run with, written into its point file, so that the merge can refuse
//! points of another plan (a quick shard merged by a full `--merge`, another seed) and name the
//! difference instead of labelling the points with its own flags.

use serde::{Deserialize, Serialize};

use crate::pipeline::plan::source_name;
use crate::study::plan::StudyPlan;

/// The fixed parts of a study plan, as recorded beside each point's result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanStamp {
    /// The study's name (`realism`, `rate`, `channels`, `cell`).
    pub study: String,
    /// Seed of generation, sampling and training.
    pub seed: u64,
    /// Importance-sampled training samples per estimator.
    pub samples: usize,
    /// Pseudo-inputs per sparse GP.
    pub pseudo_inputs: usize,
    /// Optimiser iterations per GP.
    pub max_iters: usize,
    /// Share of each training track's sweeps simulated.
    pub training_sweep_share: f64,
    /// GP kinds trained.
    pub gps: Vec<String>,
    /// Training tracks, by name.
    pub training: Vec<String>,
    /// Evaluated situations, by name.
    pub situations: Vec<String>,
}

impl PlanStamp {
    /// The stamp of `plan`.
    pub fn of(plan: &StudyPlan) -> Self {
        Self {
            study: plan.factor.name().to_owned(),
            seed: plan.seed,
            samples: plan.samples,
            pseudo_inputs: plan.pseudo_inputs,
            max_iters: plan.max_iters,
            training_sweep_share: plan.training_sweep_share,
            gps: plan.gps.iter().map(|g| g.name().to_owned()).collect(),
            training: plan.training.iter().map(source_name).collect(),
            situations: plan.situations.iter().map(source_name).collect(),
        }
    }

    /// Every field where `recorded` (from a point file) differs from `self` (the merge's plan),
    /// as `field: points have A, this plan B`; empty when they agree.
    pub fn differences(&self, recorded: &PlanStamp) -> Vec<String> {
        let mut out = Vec::new();
        let mut check = |field: &str, ours: String, theirs: String| {
            if ours != theirs {
                out.push(format!("{field}: points have {theirs}, this plan {ours}"));
            }
        };
        check("study", self.study.clone(), recorded.study.clone());
        check("seed", self.seed.to_string(), recorded.seed.to_string());
        check(
            "samples",
            self.samples.to_string(),
            recorded.samples.to_string(),
        );
        check(
            "pseudo_inputs",
            self.pseudo_inputs.to_string(),
            recorded.pseudo_inputs.to_string(),
        );
        check(
            "max_iters",
            self.max_iters.to_string(),
            recorded.max_iters.to_string(),
        );
        check(
            "training_sweep_share",
            self.training_sweep_share.to_string(),
            recorded.training_sweep_share.to_string(),
        );
        check("gps", self.gps.join(","), recorded.gps.join(","));
        check(
            "training",
            self.training.join(","),
            recorded.training.join(","),
        );
        check(
            "situations",
            self.situations.join(","),
            recorded.situations.join(","),
        );
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::plan::BenchPlan;
    use crate::study::plan::StudyFactor;

    #[test]
    fn a_plan_agrees_with_its_own_stamp() {
        let plan = StudyPlan::from_bench(StudyFactor::Rate, &BenchPlan::full());
        assert!(
            PlanStamp::of(&plan)
                .differences(&PlanStamp::of(&plan))
                .is_empty()
        );
    }

    #[test]
    fn the_quick_plan_differs_from_the_full_one_in_the_training_share() {
        let full = PlanStamp::of(&StudyPlan::from_bench(
            StudyFactor::Rate,
            &BenchPlan::full(),
        ));
        let quick = PlanStamp::of(&StudyPlan::from_bench(
            StudyFactor::Rate,
            &BenchPlan::quick(),
        ));
        let differences = full.differences(&quick);
        assert!(
            differences
                .iter()
                .any(|d| d.starts_with("training_sweep_share:")),
            "{differences:?}"
        );
    }

    #[test]
    fn another_seed_is_named_with_both_values() {
        let plan = StudyPlan::from_bench(StudyFactor::Cell, &BenchPlan::full());
        let mut other = PlanStamp::of(&plan);
        other.seed = 99;
        let differences = PlanStamp::of(&plan).differences(&other);
        assert_eq!(
            differences,
            [format!("seed: points have 99, this plan {}", plan.seed)]
        );
    }

    #[test]
    fn a_stamp_survives_its_json_round_trip() {
        let stamp = PlanStamp::of(&StudyPlan::from_bench(
            StudyFactor::Channels,
            &BenchPlan::quick(),
        ));
        let text = serde_json::to_string(&stamp).unwrap();
        assert_eq!(serde_json::from_str::<PlanStamp>(&text).unwrap(), stamp);
    }
}
