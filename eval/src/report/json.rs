//! `metrics.json` in the SPEC §7 shape:
//! `{"situations": {"situation1": {"scans": 60, "methods": {"KF": {"heading_rmse_deg": …,
//! "heading_me_deg": …, "speed_rmse_mps": …, "speed_me_mps": …, "coverage": …, "epe_mps": …}}}},
//! "seed": …, "version": …}`. Keys are sorted at every level (maps are `BTreeMap`s and struct
//! fields are declared alphabetically); a score over no scans is `null`.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::error::EvalError;
use crate::metrics::MethodMetrics;
use crate::result::BenchmarkReport;

#[derive(Serialize)]
struct MetricsFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    seed: Option<u64>,
    situations: BTreeMap<String, SituationEntry>,
    version: &'static str,
}

#[derive(Serialize)]
struct SituationEntry {
    methods: BTreeMap<String, MethodEntry>,
    scans: usize,
}

#[derive(Serialize)]
struct MethodEntry {
    coverage: f64,
    epe_mps: Option<f64>,
    heading_me_deg: Option<f64>,
    heading_rmse_deg: Option<f64>,
    speed_me_mps: Option<f64>,
    speed_rmse_mps: Option<f64>,
}

impl From<&MethodMetrics> for MethodEntry {
    fn from(m: &MethodMetrics) -> Self {
        Self {
            coverage: m.coverage,
            epe_mps: m.epe_mps,
            heading_me_deg: m.heading_me_deg,
            heading_rmse_deg: m.heading_rmse_deg,
            speed_me_mps: m.speed_me_mps,
            speed_rmse_mps: m.speed_rmse_mps,
        }
    }
}

/// The metrics of a benchmark as a JSON value in the SPEC shape.
pub fn metrics_json_value(report: &BenchmarkReport) -> Result<serde_json::Value, EvalError> {
    let mut situations = BTreeMap::new();
    for situation in &report.situations {
        let methods = situation
            .metrics()?
            .iter()
            .map(|(method, m)| (method.name().to_owned(), MethodEntry::from(m)))
            .collect();
        situations.insert(
            situation.name.clone(),
            SituationEntry {
                methods,
                scans: situation.scans,
            },
        );
    }
    let file = MetricsFile {
        seed: report.seed,
        situations,
        version: env!("CARGO_PKG_VERSION"),
    };
    serde_json::to_value(&file).map_err(|source| EvalError::Json {
        path: "metrics.json".into(),
        source,
    })
}

/// The text of `metrics.json` (pretty-printed, sorted keys, trailing newline).
pub fn metrics_json(report: &BenchmarkReport) -> Result<String, EvalError> {
    let value = metrics_json_value(report)?;
    let mut text = serde_json::to_string_pretty(&value).map_err(|source| EvalError::Json {
        path: "metrics.json".into(),
        source,
    })?;
    text.push('\n');
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::synthetic::synthetic_report;

    #[test]
    fn metrics_json_has_exactly_the_spec_shape() {
        let text = metrics_json(&synthetic_report()).unwrap();
        let value: serde_json::Value = serde_json::from_str(&text).unwrap();
        let top: Vec<&str> = value
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        assert_eq!(top, ["seed", "situations", "version"]);
        let situations = value["situations"].as_object().unwrap();
        assert_eq!(
            situations.keys().collect::<Vec<_>>(),
            ["situation1", "situation4"]
        );
        let s1 = situations["situation1"].as_object().unwrap();
        assert_eq!(s1.keys().collect::<Vec<_>>(), ["methods", "scans"]);
        assert_eq!(s1["scans"], 30);
        let methods = s1["methods"].as_object().unwrap();
        assert_eq!(
            methods.keys().collect::<Vec<_>>(),
            ["FULL-GP-ALL", "ICP", "KF", "KF-AUTO", "SPGP-HET-ALL"]
        );
        for m in methods.values() {
            let keys: Vec<&str> = m.as_object().unwrap().keys().map(String::as_str).collect();
            assert_eq!(
                keys,
                [
                    "coverage",
                    "epe_mps",
                    "heading_me_deg",
                    "heading_rmse_deg",
                    "speed_me_mps",
                    "speed_rmse_mps"
                ]
            );
            assert!(
                m.as_object()
                    .unwrap()
                    .values()
                    .all(serde_json::Value::is_number)
            );
        }
        // KF misses scan 0 of 30.
        assert!((methods["KF"]["coverage"].as_f64().unwrap() - 29.0 / 30.0).abs() < 1e-12);
    }

    #[test]
    fn keys_appear_sorted_in_the_text_and_the_output_is_deterministic() {
        let report = synthetic_report();
        let text = metrics_json(&report).unwrap();
        assert_eq!(text, metrics_json(&report).unwrap());
        let order = [
            "\"coverage\"",
            "\"epe_mps\"",
            "\"heading_me_deg\"",
            "\"heading_rmse_deg\"",
            "\"speed_me_mps\"",
            "\"speed_rmse_mps\"",
        ];
        let positions: Vec<usize> = order.iter().map(|k| text.find(k).unwrap()).collect();
        assert!(positions.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn a_method_without_estimates_is_null_not_a_number() {
        let mut report = synthetic_report();
        report.situations[0]
            .methods
            .insert(crate::method::Method::IcpAuto, vec![None; 30]);
        let value = metrics_json_value(&report).unwrap();
        let m = &value["situations"]["situation1"]["methods"]["ICP-AUTO"];
        assert!(m["heading_rmse_deg"].is_null());
        assert_eq!(m["coverage"], 0.0);
    }
}
