//! `report.md`: per situation a heading table and a speed table laid out like thesis Tables
//! 4.6-4.15 (RMSE and ME per method), with the thesis' real-data numbers beside ours, clearly
//! labelled; a summary table; the timing table; notes.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use crate::methods::method::Method;
use crate::report::benchmark_report::BenchmarkReport;
use crate::report::breakdown::breakdown_sections;
use crate::report::files::fmt_opt;
use crate::report::perception_markdown::perception_section;
use crate::report::perception_summary::PerceptionSummary;
use crate::report::scene_markdown::scene_sections;
use crate::report::scores::{ReportScores, SituationMetrics};
use crate::report::thesis_tables::{thesis_row, thesis_situation};
use crate::scene::metrics::{MIN_SCORED_SPEED_MPS, MethodMetrics};

/// The text of `report.md`.
pub(crate) fn report_markdown(report: &BenchmarkReport, scores: &ReportScores) -> String {
    let metrics = &scores.situations[..];
    let mut md = String::new();
    // Writing to a String cannot fail, so the `fmt::Result`s below are ignored.
    let _ = writeln!(md, "# patchflow benchmark report\n");
    let _ = writeln!(
        md,
        "patchflow {}{}. Heading errors are wrapped to [−180°, 180°] and scored only where the true \
         speed is at least {MIN_SCORED_SPEED_MPS} m/s; RMSE is thesis eq. 4.1, ME is the mean absolute \
         error; coverage is the share of scans with an estimate; EPE is the mean velocity end-point \
         error ‖v̂ − v‖.\n",
        env!("CARGO_PKG_VERSION"),
        report
            .seed
            .map(|s| format!(", seed {s}"))
            .unwrap_or_default()
    );
    if metrics
        .iter()
        .any(|(name, _, _)| thesis_situation(name).is_some())
    {
        let _ = writeln!(
            md,
            "Columns marked **Hess 2008** are the thesis' own numbers, measured on real Urban Challenge \
             data (Stanford's Junior), transcribed from its Tables 4.6-4.15. They are shown for \
             orientation only: our numbers come from simulated situations after the same descriptions.\n"
        );
    }
    summary_section(&mut md, metrics);
    if !metrics.is_empty() {
        let _ = writeln!(
            md,
            "![heading and speed RMSE per method and situation](plots/summary_rmse.png)\n\n\
             *Heading (top) and speed (bottom) RMSE of the target per method and situation; \
             pale bars are the BEST and AUTO variants.*\n"
        );
    }
    for ((name, scans, methods), situation) in metrics.iter().zip(&report.situations) {
        let description = report.descriptions.get(name).map(String::as_str);
        situation_section(&mut md, name, *scans, methods, description);
        if let Some(sweep) = report.scene_figures.get(name) {
            scene_figure_lines(&mut md, name, *sweep);
        }
        breakdown_sections(&mut md, situation);
    }
    if let Some(cv) = &report.cv {
        // The CV tables sit one heading level below the report's title.
        let tables = crate::report::cv::cv_markdown(cv.folds, &cv.rows, &cv.notes);
        for line in tables.lines() {
            let line = if line.starts_with('#') {
                format!("#{line}")
            } else {
                line.to_owned()
            };
            let _ = writeln!(md, "{line}");
        }
    }
    scene_sections(&mut md, scores);
    perception_section(&mut md, &PerceptionSummary::of_scenes(&report.scenes));
    timing_section(&mut md, report);
    notes_section(&mut md, report);
    md
}

fn summary_section(md: &mut String, metrics: &[SituationMetrics]) {
    let _ = writeln!(md, "## Summary\n");
    let names: Vec<&str> = metrics.iter().map(|(n, _, _)| n.as_str()).collect();
    let methods: std::collections::BTreeSet<Method> = metrics
        .iter()
        .flat_map(|(_, _, m)| m.keys().copied())
        .collect();
    let _ = write!(md, "| Method |");
    for n in &names {
        let _ = write!(md, " {n} heading RMSE (°) / speed RMSE (m/s) |");
    }
    let _ = writeln!(md, " mean coverage | mean EPE (m/s) |");
    let _ = writeln!(md, "|---|{}---|---|", "---|".repeat(names.len()));
    for method in &methods {
        let _ = write!(md, "| {} |", method.label());
        let (mut coverage, mut epe) = (Vec::new(), Vec::new());
        for (_, _, situation) in metrics {
            match situation.get(method) {
                Some(m) => {
                    let _ = write!(
                        md,
                        " {} / {} |",
                        fmt_opt(m.heading_rmse_deg, 2),
                        fmt_opt(m.speed_rmse_mps, 2)
                    );
                    coverage.push(m.coverage);
                    epe.extend(m.epe_mps);
                }
                None => {
                    let _ = write!(md, " – |");
                }
            }
        }
        let mean = |v: &[f64]| (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64);
        let _ = writeln!(
            md,
            " {} | {} |",
            fmt_opt(mean(&coverage), 3),
            fmt_opt(mean(&epe), 2)
        );
    }
    let _ = writeln!(md);
}

