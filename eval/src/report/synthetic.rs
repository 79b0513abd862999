//! Synthetic benchmark results for the report writers' tests: a car turning through ±180° with
//! methods of different quality, gaps and coverage.

use std::collections::BTreeMap;

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::estimate::MotionEstimate;
use crate::method::Method;
use crate::progress::StageTiming;
use crate::result::{BenchmarkReport, SituationResult};
use crate::truth_at_scan::TruthAtScan;

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
            },
            StageTiming {
                stage: "evaluate".into(),
                seconds: 0.5,
            },
        ],
        seed: Some(7),
        cv: None,
        scenes: Vec::new(),
    }
}
