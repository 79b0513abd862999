//! What a benchmark run does: which scenarios, how many samples, pseudo-inputs, iterations and
//! folds. The full plan follows the thesis (4.3); the quick one is smaller.

use patchflow_learn::{EstimatorParams, GpKind};
use patchflow_occupancy::{AheadParams, OccupancyParams};
use patchflow_sim::{Realism, ScenarioSource};

use crate::cv::cv_params::CvParams;

/// The seed of every stage of the default benchmark, recorded in its outputs.
pub const BENCH_SEED: u64 = 7;

/// The training traffic of issue 24 that joined the default's training set beside the nine
/// hand-placed tracks of SPEC §3. The thesis preset trains on every training sequence but these,
/// so its rows stay on the thesis' data (and a bench on a user's own training scenarios trains it
/// on all of them).
pub const TRAINING_TRAFFIC: [&str; 2] = ["train10", "train12"];

/// Share of each training track's sweeps that `--quick` simulates: the track's last sweeps
/// (`short_tracks.rs` says why).
pub const QUICK_SWEEP_SHARE: f64 = 1.0 / 3.0;

/// The situations `--quick`'s realism study evaluates at every rung: the two in which the thesis
/// found ICP failing on real data (heading in situation 1, speed in situation 5; issue #10).
pub const QUICK_REALISM_SITUATIONS: [&str; 2] = ["situation1", "situation5"];

/// The rungs `--quick`'s realism study evaluates: `ideal` beside the `urban` evaluation (the
/// report's "Against the bar" section reads the same models on `ideal`); `harsh` is left out.
pub const QUICK_REALISM_RUNGS: [Realism; 2] = [Realism::Ideal, Realism::Urban];

/// The occupancy query times `--quick` maps (of the paper's t = 3 … 9): the two of its Figure 6
/// (the last, t = 9, is the full run's; each query time costs the quick run about 10 s of CPU,
/// docs/speed.md, stop 39).
pub const QUICK_OCCUPANCY_QUERY_SCANS: [usize; 2] = [3, 5];

/// The start scan `--quick` predicts ahead from (of the default 3 … 6).
pub const QUICK_AHEAD_START_SCANS: [usize; 1] = [3];

/// The dense random-traffic scene the whole-scan perception is also measured on
/// (`scenarios/dense_traffic.toml`; not a thesis situation, so it has no target).
pub const DENSE_TRAFFIC_TOML: &str = include_str!("../../../scenarios/dense_traffic.toml");

/// Everything a benchmark run does.
#[derive(Debug, Clone)]
pub struct BenchPlan {
    /// Training tracks, simulated into `OUT/data/train`.
    pub training: Vec<ScenarioSource>,
    /// Evaluation sequences (the situations and the dense scene), into `OUT/data/situations`.
    pub situations: Vec<ScenarioSource>,
    /// Occupancy-map scenarios (the DGPOM paper's T-junction and its training run), into
    /// `OUT/data/occupancy`; none skips the occupancy stage.
    pub occupancy: Vec<ScenarioSource>,
    /// The occupancy maps' query times (the paper's protocol by default).
    pub occupancy_params: OccupancyParams,
    /// DGPOM's predictions ahead: their start scans.
    pub ahead_params: AheadParams,
    /// GP kinds trained, one estimator each.
    pub gps: Vec<GpKind>,
    /// How the estimators are trained (their samples, pseudo-inputs, iterations and seed come
    /// from this plan): `EstimatorParams::default()`.
    pub estimator: EstimatorParams,
    /// Also train SPGP-HET by the thesis' protocol (`EstimatorParams::thesis`) for every seed
    /// and report its `SPGP-HET-ALL (thesis)` rows beside the default's.
    pub thesis_preset: bool,
    /// Importance-sampled training samples per estimator (thesis 4.3: 1,600).
    pub samples: usize,
    /// Pseudo-inputs per sparse GP (thesis 4.3: 100).
    pub pseudo_inputs: usize,
    /// Optimiser iterations per GP.
    pub max_iters: usize,
    /// Cross-validation (its sample sets are the first samples of the training draws).
    pub cv: CvParams,
    /// Seed of generation, sampling and training.
    pub seed: u64,
    /// Training draws (samples and GPs) with seeds `seed`, `seed + 1`, …; the report gives the
    /// mean ± std of the headline figures over them. The datasets are generated once.
    pub seeds: usize,
    /// Share of each training track's sweeps simulated (1 = all); `--quick` keeps every track but
    /// simulates fewer sweeps of each.
    pub training_sweep_share: f64,
    /// Keep the generated datasets under `OUT/data`; by default each is deleted once used.
    pub keep_data: bool,
    /// Whether this is the smaller `--quick` plan (noted in the report).
    pub quick: bool,
    /// The situations the realism study evaluates at every rung, by name; empty for all of them
    /// (`--quick` keeps [`QUICK_REALISM_SITUATIONS`], and its report says so).
    pub realism_situations: Vec<String>,
    /// The rungs the realism study evaluates; empty for all of them (`--quick` keeps
    /// `QUICK_REALISM_RUNGS`).
    pub realism_rungs: Vec<Realism>,
}

