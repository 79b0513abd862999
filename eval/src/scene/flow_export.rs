//! Exports an estimator's per-point scene flow beside the dataset's layout, for other tools:
//! `OUT/sequences/<name>/flow/NNNNNN.bin`, float32 vx, vy, vz per point of the sweep, world frame,
//! m/s, exactly like the dataset's own `flow/` truth.
//!
//! Points the pipeline does not see (outside the height slice or the map window) and every point
//! of a sequence's first sweep (no predecessor, so no difference map) are NaN; points of clusters
//! that are no object hypothesis are 0 (standing, as the benchmark scores them).

use std::path::Path;

use patchflow_dataset::{Dataset, write_atomic};
use patchflow_learn::{MergeRule, MotionEstimator, ScanMotion, ScanStream, SweepFeatures};

use crate::error::EvalError;
use crate::methods::method::GpReadout;

/// Fastest flow a prediction may give, m/s: far above any road user; a model predicting more
/// (or a non-finite value) is broken, and its export is refused rather than written.
pub const MAX_FLOW_MPS: f64 = 1000.0;

/// Writes the flow of every sweep of every sequence of `dataset` into `out` (the same layout);
/// returns the number of sweeps written. `on_sweep` is called once per sweep.
pub fn export_flow(
    dataset: &Dataset,
    estimator: &MotionEstimator,
    readout: GpReadout,
    out: &Path,
    on_sweep: &(dyn Fn() + Sync),
) -> Result<usize, EvalError> {
    let mut written = 0;
    for info in dataset.sequences() {
        let sequence = dataset.sequence(&info.name)?;
        let dir = out.join("sequences").join(&info.name).join("flow");
        std::fs::create_dir_all(&dir).map_err(|e| EvalError::io(&dir, e))?;
        let write = |index: usize, velocities: &[[f32; 3]]| -> Result<(), EvalError> {
            let bytes: Vec<u8> = velocities
                .iter()
                .flatten()
                .flat_map(|v| v.to_le_bytes())
                .collect();
            write_atomic(&dir.join(format!("{index:06}.bin")), &bytes)?;
            on_sweep();
            Ok(())
        };
        if sequence.is_empty() {
            continue;
        }
        write(0, &vec![[f32::NAN; 3]; sequence.read_sweep(0)?.len()])?;
        written += 1;
        let mut stream = ScanStream::new(&sequence, vec![estimator.feature_params().clone()])?;
        while let Some((index, sweep)) = stream.read_next()? {
            let features = stream.features_of(&sweep)?;
            let motion = estimator.estimate_features(&features[0])?;
            let mut velocities = vec![[f32::NAN; 3]; sweep.len()];
            for (i, point) in features[0].points().iter().enumerate() {
                let [vx, vy] = velocity(&features[0], &motion, readout, i);
                let speed = vx.hypot(vy);
                if !speed.is_finite() || speed > MAX_FLOW_MPS {
                    return Err(EvalError::BadObservation {
                        situation: info.name.clone(),
                        scan: index,
                        reason: format!(
                            "the model predicts a speed of {} m/s at point {} (more than {MAX_FLOW_MPS} m/s, or not a number): the model file is broken; no flow file written for this sweep",
                            vx.hypot(vy),
                            point.index
                        ),
                    });
                }
                velocities[point.index] = [vx as f32, vy as f32, 0.0];
            }
            write(index, &velocities)?;
            written += 1;
        }
    }
    Ok(written)
}

/// The velocity the estimator gives sliced point `i`, world frame, m/s (0 outside hypotheses).
fn velocity(
    features: &SweepFeatures,
    motion: &ScanMotion,
    readout: GpReadout,
    i: usize,
) -> [f64; 2] {
    let merged = |rule: MergeRule| {
        let estimate = motion.clusters[features.cluster_of(i)]?;
        let m = match rule {
            MergeRule::All => estimate.all,
            MergeRule::Best => estimate.best,
        }?;
        let (s, c) = m.heading_rad.sin_cos();
        Some([m.speed_mps * c, m.speed_mps * s])
    };
    let v = match readout {
        GpReadout::Merged(rule) => merged(rule),
        GpReadout::PerPoint => motion.points[i].map(|p| p.velocity_xy_mps()),
    };
    v.unwrap_or([0.0, 0.0])
}

#[cfg(test)]
mod tests {
    use super::*;
    use patchflow_dataset::{Pose, SequenceWriter};
    use patchflow_learn::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
    use patchflow_learn::{EstimatorParams, FeatureParams, GpKind};

    /// Tracks of a car at several headings past a sensor at the origin, 6 sweeps each.
    fn dataset(root: &Path, headings: &[f64]) -> Dataset {
        dataset_with_target(root, headings, false)
    }

    /// [`dataset`], with the car marked as the sequence's target when `target`.
    fn dataset_with_target(root: &Path, headings: &[f64], target: bool) -> Dataset {
        let lidar = SyntheticLidar::with_resolution(24, 720);
        for (k, &heading) in headings.iter().enumerate() {
            let writer = SequenceWriter::open(root, &format!("track{k}")).unwrap();
            let mut scene = SyntheticScene {
                boxes: vec![SceneBox::car(1, [9.0, 3.0], heading, 6.0)],
            };
            let (mut poses, mut stamps): (Vec<Pose>, Vec<f64>) = (Vec::new(), Vec::new());
            for i in 0..6 {
                let mut sweep = scene.scan(&lidar, [0.0, 0.0], 0.0, i);
                sweep.objects[0].target = target;
                writer.write_sweep(&sweep).unwrap();
                poses.push(sweep.world_from_sensor);
                stamps.push(sweep.stamp_secs);
                scene = scene.advanced(0.1);
            }
            writer
                .finish("synthetic", 0, 10.0, &poses, &stamps, "test")
                .unwrap();
        }
        Dataset::open(root).unwrap()
    }

