//! Synthetic benchmark results for the report writers' tests: a car turning through ±180° with
//! methods of different quality, gaps and coverage; and whole-scene results of random points,
//! objects and timings.

use std::collections::BTreeMap;

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::methods::estimate::MotionEstimate;
use crate::methods::method::Method;
use crate::report::benchmark_report::BenchmarkReport;
use crate::report::stage_timing::StageTiming;
use crate::scene::result::{SceneResult, SituationResult};
use crate::scene::truth_at_scan::TruthAtScan;

/// A situation of `scans` scans: heading turns from 150° through 180° to −140°, speed 4-8 m/s
/// (and 0.3 m/s, unscored for heading, in the first two scans).
pub(crate) fn synthetic_situation(name: &str, scans: usize, seed: u64) -> SituationResult {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let truth: Vec<TruthAtScan> = (0..scans)
        .map(|k| {
            let u = k as f64 / scans as f64;
            let heading = (150.0 + 70.0 * u).to_radians();
            let speed = if k < 2 { 0.3 } else { 4.0 + 4.0 * u };
            TruthAtScan::from_velocity(k, [speed * heading.cos(), speed * heading.sin()])
        })
        .collect();
    let mut noisy = |heading_std_deg: f64, speed_std: f64, skip: &dyn Fn(usize) -> bool| {
        truth
            .iter()
            .map(|t| {
                if skip(t.scan) {
                    return None;
                }
                let h = t.heading_rad + rng.random_range(-1.0..1.0) * heading_std_deg.to_radians();
                let s = (t.speed_mps + rng.random_range(-1.0..1.0) * speed_std).max(0.0);
                Some(MotionEstimate::from_velocity([s * h.cos(), s * h.sin()]))
            })
            .collect::<Vec<_>>()
    };
    let mut methods = BTreeMap::new();
    methods.insert(Method::Kf, noisy(3.0, 0.4, &|k| k == 0));
    methods.insert(Method::Icp, noisy(12.0, 1.5, &|k| k == 0 || k == 7));
    methods.insert(Method::SpgpHetAll, noisy(8.0, 0.8, &|k| k % 5 == 3));
    methods.insert(Method::KfAuto, noisy(4.0, 0.5, &|k| k < 3));
    methods.insert(Method::FullGpAll, noisy(20.0, 2.0, &|_| false));
    SituationResult {
        name: name.to_owned(),
        scans,
        truth,
        methods,
    }
}

/// Two situations (`situation1` with 30 scans, `situation4` with 24), notes and timings.
pub(crate) fn synthetic_report() -> BenchmarkReport {
    BenchmarkReport {
        situations: vec![
            synthetic_situation("situation1", 30, 1),
            synthetic_situation("situation4", 24, 2),
        ],
        notes: vec!["synthetic results for a test".into()],
        timings: vec![
            StageTiming {
                stage: "generate".into(),
                seconds: 1.25,
                cpu_seconds: Some(2.0),
            },
            StageTiming {
                stage: "evaluate".into(),
                seconds: 0.5,
                cpu_seconds: Some(0.75),
            },
        ],
        seed: Some(7),
        cv: None,
        scenes: Vec::new(),
        descriptions: Default::default(),
        scene_figures: Default::default(),
    }
}

/// A whole scene of `scans` scans: random scored points for four methods, a moving car and a
/// walking pedestrian at every scan, and scan timings.
pub(crate) fn synthetic_scene(name: &str, scans: usize, seed: u64) -> SceneResult {
    use crate::scene::objects::ObjectScan;
    use crate::scene::perception_timing::{ScanTiming, StepTiming};
    use crate::scene::scene_flow::SceneFlowTally;
    use crate::scene::scene_point::FlowClass;
    use patchflow_dataset::ActorClass;

    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let methods = [
        (Method::KfAuto, 0.02),
        (Method::SpgpHetAll, 0.1),
        (Method::SpgpHetPoint, 0.2),
        (Method::ZeroFlow, -1.0),
    ];
    let mut scene_flow: BTreeMap<Method, SceneFlowTally> = BTreeMap::new();
    for _ in 0..scans * 50 {
        let class = FlowClass::ALL[rng.random_range(0..FlowClass::ALL.len())];
        let speed = if class.is_foreground() {
            rng.random_range(0.0..12.0)
        } else {
            0.0
        };
        let truth = [speed * 0.1, 0.0, 0.0];
        for (method, noise) in methods {
            let predicted = if noise < 0.0 {
                [0.0; 3]
            } else {
                [
                    truth[0] + rng.random_range(-noise..noise),
                    rng.random_range(-noise..noise),
                    0.0,
                ]
            };
            scene_flow
                .entry(method)
                .or_default()
                .add(predicted, truth, class, 0.1);
        }
    }
    let mut objects = Vec::new();
    for scan in 0..scans {
        for (actor, class, velocity) in [
            (1, ActorClass::Car, [6.0, 1.0]),
            (2, ActorClass::Pedestrian, [0.0, 1.3]),
        ] {
            let truth = TruthAtScan {
                range_m: Some(5.0 + 3.0 * scan as f64),
                target_points: Some(20 + 40 * scan),
                ..TruthAtScan::from_velocity(scan, velocity)
            };
            let noisy = |std: f64, rng: &mut ChaCha8Rng| {
                Some(MotionEstimate::from_velocity([
                    velocity[0] + rng.random_range(-std..std),
                    velocity[1] + rng.random_range(-std..std),
                ]))
            };
            let estimates = BTreeMap::from([
                (Method::KfAuto, noisy(0.3, &mut rng)),
                (Method::SpgpHetAll, noisy(1.0, &mut rng)),
                (
                    Method::ZeroFlow,
                    Some(MotionEstimate::from_velocity([0.0, 0.0])),
                ),
            ]);
            let point_epe_m = methods
                .iter()
                .map(|(m, noise)| (*m, noise.max(0.6) * rng.random_range(0.5..1.0)))
                .collect();
            objects.push(ObjectScan {
                scan,
                actor,
                class,
                truth,
                estimates,
                point_epe_m,
            });
        }
    }
    let timing = (0..scans)
        .map(|k| ScanTiming {
            slice_secs: 0.002,
            maps_secs: 0.015 + 0.001 * k as f64,
            clusters_secs: 0.001,
            maps_and_clusters_secs: 0.016 + 0.001 * k as f64,
            estimators: vec![StepTiming {
                patches_secs: 0.004,
                gp_secs: 0.010,
                samples: 300,
                points: 1500,
                ..StepTiming::default()
            }],
            whole_scan_cpu_secs: Some(0.05),
            ..ScanTiming::default()
        })
        .collect();
    SceneResult {
        name: name.to_owned(),
        scans,
        scene_flow,
        objects,
        timing,
    }
}

/// [`synthetic_report`] with whole-scene results for both situations and for `dense`, a sequence
/// without a target.
pub(crate) fn synthetic_report_with_scenes() -> BenchmarkReport {
    BenchmarkReport {
        scenes: vec![
            synthetic_scene("situation1", 30, 3),
            synthetic_scene("situation4", 24, 4),
            synthetic_scene("dense", 12, 5),
        ],
        ..synthetic_report()
    }
}
