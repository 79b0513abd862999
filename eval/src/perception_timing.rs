//! What the per-scan perception costs (SPEC §8: under 50 ms a scan), split the way the thesis
//! pipeline runs: maps and clusters once per scan, then patches and GP prediction per estimator.

/// Mean per-scan perception cost of a benchmark run.
///
/// ```
/// let scans = [
///     patchflow_eval::PerceptionTiming { maps_secs: 0.010, estimate_secs: 0.004, target_points: 100.0 },
///     patchflow_eval::PerceptionTiming { maps_secs: 0.012, estimate_secs: 0.006, target_points: 300.0 },
/// ];
/// let mean = patchflow_eval::PerceptionTiming::mean(&scans);
/// assert!((mean.per_estimator_secs() - 0.016).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PerceptionTiming {
    /// Reflection and difference maps and clusters (thesis 2.1-2.2.1), seconds.
    pub maps_secs: f64,
    /// Patches and GP prediction and merging for the target cluster (thesis 3.1), seconds, for
    /// one estimator (the mean over the estimators evaluated).
    pub estimate_secs: f64,
    /// Sliced points in the target cluster.
    pub target_points: f64,
}

impl PerceptionTiming {
    /// What one estimator needs per scan: its maps and clusters plus its prediction.
    pub fn per_estimator_secs(&self) -> f64 {
        self.maps_secs + self.estimate_secs
    }

    /// The mean over scans (zero for none).
    pub fn mean(scans: &[PerceptionTiming]) -> PerceptionTiming {
        let n = scans.len().max(1) as f64;
        let sum = |f: fn(&PerceptionTiming) -> f64| scans.iter().map(f).sum::<f64>() / n;
        PerceptionTiming {
            maps_secs: sum(|t| t.maps_secs),
            estimate_secs: sum(|t| t.estimate_secs),
            target_points: sum(|t| t.target_points),
        }
    }

    /// One line for reports: the split and the per-estimator total, in milliseconds.
    pub fn summary(&self) -> String {
        format!(
            "{:.1} ms per scan and estimator (maps and clusters {:.1} ms, patches and GP prediction for the target cluster of {:.0} points on average {:.1} ms)",
            self.per_estimator_secs() * 1e3,
            self.maps_secs * 1e3,
            self.target_points,
            self.estimate_secs * 1e3
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mean_of_no_scans_is_zero() {
        assert_eq!(PerceptionTiming::mean(&[]), PerceptionTiming::default());
    }

    #[test]
    fn the_summary_reports_milliseconds() {
        let t = PerceptionTiming {
            maps_secs: 0.0125,
            estimate_secs: 0.0031,
            target_points: 210.0,
        };
        let s = t.summary();
        assert!(s.starts_with("15.6 ms per scan and estimator"), "{s}");
        assert!(
            s.contains("12.5 ms") && s.contains("210 points") && s.contains("3.1 ms"),
            "{s}"
        );
    }
}
