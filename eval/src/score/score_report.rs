//! What `patchflow score` writes: every method's scores per sequence and pooled over the
//! sequences, as `metrics.json`, `tables.csv` and `report.md`, each written once and atomically.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::error::EvalError;
use crate::report::{create_dir, fmt_opt, write_atomic, write_json_atomic};
use crate::score::method_scores::{MethodScores, MethodSource};

/// One sequence's (or the pool's) scores.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SequenceScores {
    /// Scans scored (every sweep but the first).
    pub scans: usize,
    /// Per method name.
    pub methods: BTreeMap<String, MethodScores>,
}

/// Everything `patchflow score` reports.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScoreReport {
    /// The dataset scored against.
    pub dataset: String,
    /// Where the scored points' height slice and map window come from (a model's feature
    /// parameters, or the defaults).
    pub scored_points: String,
    /// Per sequence, in the dataset's order.
    pub sequences: BTreeMap<String, SequenceScores>,
    /// Every sequence pooled.
    pub pooled: SequenceScores,
}

/// The files [`ScoreReport::write`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct ScoreFiles {
    /// `OUT/metrics.json`.
    pub metrics_json: PathBuf,
    /// `OUT/tables.csv`.
    pub tables_csv: PathBuf,
    /// `OUT/report.md`.
    pub report_md: PathBuf,
}

const CSV_HEADER: &str = "scope,method,source,points,epe3d_m,acc_strict,acc_relax,outliers,\
epe_fg_dynamic_m,epe_fg_static_m,epe_bg_static_m,epe_threeway_m,normalised_dynamic_epe,\
bucketed_static_epe_m,moving_iou,object_scans,heading_rmse_deg,speed_rmse_mps,object_coverage";

impl ScoreReport {
    /// Writes `metrics.json`, `tables.csv` and `report.md` into `out`.
    pub fn write(&self, out: &Path) -> Result<ScoreFiles, EvalError> {
        create_dir(out)?;
        let files = ScoreFiles {
            metrics_json: out.join("metrics.json"),
            tables_csv: out.join("tables.csv"),
            report_md: out.join("report.md"),
        };
        write_json_atomic(&files.metrics_json, self)?;
        write_atomic(&files.tables_csv, self.csv().as_bytes())?;
        write_atomic(&files.report_md, self.markdown().as_bytes())?;
        Ok(files)
    }

    /// One row per scope (each sequence, then `all`) and method.
    pub fn csv(&self) -> String {
        let mut out = format!("{CSV_HEADER}\n");
        let all = "all".to_owned();
        let scopes = self.sequences.iter().chain([(&all, &self.pooled)]);
        for (scope, scores) in scopes {
            for (method, s) in &scores.methods {
                let f = &s.scene_flow;
                let n = |v: Option<f64>| v.map_or_else(String::new, |v| format!("{v:.6}"));
                let cells = [
                    n(f.epe3d_m),
                    n(f.acc_strict),
                    n(f.acc_relax),
                    n(f.outliers),
                    n(f.epe_fg_dynamic_m),
                    n(f.epe_fg_static_m),
                    n(f.epe_bg_static_m),
                    n(f.epe_threeway_m),
                    n(f.normalised_dynamic_epe),
                    n(f.bucketed_static_epe_m),
                    n(s.moving_iou),
                ];
                let _ = writeln!(
                    out,
                    "{scope},{method},{},{},{},{},{},{},{}",
                    source_label(&s.source),
                    f.points,
                    cells.join(","),
                    s.object_scans,
                    n(s.objects.heading_rmse_deg),
                    n(s.objects.speed_rmse_mps),
                    format_args!("{:.6}", s.objects.coverage),
                );
            }
        }
        out
    }

    /// The report: the pooled table first (oracle methods last and marked), then per sequence.
    pub fn markdown(&self) -> String {
        let mut out = String::from("# Scores of prediction folders\n\n");
        let _ = writeln!(
            out,
            "Dataset `{}`, {} sequences, {} scans; scored points: {}. Every method is scored by \
             the code of `patchflow evaluate` (SPEC §6). A point without a prediction (NaN) \
             stands still. Moving IoU is per point over the scored points (SemanticKITTI MOS); \
             an object's heading and speed are the mean of its points' predicted flow. Oracle \
             methods read the truth association: upper bounds, not ranked.\n",
            self.dataset,
            self.sequences.len(),
            self.pooled.scans,
            self.scored_points,
        );
        out.push_str("## All sequences\n\n");
        table(&mut out, &self.pooled);
        for (name, scores) in &self.sequences {
            let _ = writeln!(out, "## {name} ({} scans)\n", scores.scans);
            table(&mut out, scores);
        }
        out
    }
}

fn source_label(source: &MethodSource) -> String {
    match source {
        MethodSource::Predictions(path) => format!("predictions {}", path.replace(',', ";")),
        MethodSource::BuiltIn => "built-in".into(),
        MethodSource::Oracle => "built-in (oracle)".into(),
    }
}

fn table(out: &mut String, scores: &SequenceScores) {
    out.push_str(
        "| method | EPE3D (m) | AccS | AccR | Outl. | 3-way EPE (m) | static bucket (m) | \
         norm. dyn. EPE | moving IoU | heading RMSE (°) | speed RMSE (m/s) | obj. scans |\n",
    );
    out.push_str("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    let mut rows: Vec<(&String, &MethodScores)> = scores.methods.iter().collect();
    // Ranked by three-way EPE; oracles after the rest.
    rows.sort_by(|a, b| {
        let key = |s: &MethodScores| {
            let rank = s.scene_flow.epe_threeway_m.unwrap_or(f64::INFINITY);
            (s.source == MethodSource::Oracle, rank)
        };
        let (ka, kb) = (key(a.1), key(b.1));
        ka.0.cmp(&kb.0)
            .then(ka.1.total_cmp(&kb.1))
            .then(a.0.cmp(b.0))
    });
    for (name, s) in rows {
        let f = &s.scene_flow;
        let label = match s.source {
            MethodSource::Oracle => format!("{name} (oracle)"),
            _ => name.clone(),
        };
        let _ = writeln!(
            out,
            "| {label} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            fmt_opt(f.epe3d_m, 3),
            fmt_opt(f.acc_strict, 3),
            fmt_opt(f.acc_relax, 3),
            fmt_opt(f.outliers, 3),
            fmt_opt(f.epe_threeway_m, 3),
            fmt_opt(f.bucketed_static_epe_m, 4),
            fmt_opt(f.normalised_dynamic_epe, 3),
            fmt_opt(s.moving_iou, 3),
            fmt_opt(s.objects.heading_rmse_deg, 1),
            fmt_opt(s.objects.speed_rmse_mps, 2),
            s.object_scans,
        );
    }
    out.push('\n');
}