fn embedded(prefix: &str) -> Vec<ScenarioSource> {
    patchflow_sim::EMBEDDED_SCENARIOS
        .iter()
        .filter(|(name, _)| name.starts_with(prefix))
        .map(|&(name, text)| ScenarioSource::Embedded(name, text))
        .collect()
}

impl BenchPlan {
    /// The default run: every training track (the nine and the training traffic), the five
    /// situations and the dense scene; the thesis' samples, pseudo-inputs and priors; fewer
    /// folds and iterations for time.
    pub fn full() -> Self {
        let mut situations = embedded("situation");
        situations.push(ScenarioSource::Embedded(
            "dense_traffic",
            DENSE_TRAFFIC_TOML,
        ));
        Self {
            training: embedded("train"),
            situations,
            occupancy: patchflow_sim::EMBEDDED_OCCUPANCY_SCENARIOS
                .iter()
                .map(|&(name, text)| ScenarioSource::Embedded(name, text))
                .collect(),
            occupancy_params: OccupancyParams::default(),
            ahead_params: AheadParams::default(),
            gps: vec![GpKind::Spgp, GpKind::SpgpHet],
            estimator: EstimatorParams::default(),
            thesis_preset: true,
            samples: 1600,
            pseudo_inputs: 100,
            // 150 rather than 300 for time (issue 24's 6 minutes): docs/speed.md has the
            // figures over seeds 7-9 before and after.
            max_iters: 150,
            cv: CvParams {
                folds: 3,
                max_iters: 50,
                seed: BENCH_SEED,
                ..CvParams::default()
            },
            seed: BENCH_SEED,
            seeds: 3,
            training_sweep_share: 1.0,
            keep_data: false,
            quick: false,
            realism_situations: Vec::new(),
            realism_rungs: Vec::new(),
        }
    }

    /// `--quick`: the five situations without the dense scene; every training track but only
    /// the last third of its sweeps; SPGP-HET only (the thesis' headline GP; cross-validation
    /// still compares it with SPGP) with the default's samples, pseudo-inputs and iterations,
    /// and without the thesis preset's rows;
    /// a smaller cross-validation; one seed; a realism study on situations 1 and 5 at the `ideal` rung beside `urban`; and
    /// occupancy maps at two of the seven query times.
    pub fn quick() -> Self {
        let full = Self::full();
        let five = embedded("situation");
        Self {
            situations: five,
            gps: vec![GpKind::SpgpHet],
            occupancy_params: OccupancyParams {
                query_scans: QUICK_OCCUPANCY_QUERY_SCANS.to_vec(),
                ..full.occupancy_params.clone()
            },
            ahead_params: AheadParams {
                start_scans: QUICK_AHEAD_START_SCANS.to_vec(),
                ..full.ahead_params.clone()
            },
            training_sweep_share: QUICK_SWEEP_SHARE,
            seeds: 1,
            // A first look: the thesis preset's rows are the full run's (its sampling pass, its
            // fit and its per-target runs cost an eighth of the quick run's CPU; docs/speed.md, stop 39).
            thesis_preset: false,
            // The default's samples, pseudo-inputs and iterations: the quick run trains the
            // default's seed-7 model on a third of the sweeps (docs/speed.md, stop 38: 1,200
            // samples and 60 pseudo-inputs met the bar in 3 of 5 situations for the same CPU).
            cv: CvParams {
                folds: 2,
                samples: 600,
                pseudo_inputs: 30,
                max_iters: 60,
                seed: BENCH_SEED,
                ..CvParams::default()
            },
            quick: true,
            realism_situations: QUICK_REALISM_SITUATIONS.map(str::to_owned).to_vec(),
            realism_rungs: QUICK_REALISM_RUNGS.to_vec(),
            ..full
        }
    }

