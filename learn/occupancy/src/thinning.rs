//! Thinning a dense scan's training samples to a budget (what it takes to map a 3-D lidar's height
//! slice with the same GPs as a planar scan). A 64-channel sweep cut to the 0.5-1.0 m slice gives
//! thousands of returns on every nearby car (several channels cross the slice there, 0.2° apart)
//! and tens of thousands of free samples along the sliced beams; an SPGP costs O(N M²) and
//! the data say no more about a 0.5 m query lattice at that density. So each scan's samples are
//! thinned on a square lattice in the plane: per cell and class (occupied, free) the sample nearest
//! the cell centre is kept (ties to the earlier sample), starting at `start_cell_m` and growing
//! the cell by √2 until the scan fits `budget_per_scan`. Deterministic (no random draw, kept
//! samples stay in their order) and the same for every method that thins.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::{OccupancyError, Result};

/// How a scan's samples are thinned.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Thinning {
    /// Most samples kept per scan (at least 2: one of each class fits in any cell).
    pub budget_per_scan: usize,
    /// Side of the first lattice tried, metres.
    pub start_cell_m: f64,
}

impl Default for Thinning {
    /// 2,000 samples per scan: about what the planar scanner gives on the busy intersection
    /// (8,300 per four-scan map), so a 3-D slice map costs what a planar one does and the two are
    /// compared on their data, not its amount. 0.25 m: half the 0.5 m query lattice.
    fn default() -> Self {
        Self {
            budget_per_scan: 2_000,
            start_cell_m: 0.25,
        }
    }
}

impl Thinning {
    /// Checks the parameters; an error names the bad field.
    pub fn validate(&self) -> Result<()> {
        if self.budget_per_scan < 2 {
            return Err(OccupancyError::BadParameter {
                name: "Thinning.budget_per_scan",
                reason: format!("must be at least 2, got {}", self.budget_per_scan),
            });
        }
        if !(self.start_cell_m.is_finite() && self.start_cell_m > 0.0) {
            return Err(OccupancyError::BadParameter {
                name: "Thinning.start_cell_m",
                reason: format!("must be positive, got {}", self.start_cell_m),
            });
        }
        Ok(())
    }

    /// Which of one scan's samples, given as (position in the plane, occupied), are kept: their
    /// indices in order; a scan within the budget is kept whole.
    ///
    /// ```
    /// use patchflow_occupancy::Thinning;
    /// let line: Vec<([f64; 2], bool)> = (0..1000).map(|i| ([i as f64 * 0.01, 0.0], true)).collect();
    /// let thin = Thinning { budget_per_scan: 100, start_cell_m: 0.05 };
    /// assert!(thin.kept(&line).len() <= 100);
    /// ```
    pub fn kept(&self, samples: &[([f64; 2], bool)]) -> Vec<usize> {
        if samples.len() <= self.budget_per_scan {
            return (0..samples.len()).collect();
        }
        let mut cell_m = self.start_cell_m;
        loop {
            let kept = kept_indices(samples, cell_m);
            // Terminates: once one cell holds every sample, at most one per class is kept.
            if kept.len() <= self.budget_per_scan {
                return kept;
            }
            cell_m *= std::f64::consts::SQRT_2;
        }
    }
}

/// Indices of the samples kept on a lattice of `cell_m`: per cell and class, the one nearest
/// the cell centre (the earlier on a tie), sorted.
fn kept_indices(samples: &[([f64; 2], bool)], cell_m: f64) -> Vec<usize> {
    let mut best: BTreeMap<(i64, i64, bool), (f64, usize)> = BTreeMap::new();
    for (i, &(xy_m, occupied)) in samples.iter().enumerate() {
        let (u, v) = (xy_m[0] / cell_m, xy_m[1] / cell_m);
        let cell = (u.floor() as i64, v.floor() as i64, occupied);
        let d2 = (u - u.floor() - 0.5).powi(2) + (v - v.floor() - 0.5).powi(2);
        best.entry(cell)
            .and_modify(|b| {
                if d2 < b.0 {
                    *b = (d2, i);
                }
            })
            .or_insert((d2, i));
    }
    let mut kept: Vec<usize> = best.values().map(|&(_, i)| i).collect();
    kept.sort_unstable();
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A seeded cloud: 5,000 free samples over 40 m × 40 m, 3,000 occupied ones on a 10 m wall.
    fn cloud() -> Vec<([f64; 2], bool)> {
        let mut z: u64 = 12345;
        let mut next = || {
            z = z.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            (z >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut out = Vec::new();
        for i in 0..8000 {
            let occupied = i % 8 < 3;
            let xy_m = if occupied {
                [10.0 * next(), 20.0 + 0.1 * next()]
            } else {
                [40.0 * next() - 20.0, 40.0 * next() - 20.0]
            };
            out.push((xy_m, occupied));
        }
        out
    }

    #[test]
    fn thinning_keeps_the_budget_both_classes_and_the_original_order() {
        let samples = cloud();
        for budget in [2, 50, 700, 2000] {
            let thin = Thinning {
                budget_per_scan: budget,
                ..Thinning::default()
            };
            let kept = thin.kept(&samples);
            assert!(kept.len() <= budget, "{} > {budget}", kept.len());
            assert!(kept.iter().any(|&i| samples[i].1) && kept.iter().any(|&i| !samples[i].1));
            // Kept samples stay in the input's order, each once.
            assert!(kept.windows(2).all(|w| w[0] < w[1]));
        }
    }

    #[test]
    fn thinning_is_deterministic_and_leaves_a_scan_within_budget_whole() {
        let samples = cloud();
        let thin = Thinning::default();
        let once = thin.kept(&samples);
        assert!(once.len() > 1000, "{}", once.len());
        assert_eq!(once, thin.kept(&samples));
        assert_eq!(thin.kept(&samples[..1500]), (0..1500).collect::<Vec<_>>());
    }

    #[test]
    fn thinning_spreads_the_kept_samples_over_the_area() {
        // The kept free samples still cover each quadrant of the square, about equally.
        let thin = Thinning {
            budget_per_scan: 400,
            ..Thinning::default()
        };
        let samples = cloud();
        let free: Vec<[f64; 2]> = thin
            .kept(&samples)
            .into_iter()
            .filter(|&i| !samples[i].1)
            .map(|i| samples[i].0)
            .collect();
        for (sx, sy) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            let n = free
                .iter()
                .filter(|p| p[0] * sx > 0.0 && p[1] * sy > 0.0)
                .count() as f64;
            let share = n / free.len() as f64;
            assert!((0.15..0.35).contains(&share), "quadrant share {share}");
        }
    }

    #[test]
    fn a_budget_below_two_is_refused_by_name() {
        let err = Thinning {
            budget_per_scan: 1,
            ..Thinning::default()
        }
        .validate()
        .unwrap_err();
        assert!(err.to_string().contains("budget_per_scan"), "{err}");
    }
}
