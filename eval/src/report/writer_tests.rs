//! Tests of the report writer: every file, names, shapes, and the whole-scene sections.

use super::*;
use crate::report::synthetic::{synthetic_report, synthetic_report_with_scenes};

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
    assert_eq!(
        files.plots.len(),
        5,
        "heading and speed per situation, the summary"
    );
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
    let columns = lines[0].split(',').count();
    assert!(lines.iter().all(|l| l.split(',').count() == columns));
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
    let icp_row = section
        .lines()
        .find(|l| l.starts_with("| ICP (oracle) |"))
        .unwrap();
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
        .insert(crate::methods::method::Method::Kf, vec![None; 3]);
    let err = write_report(&report, dir.path()).unwrap_err().to_string();
    assert!(err.contains("situation4") && err.contains("KF"), "{err}");
}

#[test]
fn whole_scene_results_reach_every_file() {
    let dir = tempfile::tempdir().unwrap();
    let files = write_report(&synthetic_report_with_scenes(), dir.path()).unwrap();
    // metrics.json: scene flow for every method (ZERO-FLOW too) and objects per situation; a
    // sequence without a target has only whole-scene entries.
    let value: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&files.metrics_json).unwrap()).unwrap();
    let s1 = &value["situations"]["situation1"];
    for method in ["KF-AUTO", "SPGP-HET-ALL", "SPGP-HET-POINT", "ZERO-FLOW"] {
        let flow = &s1["methods"][method]["scene_flow"];
        for key in [
            "epe3d_m",
            "acc_strict",
            "acc_relax",
            "outliers",
            "epe_threeway_m",
            "normalised_dynamic_epe",
        ] {
            assert!(flow[key].is_number(), "{method} {key}: {flow}");
        }
    }
    assert_eq!(
        s1["methods"]["ZERO-FLOW"]["scene_flow"]["normalised_dynamic_epe"],
        1.0
    );
    assert!(s1["methods"]["KF"]["heading_rmse_deg"].is_number());
    assert!(s1["methods"]["ZERO-FLOW"].get("heading_rmse_deg").is_none());
    assert!(s1["objects"]["KF-AUTO"]["object_scans"].as_u64().unwrap() > 0);
    let dense = &value["situations"]["dense"];
    assert!(dense["methods"]["KF-AUTO"].get("coverage").is_none());
    assert!(dense["methods"]["KF-AUTO"]["scene_flow"]["epe3d_m"].is_number());
    assert!(value["objects"]["by_class"]["pedestrian"]["KF-AUTO"].is_object());
    assert!(value["objects"]["moving"]["ZERO-FLOW"]["heading_rmse_deg"].is_null());
    // tables.csv: a row per sequence and method.
    let csv = std::fs::read_to_string(&files.tables_csv).unwrap();
    assert!(csv.lines().any(|l| l.starts_with("dense,ZERO-FLOW,")));
    assert!(
        csv.lines()
            .any(|l| l.starts_with("situation1,SPGP-HET-POINT,"))
    );
    // report.md: the sections, with the metrics' sources; the plots and perception.json exist.
    let md = std::fs::read_to_string(&files.report_md).unwrap();
    for needle in [
        "## Whole scene: every object, every point",
        "#### By class",
        "### Scene flow",
        "Neural_Scene_Flow_Prior",
        "av2-api",
        "BucketedSceneFlowEval",
        "#### dense (12 scans)",
        "## Perception per scan",
    ] {
        assert!(md.contains(needle), "{needle} missing");
    }
    for plot in ["objects_epe_by_range.png", "objects_epe_by_points.png"] {
        let bytes = std::fs::read(dir.path().join("plots").join(plot)).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    }
    let perception: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&files.perception_json).unwrap()).unwrap();
    assert_eq!(
        perception.as_array().unwrap().last().unwrap()["name"],
        "all"
    );
}

#[test]
fn per_target_tables_do_not_change_when_whole_scene_results_are_added() {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let plain = write_report(&synthetic_report(), a.path()).unwrap();
    let with = write_report(&synthetic_report_with_scenes(), b.path()).unwrap();
    let section = |path: &std::path::Path| {
        let md = std::fs::read_to_string(path).unwrap();
        let start = md.find("## Summary").unwrap();
        let end = md
            .find("## Whole scene")
            .or_else(|| md.find("## Timing"))
            .unwrap();
        md[start..end].to_owned()
    };
    assert_eq!(section(&plain.report_md), section(&with.report_md));
}

#[test]
fn a_report_of_own_scenarios_has_their_descriptions_and_no_thesis_placeholders() {
    let dir = tempfile::tempdir().unwrap();
    let mut report = synthetic_report();
    report.situations = vec![
        crate::report::synthetic::synthetic_situation("my_roundabout", 20, 3),
        crate::report::synthetic::synthetic_situation("situation4", 24, 2),
    ];
    report
        .descriptions
        .insert("my_roundabout".into(), "a van circles a roundabout".into());
    let files = write_report(&report, dir.path()).unwrap();
    let md = std::fs::read_to_string(&files.report_md).unwrap();
    let own = &md[md.find("## my_roundabout").unwrap()..md.find("## situation4").unwrap()];
    assert!(
        own.contains("Scenario: a van circles a roundabout."),
        "{own}"
    );
    for placeholder in ["Hess 2008", "layout of thesis", "| – | – |", "cf. thesis"] {
        assert!(!own.contains(placeholder), "{placeholder} in {own}");
    }
    // The thesis situation beside it keeps its thesis columns.
    assert!(
        md.contains("### Heading (degrees; layout of thesis Table 4.12)"),
        "{md}"
    );
}

#[test]
fn a_report_of_own_scenarios_alone_does_not_mention_the_thesis_tables() {
    let dir = tempfile::tempdir().unwrap();
    let mut report = synthetic_report();
    report.situations = vec![crate::report::synthetic::synthetic_situation(
        "crossing", 20, 3,
    )];
    let files = write_report(&report, dir.path()).unwrap();
    let md = std::fs::read_to_string(&files.report_md).unwrap();
    assert!(
        !md.contains("Hess 2008") && !md.contains("Tables 4.13"),
        "{md}"
    );
}