    /// The training seeds, `seed` first.
    pub fn training_seeds(&self) -> Vec<u64> {
        (0..self.seeds.max(1) as u64)
            .map(|k| self.seed + k)
            .collect()
    }

    /// Names of the GP kinds trained (`SPGP`, `SPGP-HET`), for the report and the stage lines.
    pub fn gp_names(&self) -> Vec<String> {
        self.gps.iter().map(|g| g.name().to_uppercase()).collect()
    }

    /// Names of the training tracks, for the report.
    pub fn training_names(&self) -> Vec<String> {
        self.training.iter().map(source_name).collect()
    }

    /// Names of the evaluated sequences, for the report.
    pub fn situation_names(&self) -> Vec<String> {
        self.situations.iter().map(source_name).collect()
    }
}

/// A scenario's name: the embedded name or the file stem.
pub(crate) fn source_name(source: &ScenarioSource) -> String {
    match source {
        ScenarioSource::Embedded(name, _) => (*name).to_owned(),
        ScenarioSource::File(path) => path.file_stem().map_or_else(
            || path.display().to_string(),
            |s| s.to_string_lossy().into_owned(),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_full_plan_trains_on_the_eleven_tracks_and_evaluates_six_sequences() {
        let plan = BenchPlan::full();
        assert_eq!(plan.training_names().len(), 11);
        let names = plan.training_names();
        assert!(
            TRAINING_TRAFFIC
                .iter()
                .all(|t| names.iter().any(|n| n == t))
        );
        assert_eq!(plan.situations.len(), 6);
        assert_eq!((plan.samples, plan.pseudo_inputs), (1600, 100));
        assert_eq!(plan.training_seeds(), [7, 8, 9]);
        let quick = BenchPlan::quick();
        assert_eq!(quick.training_names(), plan.training_names());
        assert!(quick.training_sweep_share < 1.0 && plan.training_sweep_share == 1.0);
        assert!(quick.quick && !plan.quick && !plan.keep_data);
    }

    #[test]
    fn the_quick_realism_study_keeps_situations_the_full_plan_has_and_the_full_one_keeps_all() {
        let full = BenchPlan::full();
        let names = full.situation_names();
        let quick = BenchPlan::quick();
        assert!(full.realism_situations.is_empty());
        assert!(!quick.realism_situations.is_empty());
        assert!(quick.realism_situations.iter().all(|n| names.contains(n)));
        assert!(full.realism_rungs.is_empty());
        assert!(quick.realism_rungs.contains(&Realism::Ideal));
        let quick_names = quick.situation_names();
        assert_eq!(quick_names.len(), 5);
        assert!(quick_names.iter().all(|n| n.starts_with("situation")));
    }

    #[test]
    fn the_quick_plan_trains_spgp_het_only_and_maps_a_subset_of_the_query_times() {
        let (full, quick) = (BenchPlan::full(), BenchPlan::quick());
        assert_eq!(full.gps, [GpKind::Spgp, GpKind::SpgpHet]);
        assert_eq!(quick.gps, [GpKind::SpgpHet]);
        let subset = |small: &[usize], large: &[usize]| {
            small.len() < large.len() && small.iter().all(|t| large.contains(t))
        };
        let (q, f) = (&quick.occupancy_params, &full.occupancy_params);
        assert!(subset(&q.query_scans, &f.query_scans));
        assert!(f.figure_scans.iter().all(|t| q.query_scans.contains(t)));
        assert!(subset(
            &quick.ahead_params.start_scans,
            &full.ahead_params.start_scans
        ));
        assert!(q.validate().is_ok());
    }

    #[test]
    fn the_dense_scene_loads_and_has_no_target() {
        let scenario = patchflow_sim::Scenario::from_toml(
            DENSE_TRAFFIC_TOML,
            "dense_traffic.toml",
            "dense_traffic",
        )
        .unwrap();
        assert!(scenario.actors.iter().all(|a| !a.target));
    }
}
