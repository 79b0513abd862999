//! Cross-validation tables after thesis Tables 4.1-4.4: `cv.json` (all rows, sorted) and `cv.md`
//! (our numbers beside the thesis' own, labelled as such).

use std::fmt::Write as _;
use std::path::Path;

use crate::cv::cv_report::{CvFeature, CvGp, CvReport, CvRow};
use crate::error::EvalError;
use crate::report::files::{create_dir, fmt_opt, write_atomic};
use crate::report::thesis_tables::{
    THESIS_CV_HEADING_LOW_VAR_RMSE_DEG, THESIS_CV_HEADING_RMSE_DEG,
    THESIS_CV_SPEED_LOW_VAR_RMSE_MPS, THESIS_CV_SPEED_RMSE_MPS,
};

/// Writes `dir/cv.json` and `dir/cv.md`.
pub fn write_cv_report(report: &CvReport, dir: &Path) -> Result<(), EvalError> {
    create_dir(dir)?;
    let (json, markdown) = render_cv(report)?;
    write_atomic(&dir.join("cv.json"), json.as_bytes())?;
    write_atomic(&dir.join("cv.md"), markdown.as_bytes())
}

/// The text of `cv.json` and `cv.md`, rows sorted by feature, GP and prior.
pub(crate) fn render_cv(report: &CvReport) -> Result<(String, String), EvalError> {
    let mut rows = report.rows.clone();
    rows.sort_by(|a, b| {
        (a.feature, a.gp)
            .cmp(&(b.feature, b.gp))
            .then(a.prior.total_cmp(&b.prior))
    });
    let value = serde_json::json!({
        "folds": report.folds,
        "rows": rows,
        "version": env!("CARGO_PKG_VERSION"),
    });
    let mut text = serde_json::to_string_pretty(&value).map_err(|source| EvalError::Json {
        path: "cv.json".into(),
        source,
    })?;
    text.push('\n');
    Ok((text, cv_markdown(report.folds, &rows, &report.notes)))
}

fn find(rows: &[CvRow], feature: CvFeature, prior: f64, gp: CvGp) -> Option<&CvRow> {
    rows.iter()
        .find(|r| r.feature == feature && r.gp == gp && (r.prior - prior).abs() < 1e-9)
}

