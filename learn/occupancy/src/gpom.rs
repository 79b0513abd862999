//! GP occupancy maps (GPOM; DGPOM paper, Section 2 and Table 1): a GP classifier by probabilistic
//! least squares from `patchflow-gp` (GP regression on ±1 labels, then a probit squashing whose
//! α, β maximise the leave-one-out predictive probability) trained on the window's samples.
//! GPOM in ℜ^D pools every scan's samples on (x, y) and ignores their times; GPOM in ℜ^{D+1} adds
//! the time as an input with its own learned (ARD) length-scale, so older scans count less where
//! the map changes. Both predict the probability of occupancy and the latent variance at the
//! query points at the query time.

use nalgebra::DMatrix;
use patchflow_gp::{PlsParams, Shape, Stationary};
use serde::{Deserialize, Serialize};

use crate::{
    GpSolver, MapMethod, MapMethodId, MapOutput, OccupancyError, OccupancySample, Result,
    SampleParams, ScanWindow, TEMPORAL_RANGE_SECS, window_samples,
};

/// Which inputs a GPOM sees.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum GpomSpace {
    /// ℜ^D: (x, y); every scan of the window pooled, time ignored.
    Space,
    /// ℜ^{D+1}: (x, y, t) with a learned temporal length-scale.
    SpaceTime,
}

/// Settings of a GP occupancy map.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GpomMethod {
    /// ℜ^D or ℜ^{D+1}.
    pub space: GpomSpace,
    /// How training samples are drawn from each scan.
    pub samples: SampleParams,
    /// Exact GP up to a few thousand training points, SPGP above.
    pub solver: GpSolver,
    /// Iteration limit of the marginal-likelihood maximisation.
    pub max_iters: usize,
    /// Iteration limit on the exact GP's path (at most `max_iters`), as DGPOM's: on the
    /// T-junction the iterations after the 25th, about 20 of 45-49 evaluations and 40 % of a
    /// map's CPU, moved no query time's AUC by more than 0.0001 (seed 7; seeds 8 and 9 in
    /// docs/occupancy.md). SPGP's fits keep `max_iters`.
    #[serde(default = "exact_max_iters")]
    pub exact_max_iters: usize,
    /// Range ℓt is held in (ℜ^{D+1}), seconds ([`TEMPORAL_RANGE_SECS`]).
    #[serde(default = "temporal_range_secs")]
    pub temporal_range_secs: [f64; 2],
}

fn temporal_range_secs() -> [f64; 2] {
    TEMPORAL_RANGE_SECS
}

fn exact_max_iters() -> usize {
    25
}

impl GpomMethod {
    /// GPOM in ℜ^D with the default settings.
    pub fn space(samples: SampleParams) -> Self {
        Self {
            space: GpomSpace::Space,
            samples,
            solver: GpSolver::default(),
            max_iters: 50,
            exact_max_iters: exact_max_iters(),
            temporal_range_secs: TEMPORAL_RANGE_SECS,
        }
    }

    /// GPOM in ℜ^{D+1} with the default settings.
    pub fn space_time(samples: SampleParams) -> Self {
        Self {
            space: GpomSpace::SpaceTime,
            ..Self::space(samples)
        }
    }

    /// The samples of every scan of `window`, oldest first (each scan's thinned if the sample
    /// parameters say so), and how many were drawn before thinning.
    pub fn training_samples(&self, window: &ScanWindow<'_>) -> (Vec<OccupancySample>, usize) {
        window_samples(window.scans, &self.samples)
    }

    /// The iteration limit of a map of `n` training points: `exact_max_iters` on the exact
    /// GP's path, `max_iters` on SPGP's.
    pub fn iterations(&self, n: usize) -> usize {
        match self.solver.is_exact(n) {
            true => self.max_iters.min(self.exact_max_iters),
            false => self.max_iters,
        }
    }

    fn inputs(&self, rows: impl ExactSizeIterator<Item = ([f64; 2], f64)>) -> DMatrix<f64> {
        let dims = match self.space {
            GpomSpace::Space => 2,
            GpomSpace::SpaceTime => 3,
        };
        let n = rows.len();
        let mut x = DMatrix::zeros(n, dims);
        for (i, (xy, t)) in rows.enumerate() {
            x[(i, 0)] = xy[0];
            x[(i, 1)] = xy[1];
            if dims == 3 {
                x[(i, 2)] = t;
            }
        }
        x
    }
}

