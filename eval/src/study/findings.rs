//! What the thesis predicts for each study and what the study found, for `study.md`: the
//! prediction is the thesis' own words (Ch. 6 future work, 4.3, 4.4), the finding is computed
//! from `study.json` (per method, where along the factor the heading and speed errors are least
//! and how they move from the first point to the last), so it can never disagree with the tables.

use std::fmt::Write as _;

use crate::report::fmt_opt;
use crate::study::measures::{MEASURES, study_methods};
use crate::study::plan::StudyFactor;
use crate::study::study_report::StudyReport;

/// What the thesis predicts for a study, with its source.
pub(crate) fn thesis_prediction(factor: StudyFactor) -> &'static str {
    match factor {
        StudyFactor::Realism => {
            "The thesis (4.4, real data) finds the Kalman filter best on heading in most \
             situations, ICP hurt where few points hit the target, SPGP-HET better than SPGP where \
             the noise is learned well, and patches better than Gabor features. A cleaner world \
             should make every method better; a harsher one should hurt ICP most."
        }
        StudyFactor::Rate => {
            "\"In principle, a laser with a higher frequency should also result in better \
             features. The higher the turning rate the smaller the map patches can be\" (Ch. 6): \
             at a higher rate the object moves less between two sweeps, so the difference map \
             holds a smaller, cleaner motion signature, and the trackers get more observations."
        }
        StudyFactor::Channels => {
            "The thesis used a 64-channel HDL-64E and found ICP hurt by few points on the \
             object (4.4); more channels put more points on a target, so ICP and the map \
             features should gain most at range, and 16 channels should hurt ICP first."
        }
        StudyFactor::Cell => {
            "The patch must be \"large enough to capture the motion cues\" and \"small enough to \
             capture local motion features that are as independent of the structure of the \
             underlying object as possible\" (2.2.2); with 11 × 11 cells of 0.10 m at 10 Hz \
             \"we are able to detect motion within the range of 2-10 m/s\" (4.3), and smaller \
             patches mean \"a smaller dimensionality and problem size\" (Ch. 6). With the patch \
             kept at 11 × 11 cells, 0.05 m cells (0.55 m patches) should see 1-5 m/s and miss \
             faster cars' motion, 0.20 m cells (2.2 m patches) should see 4-20 m/s but blur \
             slow motion and capture more of the object's shape."
        }
        StudyFactor::CellRate => {
            "\"In principle, a laser with a higher frequency should also result in better \
             features. The higher the turning rate the smaller the map patches can be. Smaller \
             map patches means a smaller dimensionality and problem size\" (Ch. 6). At 20 Hz an \
             object moves half as far between sweeps as at 10 Hz, so cells half as large see it \
             move by as many cells (0.10 m at 10 Hz and 0.05 m at 20 Hz both see 2-10 m/s, 4.3): \
             if the claim holds, each 20 Hz point reads as well as the 10 Hz point beside it with \
             a patch half the side."
        }
    }
}

/// The computed findings: per method, heading and speed RMSE at the first and last point and
/// the point where each is least.
pub(crate) fn findings_section(report: &StudyReport, level: &str) -> String {
    let mut md = format!(
        "{level} What we find (computed from `study.json`)\n\n\
         | Method | measure | first → last point | least at |\n|---|---|---|---|\n"
    );
    let (Some(first), Some(last)) = (report.points.first(), report.points.last()) else {
        return md;
    };
    for method in study_methods(report) {
        for (title, _, decimals, value) in &MEASURES[..2] {
            let at =
                |p: &crate::study::point_result::PointResult| p.pooled.get(&method).and_then(value);
            let least = report
                .points
                .iter()
                .filter_map(|p| at(p).map(|v| (v, p.label.as_str())))
                .min_by(|a, b| a.0.total_cmp(&b.0));
            // Writing to a String cannot fail.
            let _ = writeln!(
                md,
                "| {method} | {title} | {} → {} | {} |",
                fmt_opt(at(first), *decimals),
                fmt_opt(at(last), *decimals),
                least.map_or("–".into(), |(v, label)| format!(
                    "{label} ({})",
                    fmt_opt(Some(v), *decimals)
                ))
            );
        }
    }
    md.push('\n');
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_study_states_a_prediction_that_quotes_or_names_the_thesis() {
        for factor in StudyFactor::ALL {
            let text = thesis_prediction(factor);
            assert!(text.contains("thesis") || text.contains('"'), "{text}");
        }
    }

    #[test]
    fn an_empty_study_has_a_findings_header_and_no_rows() {
        let report = StudyReport {
            study: "cell".into(),
            unit: "m".into(),
            seed: 1,
            samples: 10,
            pseudo_inputs: 2,
            max_iters: 3,
            point_bins: Vec::new(),
            points: Vec::new(),
        };
        let md = findings_section(&report, "##");
        assert_eq!(md.lines().count(), 4, "{md}");
    }
}
