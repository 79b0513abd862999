//! The SPGP (FITC) and SPGP-HET negative log marginal likelihood (thesis eq. 3.30 with 3.27-3.28;
//! SPGP-HET replaces K_M by K_M + diag(h), eq. 3.34) in the stable O(NM²) form of gp.md §1, and its
//! analytic gradient by the adjoint method of gp.md §2.2-2.3. FITC is the case h = 0.
//!
//! Both passes run over fixed blocks of training rows in parallel and are reduced in block order,
//! so results are bit-identical whatever the number of threads.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use super::direct_gemm::{Lhs, Rhs, Structure, product, product_then, symmetric_product};
use super::heap_warmup::keep_freed_memory_mapped;
use super::hyper::{Hyper, HyperGrad};
use super::kernel::{Kernel, OwnedPoints, Points, self_covariance};
use super::linalg::{cholesky_with_jitter, dot, log_diag_sum, lower_inverse, transpose};
use super::simd::vectorised;
use super::train_data::TrainData;
use crate::Result;

/// Pass 1 of one row block: U_b = K_MB, Ṽ_b = L⁻¹U_bΓ_b^{-1/2}, g_b and the block's share of B and
/// Ṽỹ.
pub(crate) struct Pass1 {
    /// U_b = K_MB.
    pub k: DMatrix<f64>,
    /// Ṽ_b = V_bΓ_b^{-1/2} with V_b = L⁻¹U_b.
    pub vt: DMatrix<f64>,
    /// g_b = λ_b + σ², the diagonal of Γ.
    pub g: DVector<f64>,
    vvt: DMatrix<f64>,
    vy: DVector<f64>,
    yy: f64,
    log_g: f64,
}

/// The factorisation shared by the objective, its gradient and the predictive posterior.
pub(crate) struct Factors {
    /// The pseudo-inputs as kernel points.
    pub z: OwnedPoints,
    /// K_M without jitter or h.
    pub k_m: DMatrix<f64>,
    /// L⁻¹ with L = chol(K_M + diag(h) + εI).
    pub l_inv: DMatrix<f64>,
    /// L⁻ᵀ, stored so the products with it read contiguous memory.
    pub l_inv_t: DMatrix<f64>,
    /// B⁻¹ with B = I + ṼṼᵀ.
    pub b_inv: DMatrix<f64>,
    /// u = L_B⁻ᵀ c (gp.md §2.2).
    pub u: DVector<f64>,
    /// The jitter ε that made chol(B_u) succeed.
    pub jitter: f64,
    /// The NLML 𝓛 (gp.md §1 step 8).
    pub nlml: f64,
    /// Pass 1 of each row block, in block order.
    pub blocks: Vec<Pass1>,
}

/// The NLML, its gradient and ∂𝓛/∂ε = tr(∂𝓛/∂B_u).
pub(crate) struct Evaluation {
    /// 𝓛.
    pub nlml: f64,
    /// Gradient in log-coordinates (raw Z).
    pub grad: HyperGrad,
    /// ∂𝓛/∂ε, for a jitter proportional to s.
    pub d_jitter: f64,
}

/// U_b = k(Z, X_b) and diag K_bb of one row block: the O(NMD) part of pass 1, which needs only
/// the pseudo-inputs and so runs while K_M is factored.
fn covariances<K: Kernel>(
    data: &TrainData,
    z: Points<'_>,
    h: &Hyper<K>,
    (start, len): (usize, usize),
) -> (DMatrix<f64>, DVector<f64>) {
    let x = data.points().range(start, len);
    (h.kernel.cross(z, x), h.kernel.diag(x))
}