impl MapMethod for GpomMethod {
    fn id(&self) -> MapMethodId {
        match self.space {
            GpomSpace::Space => MapMethodId::GpomRd,
            GpomSpace::SpaceTime => MapMethodId::GpomRd1,
        }
    }

    fn map(&self, window: &ScanWindow<'_>, points_m: &[[f64; 2]]) -> Result<MapOutput> {
        self.samples.validate()?;
        let scan = window.query_scan().map_or(0, |s| s.index);
        let degenerate = |reason: String| OccupancyError::Degenerate {
            method: self.id().name().to_owned(),
            scan,
            reason,
        };
        // Training data: returns occupied, free space along the beams (Section 2), thinned for
        // dense scans.
        let (samples, drawn) = self.training_samples(window);
        let x = self.inputs(samples.iter().map(|s| (s.xy_m, s.t_secs)));
        let labels: Vec<bool> = samples.iter().map(|s| s.occupied).collect();
        // GP classification by probabilistic least squares, α and β by leave-one-out (GPML §6.5).
        let gp = self
            .solver
            .params(samples.len(), self.samples.seed ^ scan as u64)
            .max_iters(self.iterations(samples.len()))
            // Squared exponential over (x, y) with ARD length-scales; in ℜ^{D+1} times a squared
            // exponential over t with its own, learned temporal length-scale.
            .kernel(match self.space {
                GpomSpace::Space => Stationary::se_ard(),
                GpomSpace::SpaceTime => {
                    // ℓt held in the range the window can identify; the fit sees t over its
                    // standard deviation, so the range is in those units.
                    let spread = model_input_spread(&x).get(2).copied().unwrap_or(1.0);
                    let spread = if spread > 1e-12 { spread } else { 1.0 };
                    let [lo, hi] = self.temporal_range_secs;
                    Stationary::space_time(2, Shape::SquaredExponential, Shape::SquaredExponential)
                        .bounded(2, lo / spread, hi / spread)
                        .map_err(|e| degenerate(e.to_string()))?
                }
            });
        let classifier = PlsParams::new(gp)
            .fit(&x, &labels)
            .map_err(|e| degenerate(e.to_string()))?;
        // Probability of occupancy and latent variance at the query points at the query time.
        let query = self.inputs(points_m.iter().map(|&p| (p, window.query_secs)));
        let prediction = classifier
            .predict(&query)
            .map_err(|e| degenerate(e.to_string()))?;
        let model = classifier.regression();
        let units = ["x", "y", "t"];
        let scales_in_units: Vec<f64> = model
            .lengthscales()
            .iter()
            .zip(model_input_spread(&x))
            .map(|(l, spread)| l * spread)
            .collect();
        let scales: Vec<String> = scales_in_units
            .iter()
            .zip(units)
            .map(|(l, axis)| {
                let unit = if axis == "t" { "s" } else { "m" };
                format!("ℓ{axis} {l:.2} {unit}")
            })
            .collect();
        let s = classifier.squashing();
        let report = model.fit_report();
        Ok(MapOutput {
            probability: prediction.probability.iter().copied().collect(),
            variance: Some(prediction.regression.var_latent.iter().copied().collect()),
            training_points: samples.len(),
            drawn_points: drawn,
            summary: format!(
                "{}, σ² = {:.3}, α = {:.2}, β = {:.2}, {} evaluations",
                scales.join(", "),
                model.noise_variance(),
                s.alpha,
                s.beta,
                report.evals
            ),
            solver: Some(self.solver.path(samples.len())),
            temporal_lengthscales: scales_in_units
                .get(2)
                .map(|&l| vec![[0.0, l]])
                .unwrap_or_default(),
        })
    }
}