fn situation_section(
    md: &mut String,
    name: &str,
    scans: usize,
    methods: &BTreeMap<Method, MethodMetrics>,
    description: Option<&str>,
) {
    let thesis = thesis_situation(name);
    let _ = writeln!(md, "## {name} ({scans} scans)\n");
    match (thesis, description) {
        (Some(t), _) => {
            let _ = writeln!(md, "After thesis 4.4: {}.\n", t.description);
        }
        (None, Some(d)) => {
            let _ = writeln!(md, "Scenario: {d}.\n");
        }
        (None, None) => {}
    }
    // Thesis columns only where the thesis measured this situation.
    let (heading_title, speed_title, thesis_head, thesis_rule) = match thesis {
        Some(t) => (
            format!("Heading (degrees; layout of thesis {})", t.heading_table),
            format!("Speed (m/s; layout of thesis {})", t.speed_table),
            " Hess 2008 RMSE | Hess 2008 ME |",
            "---|---|",
        ),
        None => (
            "Heading (degrees)".to_owned(),
            "Speed (m/s)".to_owned(),
            "",
            "",
        ),
    };
    let thesis_cells = |row: Option<crate::report::thesis_tables::ThesisRow>| match thesis {
        Some(_) => format!(
            " {} | {} |",
            fmt_opt(row.map(|r| r.rmse), 2),
            fmt_opt(row.map(|r| r.me), 2)
        ),
        None => String::new(),
    };
    let _ = writeln!(md, "### {heading_title}\n");
    let _ = writeln!(
        md,
        "| Method | RMSE | ME | scored scans | coverage |{thesis_head}\n|---|---|---|---|---|{thesis_rule}"
    );
    for (method, m) in methods {
        let row = thesis.and_then(|t| thesis_row(&t.heading, *method));
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {:.3} |{}",
            method.label(),
            fmt_opt(m.heading_rmse_deg, 2),
            fmt_opt(m.heading_me_deg, 2),
            m.heading_scored_scans,
            m.coverage,
            thesis_cells(row),
        );
    }
    let _ = writeln!(md, "\n### {speed_title}\n");
    let _ = writeln!(
        md,
        "| Method | RMSE | ME | EPE | coverage |{thesis_head}\n|---|---|---|---|---|{thesis_rule}"
    );
    for (method, m) in methods {
        let row = thesis.and_then(|t| thesis_row(&t.speed, *method));
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {:.3} |{}",
            method.label(),
            fmt_opt(m.speed_rmse_mps, 2),
            fmt_opt(m.speed_me_mps, 2),
            fmt_opt(m.epe_mps, 2),
            m.coverage,
            thesis_cells(row),
        );
    }
    let cf = |figure: &str| format!(" (cf. thesis {figure})");
    let (heading_fig, speed_fig) = thesis.map_or((String::new(), String::new()), |t| {
        (cf(t.heading_figure), cf(t.speed_figure))
    });
    let _ = writeln!(
        md,
        "\n![{name} heading](plots/{name}_heading.png)\n\n*Heading over time, true and estimated{heading_fig}.*\n"
    );
    let _ = writeln!(
        md,
        "![{name} speed](plots/{name}_speed.png)\n\n*Speed over time, true and estimated{speed_fig}.*\n"
    );
}

fn scene_figure_lines(md: &mut String, name: &str, sweep: usize) {
    let _ = writeln!(
        md,
        "![{name} scene](plots/{name}_scene.png)\n\n*Bird's-eye view: static structures, the ego \
         path, every actor's path, the target in red; boxes and range rings at sweep {sweep}.*\n"
    );
    let _ = writeln!(
        md,
        "![{name} point cloud](plots/{name}_cloud.png)\n\n*Sweep {sweep} from above: points \
         coloured by class, moving points by the direction of their true flow (colour wheel).*\n"
    );
}

fn timing_section(md: &mut String, report: &BenchmarkReport) {
    if report.timings.is_empty() {
        return;
    }
    let _ = writeln!(
        md,
        "## Timing\n\nWall-clock and CPU seconds (all threads) per stage; CPU over wall is the \
         number of cores a stage kept busy, and on a machine shared with other work the CPU \
         time is the steadier measure.\n\n| Stage | wall s | CPU s | cores busy |\n|---|---|---|---|"
    );
    let cpu = |t: Option<f64>| t.map_or_else(|| "–".to_owned(), |c| format!("{c:.1}"));
    let busy = |cpu: Option<f64>, wall: f64| {
        cpu.filter(|_| wall > 0.0)
            .map_or_else(|| "–".to_owned(), |c| format!("{:.2}", c / wall))
    };
    for t in &report.timings {
        let _ = writeln!(
            md,
            "| {} | {:.1} | {} | {} |",
            t.stage,
            t.seconds,
            cpu(t.cpu_seconds),
            busy(t.cpu_seconds, t.seconds)
        );
    }
    let total: f64 = report.timings.iter().map(|t| t.seconds).sum();
    let total_cpu: Option<f64> = report.timings.iter().map(|t| t.cpu_seconds).sum();
    let _ = writeln!(
        md,
        "| **total** | {total:.1} | {} | {} |\n",
        cpu(total_cpu),
        busy(total_cpu, total)
    );
}

fn notes_section(md: &mut String, report: &BenchmarkReport) {
    let _ = writeln!(md, "## Notes\n");
    for note in &report.notes {
        let _ = writeln!(md, "- {note}");
    }
    let _ = writeln!(
        md,
        "- KF and ICP get the target's cluster from ground truth each scan, as in the thesis; \
         KF-AUTO and ICP-AUTO associate clusters themselves (χ²-gated nearest-neighbour tracking, \
         nearest predicted centroid) and use the target id only to read out their estimate."
    );
    let _ = writeln!(
        md,
        "- Plots place each estimated heading at the true heading plus its wrapped error, so curves \
         do not jump at ±180°; speed plots clip estimates above the plot's top edge."
    );
    if report
        .situations
        .iter()
        .any(|s| thesis_situation(&s.name).is_some())
    {
        let _ = writeln!(
            md,
            "- Thesis Tables 4.13 and 4.15 print an ME above the RMSE for some GP rows, which a mean \
             absolute error cannot exceed; they are transcribed as printed."
        );
    }
}
