//! `occupancy.md` and the occupancy section of the benchmark's `report.md`: per scenario a table
//! laid out like the DGPOM paper's Table 1 (one row per algorithm, one column per query time),
//! the paper's rows beside ours and labelled as the paper's, then the time and training points of
//! one map per method, the figures and notes.

use std::fmt::Write as _;

use patchflow_occupancy::SequenceScores;

use super::json::query_time_key;
use super::paper_table::{PAPER_QUERY_TIMES, PAPER_TABLE_1};
use super::{OccupancyReport, plot::figure_file_name};

/// Method order in tables: the paper's (DGPOM, GPOM ℜ^D, GPOM ℜ^{D+1}), then the grid, then others.
const ORDER: [&str; 4] = ["DGPOM", "GPOM-RD", "GPOM-RD1", "GRID"];

/// Label of one of our methods in the tables.
fn label(method: &str) -> String {
    match PAPER_TABLE_1.iter().find(|row| row.method == method) {
        Some(row) => format!("{} (ours, `{method}`)", row.label),
        None if method == "GRID" => "occupancy grid (ours, `GRID`)".to_owned(),
        None => format!("`{method}` (ours)"),
    }
}

fn ordered(scores: &SequenceScores) -> Vec<&str> {
    let mut names: Vec<&str> = scores.methods.keys().map(String::as_str).collect();
    names.sort_by_key(|n| (ORDER.iter().position(|o| o == n).unwrap_or(ORDER.len()), *n));
    names
}

/// The occupancy section (a level-2 heading and its tables), for `report.md` and `occupancy.md`.
pub fn occupancy_section(report: &OccupancyReport) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## Occupancy maps (DGPOM paper, Section 3.1)\n\nROC AUC of the probability of occupancy against the exact occupancy on a {} m lattice of query points over the area the scanner observes (within range, inside its field of view, in front of static structure), at each query time; every map is built from the scan at the query time and the {} before it. The paper's numbers come from its own simulated T-junction, whose layout, traffic and scored area we could only rebuild from its text: compare the pattern, not the digits.\n",
        report.params.query_spacing_m,
        report.params.scans_per_map.saturating_sub(1)
    );
    for scores in &report.scenarios {
        auc_table(&mut md, scores);
        timing_table(&mut md, scores);
        let _ = writeln!(
            md,
            "Figures (cf. the paper's Figure 6: ground truth with the scan, probability of occupancy, predictive variance):\n"
        );
        for method in ordered(scores) {
            let file = figure_file_name(&scores.name, method);
            let _ = writeln!(md, "- `{method}`: [plots/{file}](plots/{file})");
        }
        md.push('\n');
    }
    if !report.notes.is_empty() {
        let _ = writeln!(md, "### Notes on the occupancy maps\n");
        for note in &report.notes {
            let _ = writeln!(md, "- {note}");
        }
        md.push('\n');
    }
    md
}

/// The whole `occupancy.md`.
pub fn occupancy_markdown(report: &OccupancyReport) -> String {
    format!(
        "# Occupancy maps\n\nSeed {} (free-space samples along the beams); `occupancy.json` holds the same numbers.\n\n{}",
        report.seed,
        occupancy_section(report)
    )
}

fn auc_table(md: &mut String, scores: &SequenceScores) {
    let scans: Vec<usize> = scores.query_secs.keys().copied().collect();
    let keys: Vec<String> = scans.iter().map(|&t| query_time_key(scores, t)).collect();
    let _ = writeln!(
        md,
        "### {}: ROC AUC by query time (layout of the paper's Table 1)\n",
        scores.name
    );
    let header: Vec<String> = keys.iter().map(|k| format!("t = {k}")).collect();
    let _ = writeln!(md, "| algorithm | {} | mean |", header.join(" | "));
    let _ = writeln!(md, "|---|{}---|", "---|".repeat(keys.len()));
    // The paper's order (DGPOM, GPOM ℜ^D, GPOM ℜ^{D+1}), each of our rows above the paper's;
    // the paper's rows are there even for methods we did not run.
    for method in ORDER {
        if let Some(m) = scores.methods.get(method) {
            let cells: Vec<Option<f64>> = scans
                .iter()
                .map(|t| m.auc_by_query_scan.get(t).copied().flatten())
                .collect();
            write_row(md, &label(method), &cells);
        }
        if let Some(row) = PAPER_TABLE_1.iter().find(|r| r.method == method) {
            write_row(
                md,
                &format!("{} (paper)", row.label),
                &paper_cells(row.auc, &keys),
            );
        }
    }
    for method in ordered(scores).into_iter().filter(|m| !ORDER.contains(m)) {
        let m = &scores.methods[method];
        let cells: Vec<Option<f64>> = scans
            .iter()
            .map(|t| m.auc_by_query_scan.get(t).copied().flatten())
            .collect();
        write_row(md, &label(method), &cells);
    }
    let occupied: Vec<String> = scans
        .iter()
        .map(|t| {
            let (o, n) = (
                scores.occupied_points.get(t).copied().unwrap_or(0),
                scores.query_points.get(t).copied().unwrap_or(0),
            );
            format!("{o}/{n}")
        })
        .collect();
    let _ = writeln!(
        md,
        "| occupied / query points | {} | |\n",
        occupied.join(" | ")
    );
}

/// The paper's values at our query times (blank where the paper has none).
fn paper_cells(auc: [f64; 7], keys: &[String]) -> Vec<Option<f64>> {
    keys.iter()
        .map(|k| {
            PAPER_QUERY_TIMES
                .iter()
                .position(|t| t.to_string() == *k)
                .map(|i| auc[i])
        })
        .collect()
}

fn write_row(md: &mut String, label: &str, cells: &[Option<f64>]) {
    let values: Vec<f64> = cells.iter().flatten().copied().collect();
    let mean = (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64);
    let text: Vec<String> = cells.iter().map(|c| fmt(*c)).collect();
    let _ = writeln!(md, "| {label} | {} | {} |", text.join(" | "), fmt(mean));
}

fn fmt(value: Option<f64>) -> String {
    value.map_or_else(|| "–".to_owned(), |v| format!("{v:.4}"))
}

fn timing_table(md: &mut String, scores: &SequenceScores) {
    let _ = writeln!(
        md,
        "One map (fit and prediction over the query points), per method:\n\n| method | seconds per map (mean) | slowest map (s) | training points per map (mean) | fit (last map) |\n|---|---|---|---|---|"
    );
    for method in ordered(scores) {
        let Some(m) = scores.methods.get(method) else {
            continue;
        };
        let slowest = m.seconds_per_map.iter().copied().fold(0.0, f64::max);
        let _ = writeln!(
            md,
            "| `{method}` | {:.3} | {:.3} | {:.0} | {} |",
            m.mean_seconds_per_map(),
            slowest,
            m.mean_training_points(),
            m.summaries.last().map_or("", String::as_str)
        );
    }
    md.push('\n');
}
