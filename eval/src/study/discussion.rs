//! The synthetic-to-real discussion of a bench report (issue #10): for each finding of thesis
//! Section 4.5, the thesis' real-data figures (labelled as such) beside ours at each rung of the
//! realism study, and whether the rung reproduces it. Every figure is read from the study
//! (`realism/study.json`) or the cross-validation (`cv.json`) of the run; none is typed in.

use std::fmt::Write as _;

use crate::cv::cv_report::{CvFeature, CvGp, CvReport};
use crate::methods::method::{CANONICAL_METHODS, Method};
use crate::report::fmt_opt;
use crate::report::thesis_tables::{THESIS_CV_HEADING_RMSE_DEG, THESIS_SITUATIONS};
use crate::study::point_result::PointResult;
use crate::study::study_report::StudyReport;

/// The thesis' six methods (it has no `-AUTO` variants).
fn thesis_methods() -> &'static [Method] {
    &CANONICAL_METHODS[..6]
}

fn verdict(holds: bool) -> &'static str {
    if holds {
        "reproduced"
    } else {
        "not reproduced"
    }
}

/// Situations (of `rows`: situation → method → heading RMSE) where `winner` beats `others`.
fn wins(rows: &[Vec<(Method, Option<f64>)>], winner: Method, others: &[Method]) -> usize {
    rows.iter()
        .filter(|row| {
            let of = |m: Method| row.iter().find(|(x, _)| *x == m).and_then(|(_, v)| *v);
            let Some(w) = of(winner) else { return false };
            others
                .iter()
                .filter(|&&m| m != winner)
                .all(|&m| of(m).is_none_or(|v| w < v))
        })
        .count()
}

/// A rung's heading RMSE per situation and thesis method.
fn heading_rows(point: &PointResult) -> Vec<Vec<(Method, Option<f64>)>> {
    point
        .situations
        .values()
        .map(|methods| {
            thesis_methods()
                .iter()
                .map(|&m| (m, methods.get(m.name()).and_then(|s| s.heading_rmse_deg)))
                .collect()
        })
        .collect()
}

fn thesis_heading_rows() -> Vec<Vec<(Method, Option<f64>)>> {
    THESIS_SITUATIONS
        .iter()
        .map(|s| s.heading.iter().map(|r| (r.method, Some(r.rmse))).collect())
        .collect()
}

