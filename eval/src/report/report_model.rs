//! One benchmark report as a value, built once per run: the results, every score computed once
//! from them, and what the run adds beside the scores (sections of `report.md` right after the
//! summary and at its end, top-level entries of `metrics.json`). It renders Markdown, JSON and
//! CSV in one pass, so no file is patched after it is written.

use std::collections::BTreeSet;

use crate::error::EvalError;
use crate::report::benchmark_report::BenchmarkReport;
use crate::report::csv::tables_csv;
use crate::report::json::{metrics_text, metrics_value};
use crate::report::markdown::report_markdown;
use crate::report::perception_summary::PerceptionSummary;
use crate::report::scores::ReportScores;

/// What a run adds to its report beside the scores.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReportExtras {
    /// Sections of `report.md` right after its summary, in order (each opens with `## `).
    pub after_summary: Vec<String>,
    /// Sections at the end of `report.md`, in order.
    pub at_end: Vec<String>,
    /// Top-level entries of `metrics.json` beside the SPEC §7 shape (seeds, models, spread, bar);
    /// an entry of the same name replaces the shape's.
    pub metrics: serde_json::Map<String, serde_json::Value>,
}

/// The report of one run: the results, their scores and the run's extras.
#[derive(Debug, Clone)]
pub(crate) struct ReportModel<'a> {
    /// The results.
    pub results: &'a BenchmarkReport,
    /// Every score the files show, computed once.
    pub scores: ReportScores,
    /// What the run adds.
    pub extras: ReportExtras,
}

/// The text of every report file, rendered in one pass from one model.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RenderedReport {
    /// `metrics.json`.
    pub metrics_json: String,
    /// `tables.csv`.
    pub tables_csv: String,
    /// `report.md`.
    pub report_md: String,
    /// `perception.json`, when sequences were evaluated as whole scenes.
    pub perception_json: Option<String>,
}

impl<'a> ReportModel<'a> {
    /// Scores `results` once; the extras start empty.
    pub fn new(results: &'a BenchmarkReport) -> Result<Self, EvalError> {
        check_names(results)?;
        Ok(Self {
            results,
            scores: ReportScores::of(results)?,
            extras: ReportExtras::default(),
        })
    }

    /// Every report file's text.
    pub fn render(&self) -> Result<RenderedReport, EvalError> {
        let mut metrics = metrics_value(self.results, &self.scores)?;
        if let Some(object) = metrics.as_object_mut() {
            object.extend(self.extras.metrics.clone());
        }
        let perception_json = if self.results.scenes.is_empty() {
            None
        } else {
            let perception = PerceptionSummary::of_scenes(&self.results.scenes);
            let text =
                serde_json::to_string_pretty(&perception).map_err(|source| EvalError::Json {
                    path: "perception.json".into(),
                    source,
                })?;
            Some(format!("{text}\n"))
        };
        Ok(RenderedReport {
            metrics_json: metrics_text(&metrics)?,
            tables_csv: tables_csv(&self.scores),
            report_md: self.markdown(),
            perception_json,
        })
    }

    /// `report.md`: the scores' sections with the extras after the summary and at the end.
    fn markdown(&self) -> String {
        let md = report_markdown(self.results, &self.scores);
        // Before the second `## ` heading (right after the summary), or at the end.
        let at = md
            .match_indices("\n## ")
            .nth(1)
            .map_or(md.len(), |(i, _)| i + 1);
        let mut out = String::with_capacity(md.len());
        out.push_str(&md[..at]);
        for section in &self.extras.after_summary {
            out.push_str(section);
            out.push('\n');
        }
        out.push_str(&md[at..]);
        for section in &self.extras.at_end {
            out.push('\n');
            out.push_str(section);
        }
        out
    }
}

/// Situation names must be unique and usable as file names.
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
    use crate::report::synthetic::{synthetic_report, synthetic_report_with_scenes};

    fn extras() -> ReportExtras {
        let mut metrics = serde_json::Map::new();
        metrics.insert("seeds".into(), serde_json::json!([7, 8, 9]));
        ReportExtras {
            after_summary: vec!["## Against the bar\n\nbar\n".into(), "## Spread\n".into()],
            at_end: vec!["## Occupancy\n".into(), "## Realism\n".into()],
            metrics,
        }
    }

    #[test]
    fn the_extras_sit_after_the_summary_and_at_the_end_of_the_markdown() {
        let results = synthetic_report();
        let mut model = ReportModel::new(&results).unwrap();
        let plain = model.render().unwrap().report_md;
        model.extras = extras();
        let md = model.render().unwrap().report_md;
        let headings: Vec<&str> = md.lines().filter(|l| l.starts_with("## ")).collect();
        let plain_headings: Vec<&str> = plain.lines().filter(|l| l.starts_with("## ")).collect();
        assert_eq!(headings[0], plain_headings[0], "the summary stays first");
        assert_eq!(headings[1..3], ["## Against the bar", "## Spread"]);
        assert_eq!(headings[3..headings.len() - 2], plain_headings[1..]);
        assert_eq!(
            headings[headings.len() - 2..],
            ["## Occupancy", "## Realism"]
        );
        assert!(md.ends_with("\n## Occupancy\n\n## Realism\n"));
    }

    #[test]
    fn the_json_is_the_spec_shape_plus_the_extra_entries() {
        let results = synthetic_report();
        let mut model = ReportModel::new(&results).unwrap();
        let plain: serde_json::Value =
            serde_json::from_str(&model.render().unwrap().metrics_json).unwrap();
        model.extras = extras();
        let rendered = model.render().unwrap();
        let mut json: serde_json::Value = serde_json::from_str(&rendered.metrics_json).unwrap();
        let object = json.as_object_mut().unwrap();
        assert_eq!(object.remove("seeds"), Some(serde_json::json!([7, 8, 9])));
        assert_eq!(json, plain);
        assert_eq!(rendered.tables_csv, tables_csv(&model.scores));
    }

    #[test]
    fn perception_json_is_rendered_only_for_whole_scenes() {
        let targets = synthetic_report();
        assert_eq!(
            ReportModel::new(&targets)
                .unwrap()
                .render()
                .unwrap()
                .perception_json,
            None
        );
        let scenes = synthetic_report_with_scenes();
        let rendered = ReportModel::new(&scenes).unwrap().render().unwrap();
        let text = rendered.perception_json.unwrap();
        assert!(text.ends_with('\n'));
        let value: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert!(
            value
                .as_array()
                .is_some_and(|sequences| !sequences.is_empty()),
            "{value}"
        );
    }
}
