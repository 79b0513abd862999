//! What a study runs (issue #10): one varied factor (the realism rung, the lidar rate, its
//! channels, the patch-map cell size), its points in sorted order, and everything else fixed and
//! seeded: the training tracks, the situations, samples, pseudo-inputs, iterations and the seed
//! of the benchmark.

use patchflow_learn::GpKind;
use patchflow_sim::{Realism, ScenarioSource};

use crate::error::EvalError;
use crate::pipeline::plan::BenchPlan;
use crate::study::sensor_setting::SensorSetting;

/// The factor a study varies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StudyFactor {
    /// The realism rung of the evaluated situations; models trained on the default rung (`urban`).
    Realism,
    /// The lidar's turn rate (Hz); each point trains and evaluates on its own data, of the same
    /// duration (sweeps scale with the rate).
    Rate,
    /// The lidar's channel count; each point trains and evaluates on its own data.
    Channels,
    /// The cell of the maps the patches sample (thesis 4.3: 0.10 m, the maps' own) with the patch
    /// kept at 11 × 11 cells, so the patch side follows the cell (0.55, 1.1, 2.2 m): finer maps
    /// and smaller patches (thesis Ch. 6). The clusters and the moving classifier keep their
    /// 0.10 m maps. Each point samples, trains and evaluates on its own features of the same
    /// sweeps.
    Cell,
    /// The cell and the rate together (thesis Ch. 6, "the higher the turning rate the smaller the
    /// map patches can be"): pairs of points that move an object by the same number of cells per
    /// sweep, a 10 Hz point and a 20 Hz point with cells half as large (0.10 m at 10 Hz beside
    /// 0.05 m at 20 Hz, 0.20 m beside 0.10 m). Each rate trains and evaluates on its own data;
    /// the points of one rate share their sweeps.
    CellRate,
}

impl StudyFactor {
    /// Every study `patchflow study NAME` knows.
    pub const ALL: [StudyFactor; 5] = [
        Self::Realism,
        Self::Rate,
        Self::Channels,
        Self::Cell,
        Self::CellRate,
    ];

    /// The study's name on the command line and in `study.json`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Realism => "realism",
            Self::Rate => "rate",
            Self::Channels => "channels",
            Self::Cell => "cell",
            Self::CellRate => "cell-rate",
        }
    }

    /// Parses a study name.
    ///
    /// ```
    /// use patchflow_eval::StudyFactor;
    /// assert_eq!(StudyFactor::parse("rate").unwrap(), StudyFactor::Rate);
    /// assert!(StudyFactor::parse("colour").is_err());
    /// ```
    pub fn parse(name: &str) -> Result<Self, EvalError> {
        Self::ALL
            .into_iter()
            .find(|f| f.name() == name)
            .ok_or_else(|| {
                let known: Vec<&str> = Self::ALL.iter().map(|f| f.name()).collect();
                EvalError::BadParameter {
                    name: "study",
                    reason: format!(
                        "unknown study {name:?}: expected one of {}",
                        known.join(", ")
                    ),
                }
            })
    }

    /// The unit of the factor's values. A `cell-rate` point's value is its cell times its rate:
    /// the speed at which an object moves one cell per sweep.
    pub fn unit(self) -> &'static str {
        match self {
            Self::Realism => "rung",
            Self::Rate => "Hz",
            Self::Channels => "channels",
            Self::Cell => "m",
            Self::CellRate => "m/s",
        }
    }

    /// The study's points in sorted order (mildest rung, lowest rate, fewest channels, finest
    /// cells first).
    pub fn points(self) -> Vec<StudyPoint> {
        match self {
            Self::Realism => Realism::ALL
                .into_iter()
                .enumerate()
                .map(|(k, rung)| StudyPoint {
                    index: k,
                    label: rung.name().to_owned(),
                    value: k as f64,
                    train: SensorSetting::default(),
                    evaluate: SensorSetting {
                        realism: Some(rung),
                        ..SensorSetting::default()
                    },
                })
                .collect(),
            Self::Rate => [5.0, 10.0, 20.0]
                .into_iter()
                .enumerate()
                .map(|(k, hz)| {
                    let setting = SensorSetting {
                        rate_hz: Some(hz),
                        ..SensorSetting::default()
                    };
                    StudyPoint::own_data(k, format!("{hz:.0} Hz"), hz, setting)
                })
                .collect(),
            Self::Channels => [16, 32, 64, 128]
                .into_iter()
                .enumerate()
                .map(|(k, channels)| {
                    let setting = SensorSetting {
                        channels: Some(channels),
                        ..SensorSetting::default()
                    };
                    StudyPoint::own_data(k, format!("{channels} ch"), f64::from(channels), setting)
                })
                .collect(),
            Self::Cell => CELL_SIZES_M
                .into_iter()
                .enumerate()
                .map(|(k, cell_m)| {
                    let setting = SensorSetting {
                        cell_m: Some(cell_m),
                        ..SensorSetting::default()
                    };
                    StudyPoint::own_data(k, format!("{cell_m:.2} m"), cell_m, setting)
                })
                .collect(),
            Self::CellRate => CELL_RATE_PAIRS
                .into_iter()
                .flat_map(|(coarse_m, fine_m)| [(coarse_m, 10.0), (fine_m, 20.0)])
                .enumerate()
                .map(|(k, (cell_m, hz))| {
                    let setting = SensorSetting {
                        rate_hz: Some(hz),
                        cell_m: Some(cell_m),
                        ..SensorSetting::default()
                    };
                    let label = format!("{cell_m:.2} m, {hz:.0} Hz");
                    StudyPoint::own_data(k, label, cell_m * hz, setting)
                })
                .collect(),
        }
    }
}