    fn floats(path: &Path) -> Vec<f32> {
        std::fs::read(path)
            .unwrap()
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect()
    }

    /// A small SPGP estimator that trains in a fraction of a second.
    fn tiny_params() -> EstimatorParams {
        EstimatorParams {
            gp: GpKind::Spgp,
            features: FeatureParams {
                half_extent_m: 20.0,
                ..FeatureParams::default()
            },
            samples: 60,
            pseudo_inputs: 5,
            max_iters: 5,
            ..EstimatorParams::default()
        }
    }

    /// A model trained on `data` whose speed GP's targets were standardised around 1e200 m/s.
    fn broken_model(dir: &Path, data: &Dataset) -> MotionEstimator {
        broken_model_with(dir, data, &tiny_params())
    }

    /// [`broken_model`] trained with `params`.
    fn broken_model_with(dir: &Path, data: &Dataset, params: &EstimatorParams) -> MotionEstimator {
        let model = dir.join("m.json");
        MotionEstimator::train(data, params)
            .unwrap()
            .save(&model)
            .unwrap();
        let mut json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(&model).unwrap()).unwrap();
        json["speed"]["target_transform"]["mean"] = serde_json::json!([1e200]);
        std::fs::write(&model, serde_json::to_vec(&json).unwrap()).unwrap();
        MotionEstimator::load(&model).unwrap()
    }

    #[test]
    fn a_model_predicting_astronomical_speeds_is_refused_naming_the_sweep() {
        let dir = tempfile::tempdir().unwrap();
        let data = dataset(&dir.path().join("data"), &[0.4]);
        let estimator = broken_model(dir.path(), &data);
        let out = dir.path().join("flow");
        let err = export_flow(
            &data,
            &estimator,
            GpReadout::Merged(MergeRule::All),
            &out,
            &|| {},
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("track0, scan 1") && err.contains("m/s"),
            "{err}"
        );
        assert!(!out.join("sequences/track0/flow/000001.bin").exists());
    }

    #[test]
    fn evaluating_a_model_predicting_astronomical_speeds_is_refused_naming_the_sequence_and_scan() {
        let dir = tempfile::tempdir().unwrap();
        let data = dataset(&dir.path().join("data"), &[0.4]);
        let estimator = broken_model(dir.path(), &data);
        let sequence = data.sequence("track0").unwrap();
        let Err(err) = crate::scene::scene_evaluation::evaluate_sequence(
            &sequence,
            &[estimator],
            &crate::BaselineParams::default(),
            None,
            &|| {},
        ) else {
            panic!("a model predicting 1e200 m/s was evaluated");
        };
        let err = err.to_string();
        assert!(
            err.contains("track0") && err.contains("1000 m/s") && err.contains("broken"),
            "{err}"
        );
    }

    #[test]
    fn a_broken_model_with_other_feature_parameters_than_the_first_is_refused_too() {
        let dir = tempfile::tempdir().unwrap();
        let data = dataset_with_target(&dir.path().join("data"), &[0.4], true);
        let good = MotionEstimator::train(&data, &tiny_params()).unwrap();
        let mut other = tiny_params();
        other.features.half_extent_m = 18.0; // its own maps: it predicts the target only
        let broken = broken_model_with(dir.path(), &data, &other);
        let sequence = data.sequence("track0").unwrap();
        let Err(err) = crate::scene::scene_evaluation::evaluate_sequence(
            &sequence,
            &[good, broken],
            &crate::BaselineParams::default(),
            None,
            &|| {},
        ) else {
            panic!("the second model's 1e200 m/s target estimate was evaluated");
        };
        let err = err.to_string();
        assert!(
            err.contains("track0") && err.contains("model 2 of 2") && err.contains("1000 m/s"),
            "{err}"
        );
    }

    #[test]
    fn every_sweep_gets_a_flow_file_like_the_datasets_with_nan_where_nothing_was_seen() {
        let dir = tempfile::tempdir().unwrap();
        let data = dataset(&dir.path().join("data"), &[0.4, 2.0]);
        let estimator = MotionEstimator::train(&data, &tiny_params()).unwrap();
        let out = dir.path().join("flow");
        let written = export_flow(
            &data,
            &estimator,
            GpReadout::Merged(MergeRule::All),
            &out,
            &|| {},
        )
        .unwrap();
        assert_eq!(written, 12);
        let sequence = data.sequence("track0").unwrap();
        let first = floats(&out.join("sequences/track0/flow/000000.bin"));
        assert_eq!(first.len(), 3 * sequence.read_sweep(0).unwrap().len());
        assert!(first.iter().all(|v| v.is_nan()));
        let sweep = sequence.read_sweep(3).unwrap();
        let flow = floats(&out.join("sequences/track0/flow/000003.bin"));
        assert_eq!(flow.len(), 3 * sweep.len());
        // The car's sliced points move; ground points, never in the slice, are NaN.
        let on_car: Vec<&[f32]> = flow
            .chunks_exact(3)
            .zip(&sweep.labels)
            .filter(|(v, l)| l.instance() == 1 && !v[0].is_nan())
            .map(|(v, _)| v)
            .collect();
        assert!(on_car.len() > 10);
        assert!(on_car.iter().all(|v| v[0].hypot(v[1]) > 0.0 && v[2] == 0.0));
        let ground = flow
            .chunks_exact(3)
            .zip(&sweep.labels)
            .filter(|(_, l)| l.semantic() == 40);
        assert!(ground.clone().count() > 0 && ground.clone().all(|(v, _)| v[0].is_nan()));
    }
}
