//! Speed of the SPGP objective + gradient at the thesis size (SPEC §8: N = 1,600, M = 100, D = 242,
//! at least 20 × faster than GPy's FITC side by side), its growth in N (must be linear), one full
//! fit, and the exact GP's objective at the occupancy maps' size. The throughput Criterion prints
//! ("elem/s") counts floating-point operations of the dominant products, so it reads as FLOP/s:
//! 2·(2NMD + 5NM²) per evaluation (U = K_MN and (∂𝓛/∂U ∘ U)X; V = L⁻¹U, ṼṼᵀ, B⁻¹Ṽ, L⁻ᵀR and V
//! diag(d) Vᵀ), about 0.31 GFLOP at the thesis size.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::{DMatrix, DVector};
use patchflow_gp::{GpKind, GpObjective, GpParams};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;

/// Patch-like data: D inputs, a smooth target of a few of them plus noise.
fn data(n: usize, d: usize, seed: u64) -> (DMatrix<f64>, DVector<f64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let x: DMatrix<f64> = DMatrix::from_fn(n, d, |_, _| rng.random_range(-1.0..1.0));
    let y = DVector::from_fn(n, |i, _| {
        (2.0 * x[(i, 0)]).sin() + x[(i, 1)] * x[(i, 2)] + 0.1 * rng.random_range(-1.0..1.0)
    });
    (x, y)
}

/// Floating-point operations of the dominant products of one evaluation.
fn flops(n: usize, d: usize, m: usize) -> u64 {
    (2 * (2 * n * m * d + 5 * n * m * m)) as u64
}

fn objective_and_gradient(c: &mut Criterion) {
    let mut group = c.benchmark_group("spgp_objective_gradient_m100_d242");
    group.sample_size(10);
    for n in [1_600, 6_400, 25_600] {
        let (x, y) = data(n, 242, 1);
        for kind in [GpKind::Spgp, GpKind::SpgpHet] {
            let params = GpParams::new(kind)
                .check()
                .expect("default parameters are valid");
            let obj = GpObjective::new(&params, &x, &y).expect("sets up");
            let theta = obj.start();
            group.throughput(Throughput::Elements(flops(n, 242, 100)));
            group.bench_function(format!("{kind}/n{n}"), |b| {
                b.iter(|| {
                    black_box(
                        obj.value_and_gradient(black_box(&theta))
                            .expect("evaluates"),
                    )
                })
            });
        }
    }
    group.finish();
}

fn full_fit(c: &mut Criterion) {
    let (x, y) = data(1_600, 242, 2);
    let mut group = c.benchmark_group("spgp_fit_n1600_m100_d242");
    group.sample_size(10);
    group.bench_function("fit_200_iters", |b| {
        b.iter(|| {
            let model = GpParams::new(GpKind::Spgp).fit(&x, &y).expect("fits");
            let r = model.fit_report();
            eprintln!(
                "fit: {} evals, {} iterations, {:.2} s, nlml {:.3}, stop {}",
                r.evals, r.iterations, r.seconds, r.nlml, r.stop
            );
            black_box(model)
        })
    });
    group.finish();
}

/// The exact GP's objective + gradient at the size of a T-junction occupancy map (N = 1,055 points
/// in the plane) and of a moving-classifier draw (N = 800, D = 10): its Cholesky, L⁻¹ and C⁻¹
/// (about N³ floating-point operations, the throughput counted) are the cost of both.
fn exact_objective(c: &mut Criterion) {
    let mut group = c.benchmark_group("exact_objective_gradient");
    group.sample_size(20);
    for (n, d) in [(1_055, 2), (800, 10)] {
        let (x, y) = data(n, d.max(3), 3);
        let x = x.columns(0, d).into_owned();
        let params = GpParams::new(GpKind::Full)
            .check()
            .expect("default parameters are valid");
        let obj = GpObjective::new(&params, &x, &y).expect("sets up");
        let theta = obj.start();
        group.throughput(Throughput::Elements((n * n * n) as u64));
        group.bench_function(format!("n{n}_d{d}"), |b| {
            b.iter(|| {
                black_box(
                    obj.value_and_gradient(black_box(&theta))
                        .expect("evaluates"),
                )
            })
        });
    }
    group.finish();
}

criterion_group!(benches, objective_and_gradient, full_fit, exact_objective);
criterion_main!(benches);