/// The `cell-rate` study's pairs of patch-map cells, metres: (the 10 Hz point's, the 20 Hz
/// point's), the second half the first, so an object moves by as many cells per sweep at both.
/// The first pair holds the thesis' 0.10 m at 10 Hz (4.3), the second the default's 0.20 m.
pub(crate) const CELL_RATE_PAIRS: [(f64, f64); 2] = [(0.10, 0.05), (0.20, 0.10)];

/// Patch-map cell sizes of the cell study, metres: half, once and twice the thesis' 0.10 m (4.3)
/// (the default's is 0.20 m, `patchflow_learn::WIDE_PATCH_CELL_M`). With
/// 11 × 11 cells the patch sides are 0.55, 1.1 and 2.2 m, and the thesis' range of detectable
/// speeds at 10 Hz (2-10 m/s for 0.10 m cells, 4.3) scales with the cell: 1-5 and 4-20 m/s.
pub const CELL_SIZES_M: [f64; 3] = [0.05, 0.10, 0.20];

/// One point of a study: the datasets it trains and evaluates on.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyPoint {
    /// Position in sorted order (the unit `--shard I/N` counts).
    pub index: usize,
    /// Label in tables and plots, e.g. `urban`, `20 Hz`.
    pub label: String,
    /// The factor's value (the rung's position for the realism study), for the plots' x axis.
    pub value: f64,
    /// Setting of the training tracks.
    pub train: SensorSetting,
    /// Setting of the evaluated situations.
    pub evaluate: SensorSetting,
}

impl StudyPoint {
    fn own_data(index: usize, label: String, value: f64, setting: SensorSetting) -> Self {
        Self {
            index,
            label,
            value,
            train: setting,
            evaluate: setting,
        }
    }
}

/// Everything a study runs; all but the factor's points come from a benchmark plan.
#[derive(Debug, Clone)]
pub struct StudyPlan {
    /// The varied factor.
    pub factor: StudyFactor,
    /// Its points in sorted order.
    pub points: Vec<StudyPoint>,
    /// Training tracks.
    pub training: Vec<ScenarioSource>,
    /// Share of each training track's sweeps simulated (1 = all; `--quick`: a third, as in
    /// `bench --quick`).
    pub training_sweep_share: f64,
    /// Evaluated situations (those with a target).
    pub situations: Vec<ScenarioSource>,
    /// GP kinds trained, one estimator each.
    pub gps: Vec<GpKind>,
    /// Importance-sampled training samples per estimator.
    pub samples: usize,
    /// Pseudo-inputs per sparse GP.
    pub pseudo_inputs: usize,
    /// Optimiser iterations per GP.
    pub max_iters: usize,
    /// Seed of generation, sampling and training.
    pub seed: u64,
}

