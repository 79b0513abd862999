//! The notes section of a benchmark report: how the run was set up and how to read it.

use patchflow_learn::{FeatureParams, MotionEstimator};

use crate::pipeline::plan::BenchPlan;

/// The training tracks, and which share of their sweeps was simulated.
fn training_tracks(plan: &BenchPlan) -> String {
    let names = plan.training_names().join(", ");
    if plan.training_sweep_share < 1.0 {
        let percent = (100.0 * plan.training_sweep_share).round();
        format!("{names} (the last {percent:.0} % of each track's sweeps)")
    } else {
        names
    }
}

/// What a quick run leaves out, in front of the training note; empty for a full run. Every part
/// is read from the plan, beside the full plan's value.
fn quick_prefix(plan: &BenchPlan) -> String {
    if !plan.quick {
        return String::new();
    }
    let full = BenchPlan::full();
    let list = |scans: &[usize]| {
        let items: Vec<String> = scans.iter().map(usize::to_string).collect();
        items.join(", ")
    };
    let rungs = match plan.realism_rungs.as_slice() {
        [] => "every rung".to_owned(),
        some => {
            let names: Vec<&str> = some.iter().map(|r| r.name()).collect();
            names.join(" and ")
        }
    };
    format!(
        "Quick run (`--quick`): sequences {} (the full run: {}); GP kinds trained {} (the full run: {}; cross-validation compares SPGP and SPGP-HET either way){}; the realism study at {rungs}; occupancy maps at query times t = {} and predictions ahead from scans {} (the full run: t = {}, scans {}). ",
        plan.situation_names().join(", "),
        full.situation_names().join(", "),
        plan.gp_names().join(", "),
        full.gp_names().join(", "),
        if plan.thesis_preset {
            ""
        } else {
            "; no thesis preset (the full run reports its `SPGP-HET-ALL (thesis)` rows)"
        },
        list(&plan.occupancy_params.query_scans),
        list(&plan.ahead_params.start_scans),
        list(&full.occupancy_params.query_scans),
        list(&full.ahead_params.start_scans),
    )
}

/// The notes of a run; `load` is the machine's 1-minute load average at the start and the end of
/// the evaluation, where the system reports it.
pub(crate) fn notes(
    plan: &BenchPlan,
    estimators: &[MotionEstimator],
    load: Option<(f64, f64)>,
) -> Vec<String> {
    let mut notes = vec![format!(
        "{}Training tracks: {}. {} importance-sampled samples and their mirror images across the line of sight ({} rows per GP), {} pseudo-inputs, at most {} optimiser iterations per GP, seed {}. Training speed patches are aligned to the true heading plus a Gaussian error of {}° (the error of an estimated heading; thesis: exact heading).",
        quick_prefix(plan),
        training_tracks(plan),
        plan.samples,
        2 * plan.samples,
        plan.pseudo_inputs,
        plan.max_iters,
        plan.seed,
        FeatureParams::default().speed_jitter_deg
    )];
    let seeds = plan.training_seeds();
    if seeds.len() > 1 {
        let list: Vec<String> = seeds.iter().map(u64::to_string).collect();
        notes.push(format!(
            "Training seeds {}: the tables show seed {}; the section 'Spread over training seeds' gives each GP figure's mean ± std over all of them (each seed draws its own samples and fits its own GPs on the same simulated data).",
            list.join(", "),
            plan.seed
        ));
    }
    notes.push(
        "Why training differs from the thesis (docs/estimator.md has the measurements that found it): at run time speed patches follow the estimated heading, and a speed GP trained only on exactly aligned patches read a car whose merged heading was 30-60° off as nearly still; and right-hand traffic puts most drawn samples on one side of the line of sight, which the GPs learned as a prior that misreads a target crossing from the other side. The default also fits a most-likely heteroscedastic noise GP (thesis Ch. 6; docs/estimator.md). `patchflow train --preset thesis` trains by the thesis' protocol exactly (neither addition, no noise GP, a zero mean function); the rows `SPGP-HET-ALL (thesis)` are that preset."
            .to_owned(),
    );
    notes.push(
        "Reading the breakdown tables: the height slice (0.5-0.85 m above ground for the default, 0.5-1.0 m for the thesis preset) holds fewer lidar rings the farther the target, so map patches of distant targets carry little motion (the thesis gives 40-50 m as the usable range, 4.1); and a cluster with few points fixes a rotation poorly, which is where ICP is hurt (thesis 4.4). Compare each method's error in the first and last columns."
            .to_owned(),
    );
    notes.push(
        "Baselines on simulated clusters: the situations are simulated on the default realism rung (`urban`), where street clutter, parked cars, mixed pixels and ray drop join, split and hide parts of clusters, as partial views and segmentation errors do on the thesis' real data (4.4); on the `ideal` rung (the realism study below) every target point is segmented cleanly and ICP and the Kalman filter are far better than on real data. The auto-association variants show the cost of doing the association without ground truth."
            .to_owned(),
    );
    notes.push(
        "Reading the whole-scene tables: the GP estimators were trained on moving actors only (thesis 3.1.2), so they have no way to say \"standing still\" and give parked cars and standing people a speed; that is their foreground-static EPE, and why zero flow beats them on EPE3D, where standing points are the majority. Their errors on moving points (foreground-dynamic EPE, normalised EPE) are the ones to compare with the baselines'."
            .to_owned(),
    );
    if let Some((before, after)) = load {
        let cores = std::thread::available_parallelism().map_or(0, usize::from);
        notes.push(format!(
            "The machine's 1-minute load average was {before:.1} when the evaluation started and {after:.1} when it ended, on {cores} cores: wall times of the perception grow with the load, its CPU times hardly."
        ));
    }
    for e in estimators {
        for (target, gp) in ["sin_rel", "cos_rel", "speed"].iter().zip(e.gps()) {
            let r = gp.fit_report();
            notes.push(format!(
                "{} {target}: n={} d={} m={}, {} evaluations in {:.1} s, NLML {:.2} ({}).",
                e.gp_kind().name().to_uppercase(),
                r.n,
                r.d,
                r.m,
                r.evals,
                r.seconds,
                r.nlml,
                r.stop
            ));
        }
    }
    notes
}