pub(crate) fn cv_markdown(folds: usize, rows: &[CvRow], notes: &[String]) -> String {
    let mut md = String::new();
    let gps = [CvGp::Spgp, CvGp::SpgpHet];
    // Writing to a String cannot fail.
    let _ = writeln!(
        md,
        "# Cross-validation ({folds} folds)\n\nRows **Hess 2008** are the thesis' own numbers \
         (real data, Tables 4.1-4.4), shown for orientation beside ours.\n"
    );
    let _ = writeln!(
        md,
        "## Heading RMSE (degrees), all test patches (layout of thesis Table 4.1)\n"
    );
    let _ = writeln!(
        md,
        "| GP | Gabor, prior 0.01 | Gabor, prior 0.5 | patch, prior 0.01 | patch, prior 0.5 |\n|---|---|---|---|---|"
    );
    let columns = [
        (CvFeature::Gabor, 0.01),
        (CvFeature::Gabor, 0.5),
        (CvFeature::Patch, 0.01),
        (CvFeature::Patch, 0.5),
    ];
    for gp in gps {
        let _ = write!(md, "| {} (ours) |", gp.name());
        for (feature, prior) in columns {
            let _ = write!(
                md,
                " {} |",
                fmt_opt(
                    find(rows, feature, prior, gp).map(|r| r.heading_rmse_deg),
                    2
                )
            );
        }
        let _ = write!(md, "\n| {} (Hess 2008) |", gp.name());
        for (feature, prior) in columns {
            let thesis = THESIS_CV_HEADING_RMSE_DEG
                .iter()
                .find(|(f, p, g, _)| {
                    *f == feature.name() && (*p - prior).abs() < 1e-9 && *g == gp.name()
                })
                .map(|t| t.3);
            let _ = write!(md, " {} |", fmt_opt(thesis, 2));
        }
        let _ = writeln!(md);
    }
    let _ = writeln!(
        md,
        "\n## Heading RMSE (degrees), low-variance patches, patch features (layout of thesis Table 4.2)\n"
    );
    let _ = writeln!(md, "| GP | prior 0.01 | prior 0.5 |\n|---|---|---|");
    for gp in gps {
        let ours = |prior| {
            find(rows, CvFeature::Patch, prior, gp).and_then(|r| r.heading_rmse_low_var_deg)
        };
        let thesis = |prior: f64| {
            THESIS_CV_HEADING_LOW_VAR_RMSE_DEG
                .iter()
                .find(|(p, g, _)| (*p - prior).abs() < 1e-9 && *g == gp.name())
                .map(|t| t.2)
        };
        let _ = writeln!(
            md,
            "| {} (ours) | {} | {} |",
            gp.name(),
            fmt_opt(ours(0.01), 2),
            fmt_opt(ours(0.5), 2)
        );
        let _ = writeln!(
            md,
            "| {} (Hess 2008) | {} | {} |",
            gp.name(),
            fmt_opt(thesis(0.01), 2),
            fmt_opt(thesis(0.5), 2)
        );
    }
    let _ = writeln!(
        md,
        "\n## Speed RMSE (m/s), patch features, prior 0.5 (layout of thesis Tables 4.3 and 4.4)\n"
    );
    let _ = writeln!(
        md,
        "| GP | all patches (ours) | all (Hess 2008, Table 4.3) | low variance (ours) | low variance (Hess 2008, Table 4.4) |\n|---|---|---|---|---|"
    );
    for gp in gps {
        let row = find(rows, CvFeature::Patch, 0.5, gp);
        let t43 = THESIS_CV_SPEED_RMSE_MPS
            .iter()
            .find(|(g, _)| *g == gp.name())
            .map(|t| t.1);
        let t44 = THESIS_CV_SPEED_LOW_VAR_RMSE_MPS
            .iter()
            .find(|(g, _)| *g == gp.name())
            .map(|t| t.1);
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} |",
            gp.name(),
            fmt_opt(row.and_then(|r| r.speed_rmse_mps), 2),
            fmt_opt(t43, 2),
            fmt_opt(row.and_then(|r| r.speed_rmse_low_var_mps), 2),
            fmt_opt(t44, 2),
        );
    }
    let _ = writeln!(md, "\n## All configurations\n");
    let _ = writeln!(
        md,
        "| feature | prior | GP | heading RMSE (°) | low-var heading RMSE (°) | speed RMSE (m/s) | low-var speed RMSE (m/s) | test patches | low-var patches |\n|---|---|---|---|---|---|---|---|---|"
    );
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.feature.name(),
            r.prior,
            r.gp.name(),
            fmt_opt(Some(r.heading_rmse_deg), 2),
            fmt_opt(r.heading_rmse_low_var_deg, 2),
            fmt_opt(r.speed_rmse_mps, 2),
            fmt_opt(r.speed_rmse_low_var_mps, 2),
            r.n_test,
            r.n_low_var
        );
    }
    let _ = writeln!(
        md,
        "\n## Notes\n\n- Low variance: a test patch whose predicted log variance is more than one standard \
         deviation below the mean of the predicted log variances (thesis 4.3.1 fits a Gaussian to the variances; they are right-skewed, so we fit it to their logarithms); for heading, on both \
         the sine and the cosine GP."
    );
    for note in notes {
        let _ = writeln!(md, "- {note}");
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(feature: CvFeature, prior: f64, gp: CvGp, heading: f64) -> CvRow {
        CvRow {
            feature,
            prior,
            gp,
            heading_rmse_deg: heading,
            heading_rmse_low_var_deg: Some(heading / 2.0),
            speed_rmse_mps: (feature == CvFeature::Patch).then_some(3.0),
            speed_rmse_low_var_mps: (feature == CvFeature::Patch).then_some(1.5),
            n_test: 1000,
            n_low_var: 150,
        }
    }

    #[test]
    fn cv_files_hold_every_row_and_both_sets_of_numbers() {
        let dir = tempfile::tempdir().unwrap();
        let mut rows = Vec::new();
        for (fi, feature) in [CvFeature::Patch, CvFeature::Gabor].into_iter().enumerate() {
            for prior in [0.5, 0.01] {
                for gp in [CvGp::SpgpHet, CvGp::Spgp] {
                    rows.push(row(feature, prior, gp, 40.0 + fi as f64 * 17.0 + prior));
                }
            }
        }
        let report = CvReport {
            folds: 5,
            rows,
            notes: vec!["synthetic".into()],
        };
        write_cv_report(&report, dir.path()).unwrap();

        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.path().join("cv.json")).unwrap())
                .unwrap();
        let rows = json["rows"].as_array().unwrap();
        assert_eq!(rows.len(), 8);
        assert_eq!(rows[0]["feature"], "patch");
        assert_eq!(rows[0]["gp"], "SPGP");
        assert_eq!(rows[0]["prior"], 0.01);
        assert_eq!(json["folds"], 5);

        let md = std::fs::read_to_string(dir.path().join("cv.md")).unwrap();
        assert!(
            md.contains("| SPGP (ours) | 57.01 | 57.50 | 40.01 | 40.50 |"),
            "{md}"
        );
        assert!(md.contains("| SPGP-HET (Hess 2008) | 59.79 | 62.21 | 44.06 | 42.51 |"));
        assert!(md.contains("| SPGP-HET | 3.00 | 3.21 | 1.50 | 1.53 |"));
        assert!(md.contains("synthetic"));
    }
}