impl StudyPlan {
    /// A study over `factor` with the training and the five situations of `bench` (the dense
    /// scene, which has no target, is left out).
    pub fn from_bench(factor: StudyFactor, bench: &BenchPlan) -> Self {
        Self {
            factor,
            points: factor.points(),
            training: bench.training.clone(),
            training_sweep_share: bench.training_sweep_share,
            situations: bench
                .situations
                .iter()
                .filter(|s| !matches!(s, ScenarioSource::Embedded("dense_traffic", _)))
                .cloned()
                .collect(),
            gps: bench.gps.clone(),
            samples: bench.samples,
            pseudo_inputs: bench.pseudo_inputs,
            max_iters: bench.max_iters,
            seed: bench.seed,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rate_study_has_three_rates_each_trained_on_its_own_data() {
        let points = StudyFactor::Rate.points();
        let rates: Vec<f64> = points.iter().map(|p| p.value).collect();
        assert_eq!(rates, [5.0, 10.0, 20.0]);
        assert!(points.iter().all(|p| p.train == p.evaluate));
    }

    #[test]
    fn the_realism_study_trains_every_rung_on_the_default_world() {
        let points = StudyFactor::Realism.points();
        assert_eq!(points.len(), 3);
        assert!(points.iter().all(|p| p.train == SensorSetting::default()));
        assert_eq!(points[2].evaluate.key(), "harsh");
    }

    #[test]
    fn the_cell_study_varies_only_the_features_so_its_points_share_their_sweeps() {
        let points = StudyFactor::Cell.points();
        let cells: Vec<f64> = points.iter().map(|p| p.value).collect();
        assert_eq!(cells, CELL_SIZES_M);
        assert!(points.iter().all(|p| p.train.data_key() == "default"));
        assert_eq!(points[0].train.key(), "0.05m");
        assert_eq!(points[2].evaluate.features().patch_cell_m, 0.2);
        assert_eq!(points[1].label, "0.10 m");
    }

    #[test]
    fn every_cell_of_the_cell_study_passes_the_feature_checks() {
        for point in StudyFactor::Cell.points() {
            point.train.features().check().unwrap();
        }
    }

    #[test]
    fn the_cell_rate_study_pairs_each_10_hz_cell_with_half_the_cell_at_20_hz() {
        let points = StudyFactor::CellRate.points();
        let settings: Vec<(f64, f64)> = points
            .iter()
            .map(|p| (p.train.cell_m.unwrap(), p.train.rate_hz.unwrap()))
            .collect();
        assert_eq!(
            settings,
            [(0.10, 10.0), (0.05, 20.0), (0.20, 10.0), (0.10, 20.0)]
        );
        // A pair moves an object by as many cells per sweep: equal cell × rate.
        let values: Vec<f64> = points.iter().map(|p| p.value).collect();
        assert_eq!(values, [1.0, 1.0, 2.0, 2.0]);
        assert!(points.iter().all(|p| p.train == p.evaluate));
        // The points of one rate share their sweeps, the two rates do not.
        assert_eq!(points[0].train.data_key(), points[2].train.data_key());
        assert_eq!(points[1].train.data_key(), "20hz");
        assert_ne!(points[0].train.data_key(), points[1].train.data_key());
        assert_eq!(points[1].label, "0.05 m, 20 Hz");
        for point in &points {
            point.train.features().check().unwrap();
        }
    }

    #[test]
    fn an_unknown_study_names_every_known_one() {
        let error = StudyFactor::parse("colour").unwrap_err().to_string();
        for factor in StudyFactor::ALL {
            assert!(error.contains(factor.name()), "{error}");
        }
    }

    #[test]
    fn the_study_of_the_bench_plan_leaves_out_the_dense_scene() {
        let plan = StudyPlan::from_bench(StudyFactor::Channels, &BenchPlan::full());
        assert_eq!(plan.situations.len(), 5);
        assert_eq!(plan.points.len(), 4);
    }
}
