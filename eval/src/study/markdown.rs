//! `study.md`: what was varied and what was held fixed, what the thesis predicts, then one table
//! per measure (every method against the factor, the five situations pooled), the scene-flow
//! EPE of every method with `ZERO-FLOW`, what we find, the heading and speed errors by the
//! target's points, and each point's per-situation table. Every number comes from `study.json`.

use std::fmt::Write as _;

use crate::methods::method::CANONICAL_METHODS;
use crate::report::fmt_opt;
use crate::study::findings::{findings_section, thesis_prediction};
use crate::study::measures::{MEASURES, study_methods};
use crate::study::plan::StudyFactor;
use crate::study::study_report::StudyReport;

/// The whole `study.md`.
pub fn study_markdown(report: &StudyReport) -> String {
    let mut md = format!("# Study: {}\n\n", report.study);
    md.push_str(&study_section(report, "##"));
    md
}

/// The study's tables under headings of level `level` (`##` in `study.md`, `###` in a bench report).
pub fn study_section(report: &StudyReport, level: &str) -> String {
    let mut md = String::new();
    let labels: Vec<&str> = report.points.iter().map(|p| p.label.as_str()).collect();
    let settings: Vec<String> = report
        .points
        .iter()
        .map(|p| {
            format!(
                "{}: trained on `{}`, evaluated on `{}`",
                p.label, p.train, p.evaluate
            )
        })
        .collect();
    // Writing to a String cannot fail.
    let _ = writeln!(
        md,
        "Varied: {} ({}); everything else fixed: seed {}, {} samples, {} pseudo-inputs, at most {} iterations per GP. Points: {}.\n",
        report.study,
        report.unit,
        report.seed,
        report.samples,
        report.pseudo_inputs,
        report.max_iters,
        settings.join("; ")
    );
    if let Ok(factor) = StudyFactor::parse(&report.study) {
        let _ = writeln!(
            md,
            "What the thesis predicts: {}\n",
            thesis_prediction(factor)
        );
    }
    let methods = study_methods(report);
    let header = |md: &mut String, first: &str| {
        let _ = writeln!(
            md,
            "| {first} | {} |\n|---|{}",
            labels.join(" | "),
            "---|".repeat(labels.len())
        );
    };
    for (title, stem, decimals, value) in MEASURES {
        let _ = writeln!(md, "{level} {title}, the situations pooled\n");
        header(&mut md, "Method");
        for m in &methods {
            let cells: Vec<String> = report
                .points
                .iter()
                .map(|p| fmt_opt(p.pooled.get(m).and_then(value), decimals))
                .collect();
            let _ = writeln!(md, "| {m} | {} |", cells.join(" | "));
        }
        let _ = writeln!(
            md,
            "\n![{title}](plots/study_{}_{stem}.png)\n",
            report.study
        );
    }
    md.push_str(&scene_flow_table(report, level));
    md.push_str(&findings_section(report, level));
    for (title, _, decimals, value) in &MEASURES[..2] {
        let _ = writeln!(
            md,
            "{level} {title} by the target's points in the height slice ({})\n",
            report.point_bins.join(" / ")
        );
        header(&mut md, "Method");
        for m in &methods {
            let cells: Vec<String> = report
                .points
                .iter()
                .map(|p| match p.by_points.get(m) {
                    Some(bins) => bins
                        .iter()
                        .map(|b| format!("{} ({})", fmt_opt(value(b), *decimals), b.scans))
                        .collect::<Vec<_>>()
                        .join(" / "),
                    None => "–".into(),
                })
                .collect();
            let _ = writeln!(md, "| {m} | {} |", cells.join(" | "));
        }
        let _ = writeln!(md, "\n*Scans of each bin in brackets.*\n");
    }
    for point in &report.points {
        let names: Vec<&String> = point.situations.keys().collect();
        let _ = writeln!(
            md,
            "{level} {}: heading RMSE (°) / speed RMSE (m/s) / coverage per situation\n",
            point.label
        );
        let _ = writeln!(
            md,
            "| Method | {} |\n|---|{}",
            names
                .iter()
                .map(|n| n.as_str())
                .collect::<Vec<_>>()
                .join(" | "),
            "---|".repeat(names.len())
        );
        for m in &methods {
            let cells: Vec<String> = point
                .situations
                .values()
                .map(|s| match s.get(m) {
                    Some(x) => format!(
                        "{} / {} / {:.2}",
                        fmt_opt(x.heading_rmse_deg, 1),
                        fmt_opt(x.speed_rmse_mps, 2),
                        x.coverage
                    ),
                    None => "–".into(),
                })
                .collect();
            let _ = writeln!(md, "| {m} | {} |", cells.join(" | "));
        }
        md.push('\n');
    }
    md
}

/// Every method's scene flow against the factor, `ZERO-FLOW` included (it has no target
/// estimate, so it is only here): mean EPE over every scored point / over moving foreground.
fn scene_flow_table(report: &StudyReport, level: &str) -> String {
    let mut methods: Vec<String> = CANONICAL_METHODS
        .iter()
        .map(|m| m.name().to_owned())
        .collect();
    for point in &report.points {
        for m in point.scene_flow.keys() {
            if !methods.contains(m) {
                methods.push(m.clone());
            }
        }
    }
    methods.retain(|m| report.points.iter().any(|p| p.scene_flow.contains_key(m)));
    if methods.is_empty() {
        return String::new();
    }
    let labels: Vec<&str> = report.points.iter().map(|p| p.label.as_str()).collect();
    let mut md = format!(
        "{level} Scene-flow EPE (m per sweep), every scored point / moving foreground, the situations pooled\n\n\
         | Method | {} |\n|---|{}\n",
        labels.join(" | "),
        "---|".repeat(labels.len())
    );
    for m in &methods {
        let cells: Vec<String> = report
            .points
            .iter()
            .map(|p| match p.scene_flow.get(m) {
                Some(f) => format!(
                    "{} / {}",
                    fmt_opt(f.epe3d_m, 3),
                    fmt_opt(f.epe_fg_dynamic_m, 3)
                ),
                None => "–".into(),
            })
            .collect();
        let _ = writeln!(md, "| {m} | {} |", cells.join(" | "));
    }
    md.push_str(
        "\n*`ZERO-FLOW` predicts no motion: its EPE is the true displacement, the floor every \
         method must beat.*\n\n",
    );
    md
}
