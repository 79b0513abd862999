//! The per-target rows of the learned trackers (issue 27) without a whole benchmark: loads the
//! SPGP-HET model and the moving classifier a `bench --keep-data` folder saved, runs the target
//! protocol of every situation (the baselines, GP-KF and GP-ICP; `evaluate_targets_with_baselines`,
//! as the realism study and the further seeds do) and prints each method's heading and speed RMSE
//! and coverage with the bounds: GP-KF against min(KF-AUTO, SPGP-HET-ALL) + 2° and
//! KF-AUTO's speed, GP-ICP against ICP-AUTO likewise. `TRACE=situationN` also prints that
//! situation sweep by sweep (numbered as `patchflow show --scan` numbers them), with the heading
//! standard deviation the GP and GP-KF state and GP-KF's speed standard deviation.
//!
//! `cargo run --release -p patchflow-eval --example learned_targets -- BENCH_OUT [MODEL.json]`
//! (a thesis-preset model, `spgp-het-thesis.json`, prints its rows as `SPGP-HET-ALL (thesis)`)

use std::path::PathBuf;

use patchflow_dataset::Dataset;
use patchflow_eval::{
    BaselineParams, Method, score_method, stages::evaluate_targets_with_baselines,
};
use patchflow_learn::{MotionEstimator, MovingClassifier};

type Failure = Box<dyn std::error::Error>;

fn main() -> Result<(), Failure> {
    let mut args = std::env::args().skip(1);
    let root = PathBuf::from(
        args.next()
            .ok_or("usage: learned_targets BENCH_OUT [MODEL]")?,
    );
    let model = args
        .next()
        .map_or_else(|| root.join("models/spgp-het.json"), PathBuf::from);
    let estimator = MotionEstimator::load(&model)?;
    let moving = MovingClassifier::load(&root.join("models/moving.json"))?;
    let situations = Dataset::open(&root.join("data/situations"))?;
    let report = evaluate_targets_with_baselines(
        &situations,
        &[estimator],
        &BaselineParams::default(),
        Some(&moving),
    )?;
    // A thesis-preset model (`spgp-het-thesis.json`) scores as its own method.
    let methods = [
        Method::SpgpHetAll,
        Method::SpgpHetAllThesis,
        Method::KfAuto,
        Method::GpKf,
        Method::IcpAuto,
        Method::GpIcp,
    ];
    println!("| situation | method | heading RMSE (°) | speed RMSE (m/s) | coverage |");
    println!("|---|---|---|---|---|");
    let mut within = [[0usize; 2]; 2];
    let trace = std::env::var("TRACE").ok();
    for situation in &report.situations {
        if trace.as_deref() == Some(situation.name.as_str()) {
            // Numbered by sweep, as `patchflow show --scan` and `target_votes` number them (the
            // first sweep has no previous one and no estimate).
            println!(
                "sweep | true h,s | SPGP h,s,σh | KF-AUTO h,s | GP-KF h,s,σh,σs | ICP-AUTO h,s | GP-ICP h,s"
            );
            let show =
                |e: Option<&Option<patchflow_eval::MotionEstimate>>| match e.copied().flatten() {
                    Some(e) => format!("{:7.1} {:5.2}", e.heading_rad.to_degrees(), e.speed_mps),
                    None => "      -     -".to_owned(),
                };
            // A standard deviation the method states, from its variance: the heading's in degrees
            // (`degrees`), the speed's in m/s.
            let spread = |e: Option<&Option<patchflow_eval::MotionEstimate>>, degrees: bool| {
                let var = e
                    .copied()
                    .flatten()
                    .and_then(|e| if degrees { e.heading_var } else { e.speed_var });
                match var {
                    Some(var) if degrees => format!(" {:5.1}", var.sqrt().to_degrees()),
                    Some(var) => format!(" {:5.2}", var.sqrt()),
                    None => "     -".to_owned(),
                }
            };
            for (k, t) in situation.truth.iter().enumerate() {
                let of = |m: Method| situation.methods.get(&m).and_then(|v| v.get(k));
                println!(
                    "{:5} | {:7.1} {:5.2} | {}{} | {} | {}{}{} | {} | {}",
                    k + 1,
                    t.heading_rad.to_degrees(),
                    t.speed_mps,
                    show(of(Method::SpgpHetAll)),
                    spread(of(Method::SpgpHetAll), true),
                    show(of(Method::KfAuto)),
                    show(of(Method::GpKf)),
                    spread(of(Method::GpKf), true),
                    spread(of(Method::GpKf), false),
                    show(of(Method::IcpAuto)),
                    show(of(Method::GpIcp))
                );
            }
        }
        let mut rows = Vec::new();
        for method in methods {
            let Some(estimates) = situation.methods.get(&method) else {
                continue;
            };
            let m = score_method(&situation.truth, estimates)?;
            let (h, s) = (
                m.heading_rmse_deg.unwrap_or(f64::NAN),
                m.speed_rmse_mps.unwrap_or(f64::NAN),
            );
            println!(
                "| {} | {method} | {h:.2} | {s:.3} | {:.3} |",
                situation.name, m.coverage
            );
            rows.push((method, h, s));
        }
        let of = |wanted: Method| rows.iter().find(|(m, ..)| *m == wanted).map(|r| (r.1, r.2));
        for (k, (learned, baseline)) in [
            (Method::GpKf, Method::KfAuto),
            (Method::GpIcp, Method::IcpAuto),
        ]
        .into_iter()
        .enumerate()
        {
            if let (Some(l), Some(b), Some(gp)) =
                (of(learned), of(baseline), of(Method::SpgpHetAll))
            {
                within[k][0] += usize::from(l.0 <= b.0.min(gp.0) + 2.0);
                within[k][1] += usize::from(l.1 <= b.1);
            }
        }
    }
    let n = report.situations.len();
    println!(
        "\nGP-KF within: heading {}/{n}, speed {}/{n}; GP-ICP within: heading {}/{n}, speed {}/{n}",
        within[0][0], within[0][1], within[1][0], within[1][1]
    );
    Ok(())
}