/// Standard deviation of each input column (the unit of the model's standardised length-scales).
fn model_input_spread(x: &DMatrix<f64>) -> Vec<f64> {
    x.column_iter()
        .map(|c| {
            let mean = c.mean();
            (c.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / c.len().max(1) as f64).sqrt()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Beam, PlanarScan, roc_auc};

    /// A scan from the origin facing +y: 41 beams over 90°, a wall along y = 8 for x in [−4, 4]
    /// and, if `car`, a box at x in [−1, 1], y in [4, 5] in front of it.
    fn scan(index: usize, car: bool) -> PlanarScan {
        let beams = (0..41)
            .map(|j| {
                let a = (45.0 + 90.0 * f64::from(j) / 40.0).to_radians();
                let (c, s) = (a.cos(), a.sin());
                let wall = 8.0 / s;
                let range = if car && (c / s * 4.0).abs() <= 1.0 {
                    4.0 / s
                } else {
                    wall
                };
                let hit = (c * range).abs() <= 4.0;
                let r = if hit { range } else { 12.0 };
                Beam {
                    start_m: [0.0, 0.0],
                    end_m: [c * r, s * r],
                    hit,
                }
            })
            .collect();
        PlanarScan {
            index,
            stamp_secs: index as f64,
            sensor_m: [0.0, 0.0],
            yaw_rad: std::f64::consts::FRAC_PI_2,
            beams,
        }
    }

    fn method(space: GpomSpace) -> GpomMethod {
        GpomMethod {
            space,
            samples: SampleParams {
                free_spacing_m: 1.0,
                ..SampleParams::default()
            },
            solver: GpSolver {
                exact_up_to: 0,
                pseudo_inputs: 80,
                ..GpSolver::default()
            },
            max_iters: 40,
            exact_max_iters: 40,
            temporal_range_secs: TEMPORAL_RANGE_SECS,
        }
    }

    #[test]
    fn exact_maps_stop_at_the_exact_limit_and_sparse_ones_at_the_general_one() {
        let gpom = GpomMethod::space(SampleParams::default());
        assert_eq!((gpom.max_iters, gpom.exact_max_iters), (50, 25));
        let up_to = gpom.solver.exact_up_to;
        assert_eq!(gpom.iterations(up_to), 25);
        assert_eq!(gpom.iterations(up_to + 1), 50);
        // The exact limit never raises the general one.
        let capped = GpomMethod {
            max_iters: 10,
            ..gpom
        };
        assert_eq!(capped.iterations(100), 10);
        // A fit on the exact path stops at it: fewer evaluations at a limit of 2 than of 50.
        let scans = [scan(0, false), scan(1, true)];
        let window = ScanWindow {
            scans: &scans,
            query_secs: 1.0,
        };
        let evals = |limit: usize| -> usize {
            let exact = GpomMethod {
                exact_max_iters: limit,
                ..GpomMethod::space(SampleParams::default())
            };
            let out = exact.map(&window, &[[0.0, 4.0]]).unwrap();
            assert_eq!(out.solver.as_deref(), Some("exact"));
            out.summary
                .rsplit(", ")
                .next()
                .and_then(|e| e.strip_suffix(" evaluations"))
                .and_then(|e| e.parse().ok())
                .expect("evaluations in the summary")
        };
        let (short, long) = (evals(2), evals(50));
        assert!(
            short < long,
            "{short} evaluations at 2 iterations, {long} at 50"
        );
    }

    #[test]
    fn a_map_of_a_wall_ranks_the_wall_above_the_free_space_before_it() {
        let scans = [scan(0, false), scan(1, false)];
        let window = ScanWindow {
            scans: &scans,
            query_secs: 1.0,
        };
        let points: Vec<[f64; 2]> = (-3..=3)
            .flat_map(|x| {
                [
                    [f64::from(x), 8.0],
                    [f64::from(x), 4.0],
                    [f64::from(x), 2.0],
                ]
            })
            .collect();
        let truth: Vec<bool> = points.iter().map(|p| p[1] == 8.0).collect();
        let out = method(GpomSpace::Space).map(&window, &points).unwrap();
        let auc = roc_auc(&out.probability, &truth).unwrap();
        assert!(auc > 0.95, "AUC {auc}, {:?}", out.probability);
        assert_eq!(out.variance.as_ref().map(Vec::len), Some(points.len()));
        assert!(out.probability.iter().all(|p| (0.0..=1.0).contains(p)));
    }

    #[test]
    fn with_time_as_an_input_a_car_that_drove_away_weighs_less_than_without() {
        // A car stands in front of the wall in the first two scans and is gone in the last two.
        let scans = [scan(0, true), scan(1, true), scan(2, false), scan(3, false)];
        let window = ScanWindow {
            scans: &scans,
            query_secs: 3.0,
        };
        // Along the car's face, where its returns were.
        let at_car = [[-0.5, 4.0], [0.0, 4.0], [0.5, 4.0]];
        let mean = |m: GpomSpace| {
            let out = method(m).map(&window, &at_car).unwrap();
            out.probability.iter().sum::<f64>() / 3.0
        };
        let (space, space_time) = (mean(GpomSpace::Space), mean(GpomSpace::SpaceTime));
        assert!(
            space_time < space - 0.1,
            "R^D+1 {space_time} vs R^D {space}"
        );
    }
}
