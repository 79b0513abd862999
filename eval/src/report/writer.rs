//! Writes a whole benchmark report into a folder: `metrics.json`, `tables.csv`, `report.md` and
//! `plots/<situation>_heading.png`, `plots/<situation>_speed.png`.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use crate::error::EvalError;
use crate::report::csv::tables_csv;
use crate::report::files::{create_dir, write_atomic};
use crate::report::json::metrics_json;
use crate::report::markdown::{SituationMetrics, report_markdown};
use crate::report::plot::{plot_heading, plot_speed};
use crate::result::BenchmarkReport;

/// The files a report consists of.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReportFiles {
    /// `DIR/metrics.json`.
    pub metrics_json: PathBuf,
    /// `DIR/tables.csv`.
    pub tables_csv: PathBuf,
    /// `DIR/report.md`.
    pub report_md: PathBuf,
    /// `DIR/plots/*.png`, heading then speed per situation.
    pub plots: Vec<PathBuf>,
}

/// Scores every method of every situation and writes the report files into `dir` (created if needed).
/// Situation names must be unique and usable as file names (letters, digits, `_`, `-`, `.`).
///
/// ```no_run
/// use patchflow_eval::{BenchmarkReport, write_report};
/// let files = write_report(&BenchmarkReport::default(), std::path::Path::new("results/report")).unwrap();
/// println!("{}", files.report_md.display());
/// ```
pub fn write_report(report: &BenchmarkReport, dir: &Path) -> Result<ReportFiles, EvalError> {
    check_names(report)?;
    let metrics: Vec<SituationMetrics> = report
        .situations
        .iter()
        .map(|s| Ok((s.name.clone(), s.scans, s.metrics()?)))
        .collect::<Result<_, EvalError>>()?;

    let plots_dir = dir.join("plots");
    create_dir(&plots_dir)?;
    let files = ReportFiles {
        metrics_json: dir.join("metrics.json"),
        tables_csv: dir.join("tables.csv"),
        report_md: dir.join("report.md"),
        plots: report
            .situations
            .iter()
            .flat_map(|s| {
                [
                    plots_dir.join(format!("{}_heading.png", s.name)),
                    plots_dir.join(format!("{}_speed.png", s.name)),
                ]
            })
            .collect(),
    };
    let json = metrics_json(report).map_err(|err| match err {
        EvalError::Json { source, .. } => EvalError::Json {
            path: files.metrics_json.clone(),
            source,
        },
        other => other,
    })?;
    write_atomic(&files.metrics_json, json.as_bytes())?;
    write_atomic(&files.tables_csv, tables_csv(&metrics).as_bytes())?;
    write_atomic(
        &files.report_md,
        report_markdown(report, &metrics).as_bytes(),
    )?;
    for (situation, pair) in report.situations.iter().zip(files.plots.chunks(2)) {
        plot_heading(situation, &pair[0])?;
        plot_speed(situation, &pair[1])?;
    }
    Ok(files)
}

fn check_names(report: &BenchmarkReport) -> Result<(), EvalError> {
    let mut seen = BTreeSet::new();
    for s in &report.situations {
        let usable = !s.name.is_empty()
            && !s.name.starts_with('.')
            && s.name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'));
        if !usable {
            return Err(EvalError::BadResult {
                situation: s.name.clone(),
                reason: "a situation name must be letters, digits, '_', '-' or '.'".into(),
            });
        }
        if !seen.insert(s.name.as_str()) {
            return Err(EvalError::BadResult {
                situation: s.name.clone(),
                reason: "the situation appears twice".into(),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::synthetic::synthetic_report;

    #[test]
    fn the_writer_produces_every_file_for_a_two_situation_result() {
        let dir = tempfile::tempdir().unwrap();
        let files = write_report(&synthetic_report(), dir.path()).unwrap();
        for path in [&files.metrics_json, &files.tables_csv, &files.report_md] {
            assert!(
                std::fs::metadata(path).unwrap().len() > 100,
                "{}",
                path.display()
            );
        }
        assert_eq!(files.plots.len(), 4);
        for png in &files.plots {
            let bytes = std::fs::read(png).unwrap();
            assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{}", png.display());
        }
        assert!(dir.path().join("plots/situation4_speed.png").exists());
        // No temporary file is left behind.
        let leftovers: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .filter_map(Result::ok)
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty());
    }

    #[test]
    fn tables_csv_has_one_row_per_situation_and_method_in_canonical_order() {
        let dir = tempfile::tempdir().unwrap();
        let files = write_report(&synthetic_report(), dir.path()).unwrap();
        let csv = std::fs::read_to_string(&files.tables_csv).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 1 + 2 * 5);
        assert!(lines[0].starts_with("situation,method,scans,"));
        let methods: Vec<&str> = lines[1..6]
            .iter()
            .map(|l| l.split(',').nth(1).unwrap())
            .collect();
        assert_eq!(
            methods,
            ["SPGP-HET-ALL", "KF", "ICP", "KF-AUTO", "FULL-GP-ALL"]
        );
        assert!(lines.iter().skip(1).all(|l| l.split(',').count() == 11));
    }

    #[test]
    fn report_md_has_heading_and_speed_tables_with_the_thesis_numbers_labelled() {
        let dir = tempfile::tempdir().unwrap();
        let files = write_report(&synthetic_report(), dir.path()).unwrap();
        let md = std::fs::read_to_string(&files.report_md).unwrap();
        assert!(md.contains("## situation1 (30 scans)"));
        assert!(md.contains("### Heading (degrees; layout of thesis Table 4.6)"));
        assert!(md.contains("### Speed (m/s; layout of thesis Table 4.13)"));
        assert!(md.contains("Hess 2008 RMSE"));
        // Thesis Table 4.6, ICP: RMSE 33.76, ME 12.93, in the ICP row of situation1.
        let section = &md[md.find("## situation1").unwrap()..];
        let icp_row = section.lines().find(|l| l.starts_with("| ICP |")).unwrap();
        assert!(icp_row.ends_with("| 33.76 | 12.93 |"), "{icp_row}");
        assert!(md.contains("## Summary") && md.contains("## Timing") && md.contains("## Notes"));
        assert!(md.contains("synthetic results for a test"));
        assert!(md.contains("plots/situation4_heading.png"));
    }

    #[test]
    fn duplicate_or_unsafe_situation_names_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let mut report = synthetic_report();
        report.situations[1].name = "situation1".into();
        assert!(write_report(&report, dir.path()).is_err());
        report.situations[1].name = "../escape".into();
        assert!(write_report(&report, dir.path()).is_err());
    }

    #[test]
    fn a_method_with_the_wrong_number_of_estimates_is_an_error_naming_the_situation() {
        let dir = tempfile::tempdir().unwrap();
        let mut report = synthetic_report();
        report.situations[1]
            .methods
            .insert(crate::method::Method::Kf, vec![None; 3]);
        let err = write_report(&report, dir.path()).unwrap_err().to_string();
        assert!(err.contains("situation4") && err.contains("KF"), "{err}");
    }
}
