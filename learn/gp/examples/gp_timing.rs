//! Times the SPGP objective + gradient at the thesis size (N = 1,600, M = 100, D = 242) and,
//! optionally, one full fit. Prints per-evaluation wall time (min and median over rounds), process
//! CPU time, and the achieved GFLOP/s of the dominant products, then one JSON line. The machine
//! may be shared: the minimum is the figure least disturbed by other processes.
//!
//! `cargo run --release -p patchflow-gp --example gp_timing -- [N] [D] [M] [ROUNDS] [EVALS] [fit]`

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

/// Multiply-adds ×2 of the O(NMD) and O(NM²) products of one evaluation (gp.md §4): U = K_MN and
/// (∂𝓛/∂U ∘ U)X (NMD each), V = L⁻¹U, ṼṼᵀ, B⁻¹Ṽ, L⁻ᵀR and V diag(d) Vᵀ (NM² each).
fn flops(n: usize, d: usize, m: usize) -> f64 {
    let (n, d, m) = (n as f64, d as f64, m as f64);
    2.0 * (2.0 * n * m * d + 5.0 * n * m * m)
}

fn main() -> Result<(), patchflow_gp::GpError> {
    let args: Vec<String> = std::env::args().collect();
    let arg =
        |i: usize, default: usize| args.get(i).and_then(|v| v.parse().ok()).unwrap_or(default);
    let (n, d, m) = (arg(1, 1_600), arg(2, 242), arg(3, 100));
    let (rounds, evals) = (arg(4, 20), arg(5, 5).max(1));
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let x: DMatrix<f64> = DMatrix::from_fn(n, d, |_, _| rng.random_range(-1.0..1.0));
    let y = DVector::from_fn(n, |i, _| {
        (2.0 * x[(i, 0)]).sin() + x[(i, 1)] * x[(i, 2)] + 0.1 * rng.random_range(-1.0..1.0)
    });
    let params = GpParams::new(GpKind::Spgp).pseudo_inputs(m);
    let obj = GpObjective::new(&params.check()?, &x, &y)?;
    let mut theta = obj.start();
    obj.value_and_gradient(&theta)?; // warm up
    let cpu0 = cpu_seconds();
    let mut per_eval = Vec::with_capacity(rounds);
    for _ in 0..rounds {
        let clock = Instant::now();
        for _ in 0..evals {
            theta[0] += 1e-9; // a new point each time
            std::hint::black_box(obj.value_and_gradient(&theta)?);
        }
        per_eval.push(1e3 * clock.elapsed().as_secs_f64() / evals as f64);
    }
    let cpu_ms = 1e3 * (cpu_seconds() - cpu0) / (rounds * evals) as f64;
    per_eval.sort_by(f64::total_cmp);
    let (min, median) = (per_eval[0], per_eval[per_eval.len() / 2]);
    let gflops = flops(n, d, m) / (min * 1e-3) / 1e9;
    println!(
        "objective+gradient N={n} D={d} M={m} on {} threads: min {min:.2} ms, median \
         {median:.2} ms wall, {cpu_ms:.2} ms CPU per evaluation; {gflops:.1} GFLOP/s at the min",
        rayon::current_num_threads()
    );
    let summary = serde_json::json!({
        "n": n, "d": d, "m": m, "threads": rayon::current_num_threads(),
        "ms_min": min, "ms_median": median, "cpu_ms": cpu_ms, "gflops_at_min": gflops,
    });
    println!("{summary}");
    if args.get(6).is_some_and(|a| a == "fit") {
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