fn pass1<K: Kernel>(
    data: &TrainData,
    l_inv: &DMatrix<f64>,
    h: &Hyper<K>,
    (start, len): (usize, usize),
    (k, k_diag): (DMatrix<f64>, DVector<f64>),
) -> Pass1 {
    let m = l_inv.nrows();
    let y = data.y.rows(start, len);
    let mut g = DVector::zeros(len);
    let mut vy = DVector::zeros(m);
    let (mut yy, mut log_g) = (0.0, 0.0);
    // Step 3, V = L⁻¹U, with steps 4-5 and the block's share of Ṽỹ in one sweep over each group
    // of V's columns as the product finishes it.
    let vt = product_then(
        Lhs::of(l_inv),
        Structure::Lower,
        Rhs::of(&k),
        #[inline(always)]
        |j0, columns| {
            for (col, n) in columns.chunks_exact_mut(m).zip(j0..) {
                // step 4: λ = diag K_NN − q clamped at 0, q = ‖V_{:,n}‖²
                let g_n = (k_diag[n] - dot(col, col)).max(0.0)
                    + data.noise_at(start + n, h.noise_variance);
                let g_isqrt = 1.0 / g_n.sqrt();
                let yt = y[n] * g_isqrt; // ỹ = Γ^{-1/2}y
                for (v, acc) in col.iter_mut().zip(vy.as_mut_slice()) {
                    *v *= g_isqrt; // step 5: Ṽ = VΓ^{-1/2}
                    *acc += *v * yt;
                }
                g[n] = g_n;
                yy += yt * yt;
                log_g += g_n.ln();
            }
        },
    );
    let vvt = symmetric_product(Lhs::of(&vt), Structure::General, Rhs::transpose_of(&vt));
    Pass1 {
        yy,
        log_g,
        k,
        vt,
        g,
        vvt,
        vy,
    }
}

/// K_M, L⁻¹ with L = chol(K_M + diag(h) + εI), and the jitter used (steps 1-2).
fn pseudo_factor<K: Kernel>(
    h: &Hyper<K>,
    z: Points<'_>,
    jitter: f64,
) -> Result<(DMatrix<f64>, DMatrix<f64>, f64)> {
    let k_m = self_covariance(&h.kernel, z); // step 1
    let mut b_u = k_m.clone();
    if let Some(p) = &h.pseudo_noise {
        for (i, hi) in p.iter().enumerate() {
            b_u[(i, i)] += hi;
        }
    }
    let chol = cholesky_with_jitter(&b_u, jitter, "pseudo-input covariance K_M + diag(h)")?; // step 2
    let l_inv = lower_inverse(&chol.l, "chol(K_M + diag(h))")?;
    Ok((k_m, l_inv, chol.jitter))
}

/// Factors the model at `h` (gp.md §1 steps 1-8).
pub(crate) fn factor<K: Kernel>(data: &TrainData, h: &Hyper<K>, jitter: f64) -> Result<Factors> {
    let z = OwnedPoints::of_rows_kept(&h.pseudo_inputs, &h.kernel);
    let m = h.pseudo_inputs.nrows();
    let blocks = data.blocks();
    let (pseudo, covs) = rayon::join(
        || pseudo_factor(h, z.points(), jitter),
        || {
            blocks
                .par_iter()
                .map(|&blk| covariances(data, z.points(), h, blk))
                .collect::<Vec<_>>()
        },
    );
    let (k_m, l_inv, used_jitter) = pseudo?;
    let blocks: Vec<Pass1> = blocks
        .par_iter()
        .zip(covs.into_par_iter())
        .map(|(&blk, cov)| pass1(data, &l_inv, h, blk, cov))
        .collect();
    let (mut b, mut vy, mut yy, mut log_g) = (DMatrix::identity(m, m), DVector::zeros(m), 0.0, 0.0);
    for p in &blocks {
        b += &p.vvt; // step 6: B = I + ṼṼᵀ
        vy += &p.vy;
        yy += p.yy;
        log_g += p.log_g;
    }
    let lb = cholesky_with_jitter(&((&b + b.transpose()) * 0.5), 0.0, "I + ṼṼᵀ")?.l;
    let lb_inv = lower_inverse(&lb, "chol(I + ṼṼᵀ)")?;
    let c = &lb_inv * &vy; // step 7
    let n = data.len() as f64;
    let nlml = log_diag_sum(&lb)
        + 0.5 * log_g
        + 0.5 * (yy - c.dot(&c))
        + 0.5 * n * (2.0 * std::f64::consts::PI).ln(); // step 8
    let u = lb_inv.tr_mul(&c);
    let lb_inv_t = transpose(&lb_inv);
    // B⁻¹ = L_B⁻ᵀL_B⁻¹
    let b_inv = symmetric_product(
        Lhs::of(&lb_inv_t),
        Structure::Upper,
        Rhs::transpose_of(&lb_inv_t),
    );
    Ok(Factors {
        z,
        k_m,
        l_inv_t: transpose(&l_inv),
        l_inv,
        b_inv,
        u,
        jitter: used_jitter,
        nlml,
        blocks,
    })
}

