//! Tests of the check report: tallies, medians, order and the files' text.

#![allow(clippy::unwrap_used)]

use super::*;

fn reading(check: &str, world: u64, model: &str, method: &str, h: Option<f64>) -> TargetReading {
    TargetReading {
        check: check.into(),
        world,
        model: model.into(),
        method: method.into(),
        heading_rmse_deg: h,
        speed_rmse_mps: h.map(|h| h / 20.0),
        coverage: 0.5,
        within_bar: h.is_some_and(|h| h < 25.0),
    }
}

fn models() -> Vec<CheckedModel> {
    ["b.json", "a.json"]
        .iter()
        .map(|f| CheckedModel {
            file: (*f).into(),
            gp: "spgp-het".into(),
            seed: 7,
        })
        .collect()
}

/// Two checks, worlds 8 and 7, two models, two methods; given out of order.
fn report() -> CheckReport {
    let mut readings = Vec::new();
    for world in [8, 7] {
        for model in ["a.json", "b.json"] {
            for check in ["z_last", "a_first"] {
                let h = (world as f64) + if model == "a.json" { 30.0 } else { 0.0 };
                readings.push(reading(check, world, model, "GP-KF", Some(h)));
                readings.push(reading(check, world, model, "SPGP-HET-ALL", None));
            }
        }
    }
    CheckReport::new(
        vec!["z_last".into(), "a_first".into()],
        vec![7, 8],
        None,
        models(),
        readings,
    )
}

#[test]
fn readings_are_ordered_by_check_as_given_then_world_then_model_as_given() {
    let r = report();
    let keys: Vec<(&str, u64, &str)> = r
        .readings
        .iter()
        .filter(|r| r.method == "GP-KF")
        .map(|r| (r.check.as_str(), r.world, r.model.as_str()))
        .collect();
    assert_eq!(
        &keys[..4],
        [
            ("z_last", 7, "b.json"),
            ("z_last", 7, "a.json"),
            ("z_last", 8, "b.json"),
            ("z_last", 8, "a.json")
        ]
    );
}

#[test]
fn a_method_is_tallied_over_every_check_world_and_model() {
    let r = report();
    let gp_kf = r.methods.iter().find(|t| t.method == "GP-KF").unwrap();
    // Model b reads 7° and 8° (within), model a 37° and 38° (missed), on both checks.
    assert_eq!((gp_kf.within, gp_kf.readings), (4, 8));
    assert!((gp_kf.median_heading_rmse_deg.unwrap() - 22.5).abs() < 1e-12);
    let per_check = r
        .per_check
        .iter()
        .find(|t| t.check == "a_first" && t.method == "GP-KF");
    assert_eq!(per_check.map(|t| (t.within, t.readings)), Some((2, 4)));
}

#[test]
fn readings_without_an_estimate_count_as_misses_and_have_no_median() {
    let r = report();
    let spgp = r
        .methods
        .iter()
        .find(|t| t.method == "SPGP-HET-ALL")
        .unwrap();
    assert_eq!((spgp.within, spgp.readings), (0, 8));
    assert_eq!(spgp.median_heading_rmse_deg, None);
}

#[test]
fn the_json_has_no_nan_and_states_the_bar() {
    let json = serde_json::to_value(report()).unwrap();
    assert_eq!(json["bar"]["heading_rmse_deg"], 25.0);
    assert_eq!(json["bar"]["speed_rmse_mps"], 1.5);
    assert!(json["readings"][1]["heading_rmse_deg"].is_null());
}

#[test]
fn the_csv_has_one_row_per_reading_and_empty_cells_for_missing_errors() {
    let csv = report().csv();
    assert_eq!(csv.lines().count(), 1 + 16);
    assert!(
        csv.contains("z_last,7,b.json,GP-KF,7.000000,0.350000,0.500000,true\n"),
        "{csv}"
    );
    assert!(
        csv.contains("z_last,7,b.json,SPGP-HET-ALL,,,0.500000,false\n"),
        "{csv}"
    );
}

#[test]
fn the_markdown_tables_hold_every_method_and_check() {
    let md = report().markdown();
    assert!(md.contains("| GP-KF | 4 | 8 | 22.5 | 1.12 |"), "{md}");
    assert!(md.contains("| check | GP-KF | SPGP-HET-ALL |"), "{md}");
    assert!(
        md.contains("| z_last | 2 of 4 (22.5 / 1.12) | 0 of 4 (– / –) |"),
        "{md}"
    );
    assert!(
        md.contains("each check on its file's own realism rung"),
        "{md}"
    );
}

#[test]
fn a_model_file_with_a_comma_is_quoted_in_the_csv() {
    assert_eq!(csv_field("a,b.json"), "\"a,b.json\"");
    assert_eq!(csv_field("say \"x\""), "\"say \"\"x\"\"\"");
    assert_eq!(csv_field("plain.json"), "plain.json");
}
