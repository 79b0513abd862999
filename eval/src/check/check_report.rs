//! What `patchflow check` writes: every reading (check × world × model × method) and how many of
//! them are within the bar, per method and per check, as `checks.json`, `checks.csv` and
//! `checks.md`, each written once and atomically.

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::bench::{BAR_HEADING_DEG, BAR_SPEED_MPS};
use crate::check::target_reading::TargetReading;
use crate::error::EvalError;
use crate::report::{create_dir, write_atomic, write_json_atomic};
use crate::scene::metrics::median;

/// A model file read, and what trained it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckedModel {
    /// The file as given.
    pub file: String,
    /// Its GP kind (`spgp`, `spgp-het`, `full`).
    pub gp: String,
    /// Its training seed.
    pub seed: u64,
}

/// Readings within the bar among all of a method's (or a method's on one check).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckTally {
    /// The check, or `all`.
    pub check: String,
    /// The method.
    pub method: String,
    /// Readings within the bar.
    pub within: usize,
    /// Readings.
    pub readings: usize,
    /// Median heading RMSE over the readings that have one, degrees.
    pub median_heading_rmse_deg: Option<f64>,
    /// Median speed RMSE over the readings that have one, m/s.
    pub median_speed_rmse_mps: Option<f64>,
}

/// The bar every reading is held to.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CheckBar {
    /// Heading RMSE under this, degrees.
    pub heading_rmse_deg: f64,
    /// Speed RMSE under this, m/s.
    pub speed_rmse_mps: f64,
}

/// Everything `patchflow check` reports.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckReport {
    /// The program's version.
    pub version: String,
    /// The checks, in the order given.
    pub checks: Vec<String>,
    /// The world seeds.
    pub worlds: Vec<u64>,
    /// The realism rung every check ran on, or `null` for each file's own.
    pub realism: Option<String>,
    /// The models read.
    pub models: Vec<CheckedModel>,
    /// The bar.
    pub bar: CheckBar,
    /// Per method over every check, world and model (`check` is `all`).
    pub methods: Vec<CheckTally>,
    /// Per check and method.
    pub per_check: Vec<CheckTally>,
    /// Every reading: checks in order, then worlds, models and methods.
    pub readings: Vec<TargetReading>,
}

/// The files [`CheckReport::write`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckFiles {
    /// `OUT/checks.json`.
    pub json: PathBuf,
    /// `OUT/checks.csv`.
    pub csv: PathBuf,
    /// `OUT/checks.md`.
    pub markdown: PathBuf,
}

impl CheckReport {
    /// The report of `readings` (in any order; sorted here by check as given, world, model as
    /// given and method as first read).
    pub fn new(
        checks: Vec<String>,
        worlds: Vec<u64>,
        realism: Option<String>,
        models: Vec<CheckedModel>,
        mut readings: Vec<TargetReading>,
    ) -> Self {
        let mut methods_seen: Vec<String> = Vec::new();
        for r in &readings {
            if !methods_seen.contains(&r.method) {
                methods_seen.push(r.method.clone());
            }
        }
        let position = |list: &[String], item: &str| list.iter().position(|x| x == item);
        let model_files: Vec<String> = models.iter().map(|m| m.file.clone()).collect();
        readings.sort_by_key(|r| {
            (
                position(&checks, &r.check),
                r.world,
                position(&model_files, &r.model),
                position(&methods_seen, &r.method),
            )
        });
        let methods = methods_seen
            .iter()
            .map(|m| tally("all", m, readings.iter().filter(|r| &r.method == m)))
            .collect();
        let per_check = checks
            .iter()
            .flat_map(|c| methods_seen.iter().map(move |m| (c, m)))
            .map(|(c, m)| {
                let of = readings.iter().filter(|r| &r.check == c && &r.method == m);
                tally(c, m, of)
            })
            .collect();
        Self {
            version: env!("CARGO_PKG_VERSION").to_owned(),
            checks,
            worlds,
            realism,
            models,
            bar: CheckBar {
                heading_rmse_deg: BAR_HEADING_DEG,
                speed_rmse_mps: BAR_SPEED_MPS,
            },
            methods,
            per_check,
            readings,
        }
    }

    /// Writes `checks.json`, `checks.csv` and `checks.md` into `out`.
    pub fn write(&self, out: &Path) -> Result<CheckFiles, EvalError> {
        create_dir(out)?;
        let files = CheckFiles {
            json: out.join("checks.json"),
            csv: out.join("checks.csv"),
            markdown: out.join("checks.md"),
        };
        write_json_atomic(&files.json, self)?;
        write_atomic(&files.csv, self.csv().as_bytes())?;
        write_atomic(&files.markdown, self.markdown().as_bytes())?;
        Ok(files)
    }

    /// One row per reading.
    pub fn csv(&self) -> String {
        let mut out = String::from(
            "check,world,model,method,heading_rmse_deg,speed_rmse_mps,coverage,within_bar\n",
        );
        let n = |v: Option<f64>| v.map_or_else(String::new, |v| format!("{v:.6}"));
        for r in &self.readings {
            out.push_str(&format!(
                "{},{},{},{},{},{},{:.6},{}\n",
                csv_field(&r.check),
                r.world,
                csv_field(&r.model),
                r.method,
                n(r.heading_rmse_deg),
                n(r.speed_rmse_mps),
                r.coverage,
                r.within_bar
            ));
        }
        out
    }
}

/// The tally of `readings` under `check` and `method`.
fn tally<'a>(
    check: &str,
    method: &str,
    readings: impl Iterator<Item = &'a TargetReading>,
) -> CheckTally {
    let readings: Vec<&TargetReading> = readings.collect();
    CheckTally {
        check: check.to_owned(),
        method: method.to_owned(),
        within: readings.iter().filter(|r| r.within_bar).count(),
        readings: readings.len(),
        median_heading_rmse_deg: median(readings.iter().filter_map(|r| r.heading_rmse_deg)),
        median_speed_rmse_mps: median(readings.iter().filter_map(|r| r.speed_rmse_mps)),
    }
}

/// A CSV field, quoted when it holds a comma, a quote or a line break.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_owned()
    }
}

#[cfg(test)]
#[path = "check_report_tests.rs"]
mod tests;
