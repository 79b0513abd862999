//! `patchflow score` on a small scene (issue #28): predictions equal to the truth score 0 and a
//! moving IoU of 1, zero flow scores what `evaluate` gives `ZERO-FLOW`, a folder written by
//! `patchflow flow` scores what `evaluate` gives that method, and broken folders are refused with
//! the file named.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use std::path::Path;

use patchflow_dataset::Dataset;
use patchflow_eval::{GpReadout, PredictionFolder, export_flow, score_predictions};
use patchflow_learn::{EstimatorParams, GpKind, MergeRule, MotionEstimator};

/// A per-point moving mask of a sweep.
type MaskOf<'a> = &'a dyn Fn(&patchflow_dataset::Sweep) -> Vec<u8>;

fn dataset(dir: &Path) -> Dataset {
    patchflow_tests::generate_scene(dir, "tiny", patchflow_tests::TRAFFIC_SCENE, 5)
}

/// Writes a prediction folder with `flow(sweep)` (and the moving mask `moving(sweep)`) for every
/// sweep of every sequence.
fn write_folder(
    data: &Dataset,
    root: &Path,
    flow: impl Fn(&patchflow_dataset::Sweep) -> Vec<[f32; 3]>,
    moving: Option<MaskOf<'_>>,
) {
    for info in data.sequences() {
        let sequence = data.sequence(&info.name).unwrap();
        let dir = root.join("sequences").join(&info.name);
        std::fs::create_dir_all(dir.join("flow")).unwrap();
        std::fs::create_dir_all(dir.join("moving")).unwrap();
        for k in 0..sequence.len() {
            let sweep = sequence.read_sweep(k).unwrap();
            let bytes: Vec<u8> = flow(&sweep)
                .iter()
                .flatten()
                .flat_map(|v| v.to_le_bytes())
                .collect();
            std::fs::write(dir.join(format!("flow/{k:06}.bin")), bytes).unwrap();
            if let Some(moving) = moving {
                std::fs::write(dir.join(format!("moving/{k:06}.bin")), moving(&sweep)).unwrap();
            }
        }
        if moving.is_none() {
            std::fs::remove_dir(dir.join("moving")).unwrap();
        }
    }
}

fn folder(root: &Path, name: &str) -> PredictionFolder {
    PredictionFolder {
        name: name.into(),
        root: root.to_owned(),
    }
}

fn tiny_model(data: &Dataset) -> MotionEstimator {
    let params = EstimatorParams {
        gp: GpKind::Spgp,
        samples: 150,
        pseudo_inputs: 6,
        max_iters: 8,
        ..EstimatorParams::default()
    };
    MotionEstimator::train(data, &params).unwrap()
}

#[test]
fn the_truth_scores_zero_error_and_a_moving_iou_of_one_and_zero_flow_scores_as_zero_flow() {
    let dir = tempfile::tempdir().unwrap();
    let data = dataset(dir.path());
    let truth = dir.path().join("truth");
    // Moving as the scoring defines it: faster than 0.5 m/s (Argoverse 2's dynamic threshold).
    let moving = |s: &patchflow_dataset::Sweep| {
        let speed = |v: &[f32; 3]| {
            f64::from(v[0])
                .hypot(f64::from(v[1]))
                .hypot(f64::from(v[2]))
        };
        s.flow_in_world_mps
            .iter()
            .map(|v| u8::from(speed(v) > 0.5))
            .collect()
    };
    write_folder(
        &data,
        &truth,
        |s| s.flow_in_world_mps.clone(),
        Some(&moving),
    );
    let zero = dir.path().join("zero");
    write_folder(&data, &zero, |s| vec![[0.0; 3]; s.len()], None);
    let model = tiny_model(&data);
    let report = score_predictions(
        &data,
        &[folder(&truth, "TRUTH"), folder(&zero, "ZERO")],
        &[model],
        None,
        &|| {},
    )
    .unwrap();
    let all = &report.pooled.methods;
    let t = &all["TRUTH"];
    assert!(t.scene_flow.points > 1000, "{:?}", t.scene_flow);
    assert!(t.scene_flow.epe3d_m.unwrap() < 1e-6, "{:?}", t.scene_flow);
    assert!(t.scene_flow.epe_threeway_m.unwrap() < 1e-6);
    assert!(t.moving_from_mask);
    assert!(t.moving_iou.unwrap() > 0.999, "{:?}", t.moving_iou);
    assert!(t.object_scans > 5);
    assert!(t.objects.speed_rmse_mps.unwrap() < 0.05, "{:?}", t.objects);
    assert!(t.objects.heading_rmse_deg.unwrap() < 1.0, "{:?}", t.objects);
    // Zero flow written as files scores exactly what `evaluate` gives ZERO-FLOW.
    assert_eq!(all["ZERO"].scene_flow, all["ZERO-FLOW"].scene_flow);
    assert_eq!(all["ZERO"].moving_iou, Some(0.0));
    for (name, sequence) in &report.sequences {
        let m = &sequence.methods;
        assert_eq!(m["ZERO"].scene_flow, m["ZERO-FLOW"].scene_flow, "{name}");
    }
}

