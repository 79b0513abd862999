//! The measures a study's tables and plots show (heading and speed RMSE, coverage) and the
//! methods of a study in report order, shared by `study.md`, the findings and the plots.

use crate::methods::method::CANONICAL_METHODS;
use crate::study::point_result::Scores;
use crate::study::study_report::StudyReport;

/// A measure: title, file stem, decimals, and its value in a method's scores.
pub(crate) type Measure = (
    &'static str,
    &'static str,
    usize,
    fn(&Scores) -> Option<f64>,
);

/// The measures of the tables and plots.
pub(crate) const MEASURES: [Measure; 3] = [
    ("Heading RMSE (°)", "heading", 1, |s| s.heading_rmse_deg),
    ("Speed RMSE (m/s)", "speed", 2, |s| s.speed_rmse_mps),
    ("Coverage", "coverage", 2, |s| Some(s.coverage)),
];

/// Methods of a study in report order: the canonical eight, then any other (e.g. `ZERO-FLOW`).
pub(crate) fn study_methods(report: &StudyReport) -> Vec<String> {
    let mut methods: Vec<String> = CANONICAL_METHODS
        .iter()
        .map(|m| m.name().to_owned())
        .filter(|m| report.points.iter().any(|p| p.pooled.contains_key(m)))
        .collect();
    for point in &report.points {
        for m in point.pooled.keys() {
            if !methods.contains(m) {
                methods.push(m.clone());
            }
        }
    }
    methods
}
