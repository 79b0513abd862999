//! `metrics.json` in the SPEC §7 shape:
//! `{"situations": {"situation1": {"scans": 60, "methods": {"KF": {"heading_rmse_deg": …,
//! "heading_me_deg": …, "speed_rmse_mps": …, "speed_me_mps": …, "coverage": …, "epe_mps": …,
//! "scene_flow": {"epe3d_m": …, "acc_strict": …, "acc_relax": …, "outliers": …,
//! "epe_threeway_m": …, "normalised_dynamic_epe": …, …}}, "ZERO-FLOW": {"scene_flow": …}},
//! "objects": {"KF": {…}}}}, "objects": {"moving": …, "by_class": …, "standing": …,
//! "by_range": …, "by_points": …}, "seed": …, "version": …}`. A sequence without a target has
//! only scene-flow entries and objects; per-target fields appear for the methods of the thesis
//! tables. Keys are sorted at every level (maps are `BTreeMap`s and the value is built through
//! `serde_json::Value`, whose maps are sorted); a score over no scans is `null`.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::error::EvalError;
use crate::methods::method::Method;
use crate::report::benchmark_report::BenchmarkReport;
use crate::report::scores::ReportScores;
use crate::scene::metrics::MethodMetrics;
use crate::scene::objects::{ObjectGroup, ObjectMetrics};
use crate::scene::scene_flow::SceneFlowMetrics;

#[derive(Serialize)]
struct MetricsFile {
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    objects: BTreeMap<&'static str, GroupEntry>,
    #[serde(skip_serializing_if = "Option::is_none")]
    seed: Option<u64>,
    situations: BTreeMap<String, SituationEntry>,
    version: &'static str,
}

/// One group of objects (`moving`, `standing`) or one breakdown (`by_class`, …) of groups.
#[derive(Serialize)]
#[serde(untagged)]
enum GroupEntry {
    Group(BTreeMap<String, ObjectEntry>),
    Breakdown(BTreeMap<String, BTreeMap<String, ObjectEntry>>),
}

#[derive(Serialize)]
struct SituationEntry {
    methods: BTreeMap<String, MethodEntry>,
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    objects: BTreeMap<String, ObjectEntry>,
    scans: usize,
}

#[derive(Serialize, Default)]
struct MethodEntry {
    #[serde(flatten)]
    target: Option<TargetEntry>,
    #[serde(skip_serializing_if = "Option::is_none")]
    scene_flow: Option<SceneFlowMetrics>,
}

#[derive(Serialize)]
struct TargetEntry {
    coverage: f64,
    epe_mps: Option<f64>,
    heading_me_deg: Option<f64>,
    heading_rmse_deg: Option<f64>,
    speed_me_mps: Option<f64>,
    speed_rmse_mps: Option<f64>,
}

impl From<&MethodMetrics> for TargetEntry {
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

#[derive(Serialize)]
struct ObjectEntry {
    #[serde(flatten)]
    motion: TargetEntry,
    object_scans: usize,
    point_epe_m: Option<f64>,
}

impl From<&ObjectMetrics> for ObjectEntry {
    fn from(m: &ObjectMetrics) -> Self {
        Self {
            motion: TargetEntry::from(&m.motion),
            object_scans: m.object_scans,
            point_epe_m: m.point_epe_m,
        }
    }
}

fn object_entries(scores: &BTreeMap<Method, ObjectMetrics>) -> BTreeMap<String, ObjectEntry> {
    scores
        .iter()
        .map(|(m, s)| (m.name().to_owned(), ObjectEntry::from(s)))
        .collect()
}

/// The metrics of a benchmark as a JSON value in the SPEC shape.
pub fn metrics_json_value(report: &BenchmarkReport) -> Result<serde_json::Value, EvalError> {
    metrics_value(report, &ReportScores::of(report)?)
}

/// [`metrics_json_value`] from scores already computed.
pub(crate) fn metrics_value(
    report: &BenchmarkReport,
    scores: &ReportScores,
) -> Result<serde_json::Value, EvalError> {
    let mut situations: BTreeMap<String, SituationEntry> = BTreeMap::new();
    for (name, scans, metrics) in &scores.situations {
        let methods = metrics
            .iter()
            .map(|(method, m)| {
                let entry = MethodEntry {
                    target: Some(TargetEntry::from(m)),
                    scene_flow: None,
                };
                (method.name().to_owned(), entry)
            })
            .collect();
        let entry = SituationEntry {
            methods,
            objects: BTreeMap::new(),
            scans: *scans,
        };
        situations.insert(name.clone(), entry);
    }
    for scene in &scores.scenes {
        let entry = situations
            .entry(scene.name.clone())
            .or_insert_with(|| SituationEntry {
                methods: BTreeMap::new(),
                objects: BTreeMap::new(),
                scans: scene.scans,
            });
        for (method, flow) in &scene.scene_flow {
            let method_entry = entry.methods.entry(method.name().to_owned()).or_default();
            method_entry.scene_flow = Some(*flow);
        }
        entry.objects = object_entries(&scene.objects);
    }
    let mut objects: BTreeMap<&'static str, GroupEntry> = BTreeMap::new();
    for (group, methods) in &scores.objects {
        let entries = object_entries(methods);
        let breakdown = |key: &'static str, objects: &mut BTreeMap<&'static str, GroupEntry>| {
            let slot = objects
                .entry(key)
                .or_insert_with(|| GroupEntry::Breakdown(BTreeMap::new()));
            if let GroupEntry::Breakdown(groups) = slot {
                groups.insert(group.label(), object_entries(methods));
            }
        };
        match group {
            ObjectGroup::Moving => {
                objects.insert("moving", GroupEntry::Group(entries));
            }
            ObjectGroup::Standing => {
                objects.insert("standing", GroupEntry::Group(entries));
            }
            ObjectGroup::Class(_) => breakdown("by_class", &mut objects),
            ObjectGroup::Range(_) => breakdown("by_range", &mut objects),
            ObjectGroup::Points(_) => breakdown("by_points", &mut objects),
        }
    }
    let file = MetricsFile {
        objects,
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
    metrics_text(&metrics_json_value(report)?)
}

/// Pretty-printed JSON with a trailing newline.
pub(crate) fn metrics_text(value: &serde_json::Value) -> Result<String, EvalError> {
    let mut text = serde_json::to_string_pretty(value).map_err(|source| EvalError::Json {
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
            .insert(crate::methods::method::Method::IcpAuto, vec![None; 30]);
        let value = metrics_json_value(&report).unwrap();
        let m = &value["situations"]["situation1"]["methods"]["ICP-AUTO"];
        assert!(m["heading_rmse_deg"].is_null());
        assert_eq!(m["coverage"], 0.0);
    }
}
