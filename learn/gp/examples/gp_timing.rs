//! Times the SPGP objective + gradient and one full fit at the thesis size (N = 1,600, M = 100,
//! D = 242), printing wall time and process CPU time (the machine may be shared, so CPU time
//! divided by the thread count is the fairer figure).
//!
//! `cargo run --release -p patchflow-gp --example gp_timing -- [N] [D] [M] [EVALS] [fit]`

use std::time::Instant;

use nalgebra::{DMatrix, DVector};
use patchflow_gp::{GpKind, GpObjective, GpParams};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Process CPU time (user + system) in seconds, from /proc/self/stat (Linux only; 0 elsewhere).
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit(')')
        .next()
        .unwrap_or("")
        .split_whitespace()
        .collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    (ticks(11) + ticks(12)) / 100.0
}

fn main() -> Result<(), patchflow_gp::GpError> {
    let args: Vec<String> = std::env::args().collect();
    let arg =
        |i: usize, default: usize| args.get(i).and_then(|v| v.parse().ok()).unwrap_or(default);
    let (n, d, m, evals) = (arg(1, 1_600), arg(2, 242), arg(3, 100), arg(4, 20));
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let x: DMatrix<f64> = DMatrix::from_fn(n, d, |_, _| rng.random_range(-1.0..1.0));
    let y = DVector::from_fn(n, |i, _| {
        (2.0 * x[(i, 0)]).sin() + x[(i, 1)] * x[(i, 2)] + 0.1 * rng.random_range(-1.0..1.0)
    });
    let params = GpParams::new(GpKind::Spgp).pseudo_inputs(m);
    let obj = GpObjective::new(&params.check()?, &x, &y)?;
    let theta = obj.start();
    obj.value_and_gradient(&theta)?; // warm up
    let (wall, cpu) = (Instant::now(), cpu_seconds());
    for _ in 0..evals {
        std::hint::black_box(obj.value_and_gradient(&theta)?);
    }
    let per = |s: f64| 1e3 * s / evals as f64;
    println!(
        "objective+gradient N={n} D={d} M={m}: {:.2} ms wall, {:.2} ms CPU per evaluation",
        per(wall.elapsed().as_secs_f64()),
        per(cpu_seconds() - cpu)
    );
    if args.get(5).is_some_and(|a| a == "fit") {
        let (wall, cpu) = (Instant::now(), cpu_seconds());
        let model = params.fit(&x, &y)?;
        let r = model.fit_report();
        println!(
            "fit: {} evals, {} iterations, stop {}, nlml {:.3}, {:.2} s wall, {:.2} s CPU",
            r.evals,
            r.iterations,
            r.stop,
            r.nlml,
            wall.elapsed().as_secs_f64(),
            cpu_seconds() - cpu
        );
    }
    Ok(())
}
