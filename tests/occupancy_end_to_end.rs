//! Occupancy maps end to end on the shipped T-junction: generate it (a planar scanner, 12 scans)
//! and its training run, learn DGPOM's motion map from the training run, map it with DGPOM, the
//! grid and both GPOMs (small settings), predict ahead with DGPOM, score against exact truth and
//! write the report. Checks that `occupancy.json` has the SPEC §7 shape, that every map beats chance, that
//! the plots are PNGs, and that a dataset of an older build (no `static.json`) is refused with
//! the file's name.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::sync::Arc;

use patchflow_eval::{
    OccupancyReport, SequenceKind, evaluate_occupancy, learn_motion_map, load_sequence,
    occupancy_sequences, predict_ahead_with, write_occupancy_report,
};
use patchflow_occupancy::{
    AheadParams, DgpomMethod, DgpomParams, GpSolver, GpomMethod, MapMethod, MapMethodId,
    OccupancyGridMethod, OccupancyParams, OccupancySequence, SampleParams, Thinning,
};
use patchflow_sim::{GenerateOptions, ScenarioSource, Shard, generate_dataset};

fn generate(dir: &std::path::Path, names: &[&str]) -> patchflow_dataset::Dataset {
    let sources: Vec<ScenarioSource> = names
        .iter()
        .map(|name| ScenarioSource::from_argument(std::path::Path::new(name)).unwrap())
        .collect();
    let options = GenerateOptions {
        realism: None,
        out: dir.to_owned(),
        seed: 3,
        shard: Shard::ALL,
        overwrite: false,
    };
    generate_dataset(&sources, &options, &|_| {}).unwrap();
    patchflow_dataset::Dataset::open(dir).unwrap()
}

fn small_run(dataset: &patchflow_dataset::Dataset) -> OccupancyReport {
    let samples = SampleParams {
        free_spacing_m: 3.0,
        ..SampleParams::default()
    };
    let small = |m: GpomMethod| GpomMethod {
        solver: GpSolver {
            exact_up_to: 0,
            pseudo_inputs: 60,
            ..GpSolver::default()
        },
        max_iters: 25,
        ..m
    };
    let motion_map = RefCell::new(None);
    let dgpom_method = RefCell::new(None);
    let methods =
        |sequence: &OccupancySequence, kind: SequenceKind, training: Option<&OccupancySequence>| {
            assert_eq!(kind, SequenceKind::Planar);
            // The training run is handed over for methods that learn beforehand, and not scored.
            assert_eq!(sequence.name, "dgpom_tjunction");
            assert_eq!(training.map(|t| t.scans.len()), Some(100));
            let map = learn_motion_map(training.unwrap()).unwrap();
            *motion_map.borrow_mut() = Some(Arc::clone(&map));
            // DGPOM keeps its default pseudo-inputs: with 60 its map at t = 3 fell to AUC 0.59.
            let dgpom = DgpomParams {
                samples: samples.clone(),
                max_iters: 25,
                ..DgpomParams::default()
            };
            let dgpom = DgpomMethod::new(dgpom, map);
            *dgpom_method.borrow_mut() = Some(dgpom.clone());
            let methods: Vec<Box<dyn MapMethod>> = vec![
                Box::new(dgpom),
                Box::new(small(GpomMethod::space(samples.clone()))),
                Box::new(small(GpomMethod::space_time(samples.clone()))),
                Box::new(OccupancyGridMethod::default()),
            ];
            Ok(methods)
        };
    let params = OccupancyParams {
        query_scans: vec![3, 5],
        ..OccupancyParams::default()
    };
    let mut report = evaluate_occupancy(dataset, &methods, &params, 7, &|_, _, _| {}).unwrap();
    let map = motion_map.into_inner().unwrap();
    report.motion_maps.insert("dgpom_tjunction".into(), map);
    let ahead = AheadParams {
        start_scans: vec![5],
        horizon_scans: 2,
        ..AheadParams::default()
    };
    // Predicting ahead from query time 5 reuses that map's fit: no third fit is made.
    let dgpom = dgpom_method.into_inner().unwrap();
    let methods = BTreeMap::from([("dgpom_tjunction".to_owned(), dgpom.clone())]);
    predict_ahead_with(dataset, &mut report, &ahead, &|| {}, &methods).unwrap();
    assert_eq!(dgpom.fits_kept(), 2);
    let at_scan = report.ahead["dgpom_tjunction"].auc[0][0];
    let map = report.scenarios[0].methods[&MapMethodId::Dgpom].auc_by_query_scan[&5];
    assert_eq!(Some(at_scan), map);
    report
}

