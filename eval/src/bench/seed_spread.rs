//! Spread across training seeds: a benchmark trains with several seeds (each draws its own
//! importance samples, thesis 3.1.2, and fits its own GPs, 3.1.3, on the same datasets), and this
//! is the mean ± standard deviation over the seeds of each headline figure of every GP method,
//! so a reader can tell a real difference between methods from the noise of one training draw.
//! The baselines do not learn, so they give the same figures for every seed.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use serde::Serialize;

use crate::error::EvalError;
use crate::methods::method::Method;
use crate::report::fmt_opt;
use crate::scene::result::SituationResult;

/// One figure over the seeds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SeedFigure {
    /// Mean over the seeds that give the figure.
    pub mean: Option<f64>,
    /// Sample standard deviation (n − 1) over the same seeds; none below two seeds.
    pub std: Option<f64>,
    /// The figure per seed, in seed order (`null` where a seed gives none).
    pub values: Vec<Option<f64>>,
}

impl SeedFigure {
    fn of(values: Vec<Option<f64>>) -> Self {
        let present: Vec<f64> = values.iter().flatten().copied().collect();
        let n = present.len() as f64;
        let mean = (!present.is_empty()).then(|| present.iter().sum::<f64>() / n);
        let std = mean.filter(|_| present.len() >= 2).map(|m| {
            let square_sum: f64 = present.iter().map(|v| (v - m).powi(2)).sum();
            (square_sum / (n - 1.0)).sqrt()
        });
        Self { mean, std, values }
    }

    /// `mean ± std` with `decimals` decimals (`–` without a mean, no `±` without a spread).
    pub fn cell(&self, decimals: usize) -> String {
        match self.std {
            Some(std) => format!("{} ± {std:.decimals$}", fmt_opt(self.mean, decimals)),
            None => fmt_opt(self.mean, decimals),
        }
    }
}

/// The headline figures of one method in one situation over the seeds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MethodSpread {
    /// Heading RMSE, degrees.
    pub heading_rmse_deg: SeedFigure,
    /// Speed RMSE, m/s.
    pub speed_rmse_mps: SeedFigure,
    /// Share of scans with an estimate.
    pub coverage: SeedFigure,
}

/// Mean ± std over the training seeds, per situation (report order) and GP method.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SeedSpread {
    /// The training seeds, first the one of the main tables.
    pub seeds: Vec<u64>,
    /// Situation name → method → figures.
    pub situations: Vec<(String, BTreeMap<Method, MethodSpread>)>,
}

impl SeedSpread {
    /// The spread of the methods every seed's run has; `runs[k]` holds seed `seeds[k]`'s
    /// situations.
    pub fn of(seeds: &[u64], runs: &[Vec<SituationResult>]) -> Result<Self, EvalError> {
        let mut situations = Vec::new();
        let Some(first) = runs.first() else {
            return Ok(Self::default());
        };
        for situation in first {
            let mut scores = Vec::with_capacity(runs.len());
            for run in runs {
                let same = run.iter().find(|s| s.name == situation.name);
                scores.push(same.map(SituationResult::metrics).transpose()?);
            }
            let mut methods = BTreeMap::new();
            for method in situation.methods.keys() {
                let per_seed: Option<Vec<_>> = scores
                    .iter()
                    .map(|s| s.as_ref().and_then(|s| s.get(method)))
                    .collect();
                let Some(per_seed) = per_seed else { continue };
                let figure = |f: fn(&crate::scene::metrics::MethodMetrics) -> Option<f64>| {
                    SeedFigure::of(per_seed.iter().map(|m| f(m)).collect())
                };
                methods.insert(
                    *method,
                    MethodSpread {
                        heading_rmse_deg: figure(|m| m.heading_rmse_deg),
                        speed_rmse_mps: figure(|m| m.speed_rmse_mps),
                        coverage: figure(|m| Some(m.coverage)),
                    },
                );
            }
            situations.push((situation.name.clone(), methods));
        }
        Ok(Self {
            seeds: seeds.to_vec(),
            situations,
        })
    }