/// The discussion section, headings at `level`.
pub fn discussion_section(study: &StudyReport, cv: Option<&CvReport>, level: &str) -> String {
    let mut md = format!(
        "{level} Synthetic to real: which rung reproduces the thesis' findings (Section 4.5)\n\n\
         Thesis figures are from its real Urban Challenge data (Tables 4.1-4.15), not from our simulation; ours are from `realism/study.json` and `cv.json` of this run.\n\n"
    );
    let n = THESIS_SITUATIONS.len();
    // 1. KF best on heading in most situations.
    let thesis_kf = wins(&thesis_heading_rows(), Method::Kf, thesis_methods());
    let _ = writeln!(
        md,
        "1. **KF best on heading in most situations.** Thesis (real data): KF has the lowest heading RMSE of the six methods in {thesis_kf} of {n} situations."
    );
    for p in &study.points {
        let k = wins(&heading_rows(p), Method::Kf, thesis_methods());
        let m = p.situations.len();
        let _ = writeln!(
            md,
            "   - `{}`: in {k} of {m}, {}.",
            p.label,
            verdict(2 * k > m)
        );
    }
    // 2. ICP hurt by few points.
    let icp_worst = THESIS_SITUATIONS
        .iter()
        .filter_map(|s| {
            s.heading
                .iter()
                .find(|r| r.method == Method::Icp)
                .map(|r| (s.situation, r.rmse))
        })
        .fold(("", 0.0_f64), |a, b| if b.1 > a.1 { b } else { a });
    let icp_speed = THESIS_SITUATIONS
        .iter()
        .filter_map(|s| {
            s.speed
                .iter()
                .find(|r| r.method == Method::Icp)
                .map(|r| (s.situation, r.rmse))
        })
        .fold(("", 0.0_f64), |a, b| if b.1 > a.1 { b } else { a });
    let _ = writeln!(
        md,
        "2. **ICP hurt by few points.** Thesis (real data): ICP's heading RMSE reached {:.1}° ({}), its speed RMSE {:.1} m/s ({}). Ours, ICP's heading RMSE (°) with fewer than 50 target points against 200 and more (reproduced where the first is at least 1.5 × the second):",
        icp_worst.1, icp_worst.0, icp_speed.1, icp_speed.0
    );
    for p in &study.points {
        let bins = p.by_points.get(Method::Icp.name());
        let few = bins
            .and_then(|b| b.first())
            .and_then(|s| s.heading_rmse_deg);
        let many = bins.and_then(|b| b.last()).and_then(|s| s.heading_rmse_deg);
        let pooled = p.pooled.get(Method::Icp.name());
        let holds = matches!((few, many), (Some(f), Some(m)) if f >= 1.5 * m);
        let _ = writeln!(
            md,
            "   - `{}`: {} against {} (all scans: {}° heading, {} m/s speed), {}.",
            p.label,
            fmt_opt(few, 1),
            fmt_opt(many, 1),
            fmt_opt(pooled.and_then(|s| s.heading_rmse_deg), 1),
            fmt_opt(pooled.and_then(|s| s.speed_rmse_mps), 2),
            if few.is_none() || many.is_none() {
                "not measurable (a bin is empty)"
            } else {
                verdict(holds)
            }
        );
    }
    // 3. SPGP-HET better than SPGP.
    let pair = [Method::SpgpHetAll, Method::SpgpAll];
    let thesis_het = wins(&thesis_heading_rows(), Method::SpgpHetAll, &pair);
    let _ = writeln!(
        md,
        "3. **SPGP-HET better than SPGP where the noise is learned well.** Thesis (real data): SPGP-HET-ALL beats SPGP-ALL on heading in {thesis_het} of {n} situations."
    );
    for p in &study.points {
        let k = wins(&heading_rows(p), Method::SpgpHetAll, &pair);
        let m = p.situations.len();
        let _ = writeln!(
            md,
            "   - `{}`: in {k} of {m}, {}.",
            p.label,
            verdict(2 * k > m)
        );
    }
    // 4. Patches beat Gabor (cross-validation on the training rung).
    let thesis_best = |feature: &str| {
        THESIS_CV_HEADING_RMSE_DEG
            .iter()
            .filter(|r| r.0 == feature)
            .map(|r| r.3)
            .fold(f64::INFINITY, f64::min)
    };
    let _ = write!(
        md,
        "4. **Map patches beat Gabor features.** Thesis (real data, Table 4.1): best heading RMSE {:.1}° with patches against {:.1}° with Gabor features.",
        thesis_best("patch"),
        thesis_best("gabor")
    );
    let ours = |feature: CvFeature| {
        cv.map(|c| {
            c.rows
                .iter()
                .filter(|r| r.feature == feature && matches!(r.gp, CvGp::Spgp | CvGp::SpgpHet))
                .map(|r| r.heading_rmse_deg)
                .fold(f64::INFINITY, f64::min)
        })
        .filter(|v| v.is_finite())
    };
    match (ours(CvFeature::Patch), ours(CvFeature::Gabor)) {
        (Some(p), Some(g)) => {
            let _ = writeln!(
                md,
                " Ours (cross-validation on the training rung `urban`): {p:.1}° against {g:.1}°, {}. The other rungs are not cross-validated.",
                verdict(p < g)
            );
        }
        _ => {
            let _ = writeln!(
                md,
                " Not measured in this run (no cross-validation with both features)."
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
    fn the_thesis_has_kf_best_on_heading_in_some_situations_and_het_beating_spgp_in_some() {
        let kf = wins(&thesis_heading_rows(), Method::Kf, thesis_methods());
        let het = wins(
            &thesis_heading_rows(),
            Method::SpgpHetAll,
            &[Method::SpgpHetAll, Method::SpgpAll],
        );
        assert!((1..=5).contains(&kf), "{kf}");
        assert!(het <= 5);
    }

    #[test]
    fn a_method_wins_a_situation_only_below_every_other() {
        let rows = vec![
            vec![(Method::Kf, Some(1.0)), (Method::Icp, Some(2.0))],
            vec![(Method::Kf, Some(3.0)), (Method::Icp, Some(2.0))],
            vec![(Method::Kf, None), (Method::Icp, Some(2.0))],
        ];
        assert_eq!(wins(&rows, Method::Kf, &[Method::Kf, Method::Icp]), 1);
    }
}
