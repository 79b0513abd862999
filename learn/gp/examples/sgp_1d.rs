//! SPGP vs SPGP-HET on heteroscedastic 1-D toy data in the spirit of thesis Figure 3.5: a sine with
//! small noise on the left half and large noise on the right. Prints the predictive mean and
//! standard deviation (with noise) of both models on a grid, and SPGP-HET's pseudo-input noise h.
//!
//! `cargo run --release -p patchflow-gp --example sgp_1d`

use nalgebra::{DMatrix, DVector};
use patchflow_gp::{GpKind, GpParams};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

fn main() -> Result<(), patchflow_gp::GpError> {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let unit =
        Normal::new(0.0, 1.0).map_err(|e| patchflow_gp::GpError::InvalidParams(e.to_string()))?;
    let x: DMatrix<f64> = DMatrix::from_fn(200, 1, |_, _| rng.random_range(0.0..10.0));
    let noise_sd = |x: f64| if x < 5.0 { 0.05 } else { 0.5 };
    let y = DVector::from_fn(200, |i, _| {
        x[(i, 0)].sin() + noise_sd(x[(i, 0)]) * unit.sample(&mut rng)
    });
    let spgp = GpParams::new(GpKind::Spgp).pseudo_inputs(12).fit(&x, &y)?;
    let het = GpParams::new(GpKind::SpgpHet)
        .pseudo_inputs(12)
        .fit(&x, &y)?;
    let grid = DMatrix::from_fn(21, 1, |i, _| i as f64 * 0.5);
    let (a, b) = (spgp.predict(&grid)?, het.predict(&grid)?);
    println!(
        "{:>5} {:>7} {:>9} {:>9} {:>9} {:>9}",
        "x", "true_sd", "spgp_mu", "spgp_sd", "het_mu", "het_sd"
    );
    for i in 0..grid.nrows() {
        let g = grid[(i, 0)];
        let sd = noise_sd(g);
        println!(
            "{g:5.1} {sd:7.2} {:9.3} {:9.3} {:9.3} {:9.3}",
            a.mean[i],
            a.var_y[i].sqrt(),
            b.mean[i],
            b.var_y[i].sqrt()
        );
    }
    for (name, model) in [("spgp", &spgp), ("spgp-het", &het)] {
        let r = model.fit_report();
        println!(
            "{name}: {} evals, {} iterations, nlml {:.2}, σ² {:.4}",
            r.evals,
            r.iterations,
            r.nlml,
            model.noise_variance()
        );
    }
    if let Some(h) = het.pseudo_noise() {
        for (zi, hi) in het.pseudo_inputs().column(0).iter().zip(h.iter()) {
            println!("pseudo-input (standardised) {zi:7.3}  h {hi:.4}");
        }
    }
    Ok(())
}