    /// The `seed_spread` entry of `metrics.json`: `{"seeds": [...], "situations": {name:
    /// {method: {"heading_rmse_deg": {"mean", "std", "values"}, "speed_rmse_mps": …,
    /// "coverage": …}}}}`.
    pub fn json(&self) -> serde_json::Value {
        let situations: BTreeMap<&str, BTreeMap<&str, &MethodSpread>> = self
            .situations
            .iter()
            .map(|(name, methods)| {
                let methods = methods.iter().map(|(m, s)| (m.name(), s)).collect();
                (name.as_str(), methods)
            })
            .collect();
        serde_json::json!({ "seeds": self.seeds, "situations": situations })
    }

    /// The report section: one row per situation and GP method.
    pub fn markdown(&self) -> String {
        let mut md = String::new();
        let seeds: Vec<String> = self.seeds.iter().map(u64::to_string).collect();
        let _ = writeln!(md, "## Spread over training seeds\n");
        let _ = writeln!(
            md,
            "Training seeds {}: each seed draws its own importance samples (thesis 3.1.2) and fits \
             its own GPs (3.1.3) on the same simulated data; mean ± standard deviation over the \
             seeds. The other tables of this report show seed {}. The baselines (KF, ICP and \
             their AUTO variants) do not learn, so they give the same figures for every seed.\n",
            seeds.join(", "),
            seeds.first().map_or("–", String::as_str)
        );
        let _ = writeln!(
            md,
            "| situation | method | heading RMSE (°) | speed RMSE (m/s) | coverage |"
        );
        let _ = writeln!(md, "|---|---|---|---|---|");
        for (name, methods) in &self.situations {
            for (method, spread) in methods {
                let _ = writeln!(
                    md,
                    "| {name} | {method} | {} | {} | {} |",
                    spread.heading_rmse_deg.cell(1),
                    spread.speed_rmse_mps.cell(2),
                    spread.coverage.cell(2)
                );
            }
        }
        md
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_figure_over_three_seeds_has_the_sample_standard_deviation() {
        let f = SeedFigure::of(vec![Some(1.0), Some(2.0), Some(3.0)]);
        assert!((f.mean.unwrap() - 2.0).abs() < 1e-12);
        assert!((f.std.unwrap() - 1.0).abs() < 1e-12);
        assert_eq!(f.cell(1), "2.0 ± 1.0");
    }

    #[test]
    fn a_figure_of_one_seed_has_no_spread_and_a_missing_value_is_left_out() {
        let one = SeedFigure::of(vec![Some(4.0)]);
        assert_eq!((one.std, one.cell(2)), (None, "4.00".to_owned()));
        let gap = SeedFigure::of(vec![Some(1.0), None, Some(3.0)]);
        assert!((gap.mean.unwrap() - 2.0).abs() < 1e-12);
        assert_eq!(gap.values.len(), 3);
        assert_eq!(SeedFigure::of(vec![None]).cell(1), "–");
    }

    #[test]
    fn the_spread_covers_the_methods_every_seed_has() {
        let report = crate::report::synthetic_report();
        let mut gp_only = report.situations.clone();
        for s in &mut gp_only {
            s.methods.retain(|m, _| *m == Method::SpgpHetAll);
        }
        let spread = SeedSpread::of(&[7, 8], &[report.situations.clone(), gp_only]).unwrap();
        assert_eq!(spread.situations.len(), report.situations.len());
        for (_, methods) in &spread.situations {
            assert_eq!(methods.keys().collect::<Vec<_>>(), [&Method::SpgpHetAll]);
            let figure = &methods[&Method::SpgpHetAll].heading_rmse_deg;
            assert_eq!(figure.std, Some(0.0), "the same estimates twice");
        }
        let json = spread.json();
        assert_eq!(json["seeds"], serde_json::json!([7, 8]));
        let md = spread.markdown();
        assert!(
            md.contains("| SPGP-HET-ALL |") && md.contains(" ± 0.0"),
            "{md}"
        );
    }
}