/// Pass 2 of one row block: ∂𝓛/∂U_b, the block's share of V diag(d) Vᵀ, the gradient through
/// diag K_NN (∂𝓛/∂k_n = d_n, gp.md §2.1) and Σd.
struct Pass2 {
    d_u: DMatrix<f64>,
    vdvt: DMatrix<f64>,
    diag_grad: DVector<f64>,
    sum_d: f64,
}

fn pass2<K: Kernel>(
    data: &TrainData,
    h: &Hyper<K>,
    f: &Factors,
    p: &Pass1,
    (start, len): (usize, usize),
) -> Pass2 {
    let m = f.u.len();
    let u = f.u.as_slice();
    let y = data.y.rows(start, len);
    let mut d = DVector::zeros(len);
    let vt = p.vt.as_slice();
    // B⁻¹Ṽ, swept as the product finishes each group of its columns: α = C⁻¹y, d = diag(G) and,
    // in place of B⁻¹Ṽ, R = L_B⁻ᵀW1Γ^{-1/2} − uαᵀ − 2V diag(d), with V = ṼΓ^{1/2}.
    let mut r_mat = product_then(
        Lhs::of(&f.b_inv),
        Structure::General,
        Rhs::of(&p.vt),
        #[inline(always)]
        |j0, columns| {
            for (col, n) in columns.chunks_exact_mut(m).zip(j0..) {
                let vt_col = &vt[n * m..(n + 1) * m];
                let g_n = p.g[n];
                let g_sqrt = g_n.sqrt();
                let w1_sq = dot(vt_col, col); // ‖W1_{:,n}‖²
                let a = (y[n] - g_sqrt * dot(vt_col, u)) / g_n; // Ṽᵀu = Γ^{-1/2}Vᵀu
                let d_n = 0.5 * ((1.0 - w1_sq) / g_n - a * a);
                d[n] = d_n;
                let (gi, v2d) = (1.0 / g_sqrt, 2.0 * g_sqrt * d_n);
                for ((x, u), v) in col.iter_mut().zip(u).zip(vt_col) {
                    *x = *x * gi - u * a - v * v2d;
                }
            }
        },
    );
    let d_u = product(Lhs::of(&f.l_inv_t), Structure::Upper, Rhs::of(&r_mat)); // ∂𝓛/∂U = L⁻ᵀR
    // V diag(d) Vᵀ = Ṽ diag(g∘d) Ṽᵀ, reusing R's storage for Ṽ diag(g∘d).
    vectorised(
        #[inline(always)]
        || {
            for (n, (col, vt_col)) in r_mat
                .as_mut_slice()
                .chunks_exact_mut(m)
                .zip(p.vt.as_slice().chunks_exact(m))
                .enumerate()
            {
                let gd = p.g[n] * d[n];
                for (x, v) in col.iter_mut().zip(vt_col) {
                    *x = v * gd;
                }
            }
        },
    );
    Pass2 {
        d_u,
        vdvt: symmetric_product(
            Lhs::of(&r_mat),
            Structure::General,
            Rhs::transpose_of(&p.vt),
        ),
        diag_grad: h.kernel.diag_gradient(data.points().range(start, len), &d),
        // ∂𝓛/∂σ² = Σ d_n w_n with per-sample noise σ²·w_n.
        sum_d: match &data.noise_weights {
            None => d.sum(),
            Some(w) => d.dot(&w.rows(start, len)),
        },
    }
}