#[test]
fn the_tjunction_is_mapped_scored_and_reported_in_the_spec_shape() {
    let dir = tempfile::tempdir().unwrap();
    let dataset = generate(
        &dir.path().join("data"),
        &["dgpom_tjunction", "dgpom_tjunction_train"],
    );
    let report = small_run(&dataset);
    let files = write_occupancy_report(&report, &dir.path().join("report")).unwrap();

    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&files.json).unwrap()).unwrap();
    let methods = json["scenarios"]["dgpom_tjunction"]["methods"]
        .as_object()
        .unwrap();
    let names: Vec<&str> = methods.keys().map(String::as_str).collect();
    assert_eq!(names, ["DGPOM", "GPOM-RD", "GPOM-RD1", "GRID"], "{json}");
    for (name, m) in methods {
        for t in ["3", "5"] {
            let auc = m["auc_by_query_time"][t].as_f64().unwrap();
            assert!(auc > 0.6 && auc <= 1.0, "{name} at t = {t}: AUC {auc}");
        }
        assert!(m["seconds_per_map"].as_f64().unwrap() >= 0.0, "{name}");
        assert!(
            m["training_points_per_map"].as_f64().unwrap() > 100.0,
            "{name}"
        );
    }
    // DGPOM's motion map and its predictions ahead (three times: 0, 1 and 2 s after the scan).
    let scenario = &json["scenarios"]["dgpom_tjunction"];
    assert_eq!(scenario["motion_map"]["velocity_points"], 500, "{json}");
    let ahead = scenario["predict_ahead"]["auc_mean"].as_array().unwrap();
    assert_eq!(ahead.len(), 3, "{json}");
    assert!(ahead.iter().all(|a| a.as_f64().unwrap() > 0.6), "{json}");
    assert_eq!(files.plots.len(), 6);
    for plot in &files.plots {
        let bytes = std::fs::read(plot).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{}", plot.display());
    }
    let markdown = std::fs::read_to_string(&files.markdown).unwrap();
    assert!(markdown.contains("GPOM ℜ^D (paper)") && markdown.contains("DGPOM ℜ^{D+1} (paper)"));
}

#[test]
fn a_dataset_without_static_truth_is_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    let dataset = generate(&data, &["dgpom_tjunction"]);
    let static_json = data.join("sequences/dgpom_tjunction/static.json");
    std::fs::remove_file(&static_json).unwrap();
    let grid = |_: &OccupancySequence, _: SequenceKind, _: Option<&OccupancySequence>| {
        let methods: Vec<Box<dyn MapMethod>> = vec![Box::new(OccupancyGridMethod::default())];
        Ok(methods)
    };
    let params = OccupancyParams::default();
    let err = evaluate_occupancy(&dataset, &grid, &params, 7, &|_, _, _| {}).unwrap_err();
    assert!(err.to_string().contains("static.json"), "{err}");
}

/// A small street for the 3-D lidar: a wall across the road 25 m ahead, a car crossing at 12 m,
/// the sensor parked; `rate` and `sweeps` as given.
fn street_3d(rate_hz: f64) -> String {
    format!(
        r#"description = "a parked 3-D lidar, a car crossing in front of a wall"
sweeps = 5
realism = "ideal"

[lidar]
channels = 32
azimuth_steps = 720
rate_hz = {rate_hz}
rolling_shutter = false
max_range_m = 30.0

[ego]
path_m = [[0.0, 0.0], [1.0, 0.0]]
speed_mps = 0.0

[[actors]]
name = "crossing"
path_m = [[12.0, -20.0], [12.0, 40.0]]
speed_mps = 5.0

[[structures]]
kind = "wall"
centre_m = [25.0, 0.0]
size_m = [0.5, 40.0, 3.0]
"#
    )
}

#[test]
fn a_one_hertz_3d_lidar_is_mapped_through_the_height_slice_and_a_ten_hertz_one_is_not() {
    let dir = tempfile::tempdir().unwrap();
    let files = [("slice_1hz", 1.0), ("driving_10hz", 10.0)].map(|(name, rate)| {
        let path = dir.path().join(format!("{name}.toml"));
        std::fs::write(&path, street_3d(rate)).unwrap();
        path
    });
    let names: Vec<&str> = files.iter().map(|p| p.to_str().unwrap()).collect();
    let dataset = generate(&dir.path().join("data"), &names);
    // Recognition: only the 1 Hz sequence is scored, read through the slice.
    assert_eq!(occupancy_sequences(&dataset).unwrap(), ["slice_1hz"]);
    let err = load_sequence(&dataset, "driving_10hz").unwrap_err();
    assert!(err.to_string().contains("10 Hz"), "{err}");
    let (sequence, kind) = load_sequence(&dataset, "slice_1hz").unwrap();
    assert_eq!(kind, SequenceKind::HeightSlice);
    assert!((sequence.scan_height_m() - 0.75).abs() < 1e-12);
    assert!(sequence.scans.iter().all(|s| s.hits() > 50));
    // The wall's slice returns lie on its face (x = 24.75), the car's on its side near x = 12.
    let hits: Vec<[f64; 2]> = sequence.scans[3]
        .beams
        .iter()
        .filter(|b| b.hit)
        .map(|b| b.end_m)
        .collect();
    assert!(
        hits.iter()
            .all(|p| (p[0] - 24.75).abs() < 0.1 || (p[0] - 12.0).abs() < 1.5)
    );
    // Mapped and scored: GPOM-RD on thinned samples ranks the truth well above chance.
    let samples = SampleParams {
        thinning: Some(Thinning {
            budget_per_scan: 300,
            ..Thinning::default()
        }),
        ..kind.sample_params(7)
    };
    let gpom = GpomMethod {
        solver: GpSolver {
            exact_up_to: 0,
            pseudo_inputs: 60,
            ..GpSolver::default()
        },
        max_iters: 25,
        ..GpomMethod::space(samples)
    };
    let methods: Vec<&dyn MapMethod> = vec![&gpom];
    let params = OccupancyParams {
        query_scans: vec![3],
        figure_scans: vec![],
        query_spacing_m: 1.0,
        ..OccupancyParams::default()
    };
    let scores =
        patchflow_occupancy::evaluate_sequence(&sequence, &methods, &params, &|_, _| {}).unwrap();
    let m = &scores.methods[&patchflow_occupancy::MapMethodId::GpomRd];
    assert!(m.training_points_per_map[0] <= 4 * 300);
    assert!(m.drawn_points_per_map[0] > m.training_points_per_map[0]);
    let auc = m.auc_by_query_scan[&3].unwrap();
    assert!(auc > 0.75, "AUC {auc}");
}
