//! Heading RMSE of every method broken down by what makes a scan hard: the target's range (the
//! height slice holds fewer lidar rings the farther the target) and the number of its points in
//! the cluster (ICP needs enough of them to fix a rotation, thesis 4.4).

use std::fmt::Write as _;

use crate::scene::metrics::{MIN_SCORED_SPEED_MPS, heading_error_deg, rmse};
use crate::scene::result::SituationResult;
use crate::scene::truth_at_scan::TruthAtScan;

/// One breakdown: a title, column labels with the upper edge of each bin, and the scan's value.
struct Breakdown {
    title: &'static str,
    bins: [(&'static str, f64); 3],
    value: fn(&TruthAtScan) -> Option<f64>,
}

const BREAKDOWNS: [Breakdown; 2] = [
    Breakdown {
        title: "Heading RMSE (°) by the target's range",
        bins: [
            ("under 15 m", 15.0),
            ("15-30 m", 30.0),
            ("30 m and more", f64::INFINITY),
        ],
        value: |t| t.range_m,
    },
    Breakdown {
        title: "Heading RMSE (°) by the target's points in the height slice",
        bins: [
            ("under 50", 50.0),
            ("50-200", 200.0),
            ("200 and more", f64::INFINITY),
        ],
        value: |t| t.target_points.map(|n| n as f64),
    },
];

/// Writes every breakdown whose value is known for some scan of the situation.
pub(crate) fn breakdown_sections(md: &mut String, situation: &SituationResult) {
    for breakdown in &BREAKDOWNS {
        section(md, situation, breakdown);
    }
}

fn section(md: &mut String, situation: &SituationResult, breakdown: &Breakdown) {
    if situation
        .truth
        .iter()
        .all(|t| (breakdown.value)(t).is_none())
    {
        return;
    }
    let bin_of = |v: f64| breakdown.bins.iter().position(|(_, edge)| v < *edge);
    // Writing to a String cannot fail.
    let _ = writeln!(md, "#### {}\n", breakdown.title);
    let labels: Vec<&str> = breakdown.bins.iter().map(|(label, _)| *label).collect();
    let _ = writeln!(md, "| Method | {} |\n|---|---|---|---|", labels.join(" | "));
    for (method, estimates) in &situation.methods {
        let mut errors: [Vec<f64>; 3] = Default::default();
        for (truth, estimate) in situation.truth.iter().zip(estimates) {
            let (Some(e), Some(v)) = (estimate, (breakdown.value)(truth)) else {
                continue;
            };
            if truth.speed_mps < MIN_SCORED_SPEED_MPS {
                continue;
            }
            if let Some(bin) = bin_of(v) {
                errors[bin].push(heading_error_deg(e.heading_rad, truth.heading_rad));
            }
        }
        let cells: Vec<String> = errors
            .iter()
            .map(|e| match rmse(e) {
                Some(v) => format!("{v:.2} ({})", e.len()),
                None => "–".into(),
            })
            .collect();
        let _ = writeln!(md, "| {method} | {} |", cells.join(" | "));
    }
    let _ = writeln!(md, "\n*Scored scans in brackets.*\n");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::synthetic::synthetic_situation;

    fn bracket_counts(md: &str, row: &str) -> Vec<usize> {
        let line = md.lines().find(|l| l.starts_with(row)).unwrap();
        line.split('(')
            .skip(1)
            .map(|c| c.split(')').next().unwrap().parse().unwrap())
            .collect()
    }

    #[test]
    fn heading_errors_are_broken_down_by_the_targets_range_when_it_is_known() {
        let mut situation = synthetic_situation("situation3", 30, 4);
        for (k, truth) in situation.truth.iter_mut().enumerate() {
            truth.range_m = Some(5.0 + 1.5 * k as f64); // 5 m to 48.5 m: all three bins
        }
        let mut md = String::new();
        breakdown_sections(&mut md, &situation);
        assert!(md.contains("by the target's range"), "{md}");
        assert!(!md.contains("points in the height slice"), "{md}");
        let counts = bracket_counts(&md, "| KF |");
        assert_eq!(counts.len(), 3, "{md}");
        assert!(counts.iter().all(|&c| c > 0), "{md}");
    }

    #[test]
    fn heading_errors_are_broken_down_by_the_targets_points_when_they_are_known() {
        let mut situation = synthetic_situation("situation4", 30, 4);
        for (k, truth) in situation.truth.iter_mut().enumerate() {
            truth.target_points = Some(10 * k); // 0 to 290 points
        }
        let mut md = String::new();
        breakdown_sections(&mut md, &situation);
        assert!(md.contains("points in the height slice"), "{md}");
        assert!(!md.contains("by the target's range"), "{md}");
        let counts = bracket_counts(&md, "| ICP |");
        // Scans 0-4 (0-40 points): 0 and 1 too slow to score; 5-19: ICP skips scan 7; 20-29.
        assert_eq!(counts, vec![3, 14, 10], "{md}");
    }

    #[test]
    fn no_breakdown_is_written_without_ranges_or_points() {
        let mut md = String::new();
        breakdown_sections(&mut md, &synthetic_situation("situation1", 10, 1));
        assert!(md.is_empty());
    }
}