#[test]
fn a_folder_written_by_flow_scores_what_evaluate_gives_that_method() {
    let dir = tempfile::tempdir().unwrap();
    let data = dataset(dir.path());
    let model = tiny_model(&data);
    let exported = dir.path().join("exported");
    let readout = GpReadout::Merged(MergeRule::All);
    export_flow(&data, &model, readout, &exported, &|| {}).unwrap();
    let report = score_predictions(
        &data,
        &[folder(&exported, "EXPORTED")],
        &[model],
        None,
        &|| {},
    )
    .unwrap();
    let (ours, theirs) = (
        report.pooled.methods["EXPORTED"].scene_flow,
        report.pooled.methods["SPGP-ALL"].scene_flow,
    );
    assert_eq!(ours.points, theirs.points);
    // The files hold float32 velocities; evaluate scores the float64 ones.
    let close = |a: Option<f64>, b: Option<f64>| (a.unwrap() - b.unwrap()).abs() < 1e-5;
    assert!(close(ours.epe3d_m, theirs.epe3d_m), "{ours:?}\n{theirs:?}");
    assert!(close(ours.epe_threeway_m, theirs.epe_threeway_m));
    assert!(close(ours.epe_fg_dynamic_m, theirs.epe_fg_dynamic_m));
    assert!(close(ours.acc_relax, theirs.acc_relax));
    assert!(close(ours.outliers, theirs.outliers));
    assert!(close(
        ours.normalised_dynamic_epe,
        theirs.normalised_dynamic_epe
    ));
}

#[test]
fn broken_prediction_folders_are_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let data = dataset(dir.path());
    let root = dir.path().join("pred");
    let fresh = || {
        let _ = std::fs::remove_dir_all(&root);
        write_folder(&data, &root, |s| vec![[0.0; 3]; s.len()], None);
    };
    let score = || {
        score_predictions(&data, &[folder(&root, "P")], &[], None, &|| {})
            .unwrap_err()
            .to_string()
    };
    let sequence = &data.sequences()[0].name;
    let file = root.join(format!("sequences/{sequence}/flow/000003.bin"));

    fresh();
    std::fs::write(&file, [0u8; 24]).unwrap();
    let err = score();
    assert!(
        err.contains("000003.bin") && err.contains("24 bytes"),
        "{err}"
    );

    fresh();
    std::fs::remove_file(&file).unwrap();
    assert!(score().contains("000003.bin"), "{}", score());

    fresh();
    let points = std::fs::metadata(&file).unwrap().len() as usize / 4;
    let nan: Vec<u8> = (0..points).flat_map(|_| f32::NAN.to_le_bytes()).collect();
    std::fs::write(&file, nan).unwrap();
    let err = score();
    assert!(err.contains("000003.bin") && err.contains("NaN"), "{err}");

    fresh();
    let mut inf = std::fs::read(&file).unwrap();
    inf[..4].copy_from_slice(&f32::INFINITY.to_le_bytes());
    std::fs::write(&file, inf).unwrap();
    assert!(score().contains("infinite"), "{}", score());

    fresh();
    std::fs::create_dir_all(root.join("sequences/someone_elses/flow")).unwrap();
    let err = score();
    assert!(
        err.contains("someone_elses") && err.contains("another dataset"),
        "{err}"
    );

    fresh();
    let moving = root.join(format!("sequences/{sequence}/moving"));
    std::fs::create_dir_all(&moving).unwrap();
    let err = score();
    assert!(err.contains("moving/000001.bin"), "{err}");
}