/// ∂𝓛/∂B_u = L⁻ᵀSL⁻¹ (gp.md §2.2) and the kernel and Z gradients through K_M = k(Z, Z), in
/// which Z enters both arguments (so its gradient is twice the first-argument one).
fn pseudo_gradient<K: Kernel>(
    h: &Hyper<K>,
    f: &Factors,
    parts: &[Pass2],
) -> (DMatrix<f64>, DVector<f64>, DMatrix<f64>) {
    let z = f.z.points();
    let m = z.len();
    let mut s_mat = (&f.b_inv - DMatrix::identity(m, m)) * 0.5 + &f.u * f.u.transpose() * 0.5;
    for p in parts {
        s_mat += &p.vdvt;
    }
    // L⁻ᵀSL⁻¹ = L⁻ᵀ(L⁻ᵀS)ᵀ for symmetric S: two products with a triangular factor.
    let l_inv_t = Lhs::of(&f.l_inv_t);
    let half = product(l_inv_t, Structure::Upper, Rhs::of(&s_mat));
    let d_bu = product(l_inv_t, Structure::Upper, Rhs::transpose_of(&half));
    let d_bu = (&d_bu + d_bu.transpose()) * 0.5;
    let mut d_z = DMatrix::zeros(m, z.dims());
    let grad = h.kernel.cross_gradient(z, z, &f.k_m, &d_bu, Some(&mut d_z));
    (d_bu, grad, d_z * 2.0)
}

/// 𝓛 and its full gradient at `h` (gp.md §2.2-2.3, cost O(NM² + NMD + M³ + M²D)).
pub(crate) fn objective<K: Kernel>(
    data: &TrainData,
    h: &Hyper<K>,
    jitter: f64,
) -> Result<Evaluation> {
    keep_freed_memory_mapped();
    // The whole evaluation runs on a worker of the pool: its parallel passes then split among the
    // workers directly, instead of each being sent in from outside while the caller sleeps.
    rayon::scope(|_| objective_on_worker(data, h, jitter))
}

fn objective_on_worker<K: Kernel>(
    data: &TrainData,
    h: &Hyper<K>,
    jitter: f64,
) -> Result<Evaluation> {
    let f = factor(data, h, jitter)?;
    let blocks = data.blocks();
    let parts: Vec<Pass2> = blocks
        .par_iter()
        .zip(f.blocks.par_iter())
        .map(|(&blk, p)| pass2(data, h, &f, p, blk))
        .collect();
    let z = f.z.points();
    // The O(NMD) gradient through U = k(Z, X) needs only ∂𝓛/∂U: it runs beside ∂𝓛/∂B_u.
    let ((d_bu, mut kernel, mut d_z), through_u) = rayon::join(
        || pseudo_gradient(h, &f, &parts),
        || {
            blocks
                .par_iter()
                .zip(parts.par_iter().zip(f.blocks.par_iter()))
                .map(|(&(start, len), (p2, p1))| {
                    let x = data.points().range(start, len);
                    let mut d_z = DMatrix::zeros(z.len(), z.dims());
                    let g = h
                        .kernel
                        .cross_gradient(z, x, &p1.k, &p2.d_u, Some(&mut d_z));
                    (g, d_z)
                })
                .collect::<Vec<_>>()
        },
    );
    let mut sum_d = 0.0;
    for (p, (g, dz)) in parts.iter().zip(&through_u) {
        kernel += g + &p.diag_grad;
        d_z += dz;
        sum_d += p.sum_d;
    }
    let grad = HyperGrad {
        kernel,
        log_noise_variance: h.noise_variance * sum_d,
        pseudo_inputs: d_z,
        log_pseudo_noise: h
            .pseudo_noise
            .as_ref()
            .map(|p| p.component_mul(&d_bu.diagonal())),
    };
    Ok(Evaluation {
        nlml: f.nlml,
        grad,
        d_jitter: d_bu.trace(),
    })
}

#[cfg(test)]
#[path = "fitc_tests.rs"]
mod tests;
