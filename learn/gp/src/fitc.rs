//! The SPGP (FITC) and SPGP-HET negative log marginal likelihood (thesis eq. 3.30 with 3.27-3.28;
//! SPGP-HET replaces K_M by K_M + diag(h), eq. 3.34) in the stable O(NM²) form of gp.md §1, and its
//! analytic gradient by the adjoint method of gp.md §2.2-2.3. FITC is the case h = 0.
//!
//! Both passes run over fixed blocks of training rows in parallel and are reduced in block order,
//! so results are bit-identical whatever the number of threads.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use super::hyper::{Hyper, HyperGrad};
use super::kernel::{Kernel, OwnedPoints, Points, self_covariance};
use super::linalg::{cholesky_with_jitter, colsum_product, log_diag_sum, lower_inverse};
use super::linalg::{mul, scale_columns, t_view};
use super::train_data::TrainData;
use crate::Result;

/// Pass 1 of one row block: U_b = K_MB, V_b = L⁻¹U_b, g_b and the block's share of B and Ṽỹ.
pub(crate) struct Pass1 {
    /// U_b = K_MB.
    pub k: DMatrix<f64>,
    /// V_b = L⁻¹U_b.
    pub v: DMatrix<f64>,
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

fn pass1<K: Kernel>(
    data: &TrainData,
    z: Points<'_>,
    l_inv: &DMatrix<f64>,
    h: &Hyper<K>,
    (start, len): (usize, usize),
) -> Pass1 {
    let x = data.points().range(start, len);
    let k = h.kernel.cross(z, x);
    let k_diag = h.kernel.diag(x);
    let v = mul(l_inv, &k); // step 3: V = L⁻¹U
    let q = colsum_product(&v, &v);
    // step 4: λ = diag K_NN − q clamped at 0
    let g = DVector::from_fn(len, |n, _| (k_diag[n] - q[n]).max(0.0) + h.noise_variance);
    let g_isqrt = g.map(|x| 1.0 / x.sqrt());
    let mut vt = v.clone();
    scale_columns(&mut vt, &g_isqrt); // step 5: Ṽ = VΓ^{-1/2}
    let yt = data.y.rows(start, len).component_mul(&g_isqrt);
    let vvt = mul(&vt, &t_view(&vt));
    let vy = &vt * &yt;
    Pass1 {
        yy: yt.dot(&yt),
        log_g: g.iter().map(|x| x.ln()).sum(),
        k,
        v,
        g,
        vvt,
        vy,
    }
}

/// Factors the model at `h` (gp.md §1 steps 1-8).
pub(crate) fn factor<K: Kernel>(data: &TrainData, h: &Hyper<K>, jitter: f64) -> Result<Factors> {
    let z = OwnedPoints::of_rows(&h.pseudo_inputs, &h.kernel);
    let m = h.pseudo_inputs.nrows();
    let k_m = self_covariance(&h.kernel, z.points()); // step 1
    let mut b_u = k_m.clone();
    if let Some(p) = &h.pseudo_noise {
        for i in 0..m {
            b_u[(i, i)] += p[i];
        }
    }
    let chol = cholesky_with_jitter(&b_u, jitter, "pseudo-input covariance K_M + diag(h)")?; // step 2
    let l_inv = lower_inverse(&chol.l, "chol(K_M + diag(h))")?;
    let blocks: Vec<Pass1> = data
        .blocks()
        .par_iter()
        .map(|&blk| pass1(data, z.points(), &l_inv, h, blk))
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
    let b_inv = mul(&t_view(&lb_inv), &lb_inv);
    Ok(Factors {
        z,
        k_m,
        l_inv,
        b_inv,
        u,
        jitter: chol.jitter,
        nlml,
        blocks,
    })
}

/// Pass 2 of one row block: the block's shares of V diag(d) Vᵀ, the kernel and Z gradients
/// through ∂𝓛/∂U and ∂𝓛/∂diag K_NN, and Σd.
struct Pass2 {
    vdvt: DMatrix<f64>,
    kernel: DVector<f64>,
    d_z: DMatrix<f64>,
    sum_d: f64,
}

fn pass2<K: Kernel>(
    data: &TrainData,
    h: &Hyper<K>,
    f: &Factors,
    p: &Pass1,
    (start, len): (usize, usize),
) -> Pass2 {
    let g_isqrt = p.g.map(|x| 1.0 / x.sqrt());
    let mut vt = p.v.clone();
    scale_columns(&mut vt, &g_isqrt);
    let mut r_mat = mul(&f.b_inv, &vt); // B⁻¹Ṽ = L_B⁻ᵀW1
    let w1_sq = colsum_product(&vt, &r_mat); // ‖W1_{:,n}‖²
    let vu = p.v.tr_mul(&f.u);
    let y = data.y.rows(start, len);
    let alpha = DVector::from_fn(len, |n, _| (y[n] - vu[n]) / p.g[n]); // α = C⁻¹y
    let d = DVector::from_fn(len, |n, _| {
        0.5 * ((1.0 - w1_sq[n]) / p.g[n] - alpha[n] * alpha[n])
    });
    for (n, mut col) in r_mat.column_iter_mut().enumerate() {
        // R = L_B⁻ᵀW1Γ^{-1/2} − uαᵀ − 2V diag(d)
        for (m, x) in col.iter_mut().enumerate() {
            *x = *x * g_isqrt[n] - f.u[m] * alpha[n] - 2.0 * p.v[(m, n)] * d[n];
        }
    }
    let d_u = mul(&t_view(&f.l_inv), &r_mat); // ∂𝓛/∂U = L⁻ᵀR
    let x = data.points().range(start, len);
    let z = f.z.points();
    let mut d_z = DMatrix::zeros(z.dims(), z.len());
    // ∂𝓛/∂θ through U = k(Z, X_b) and through diag K_NN (∂𝓛/∂k_n = d_n, gp.md §2.1)
    let kernel =
        h.kernel.cross_gradient(z, x, &p.k, &d_u, Some(&mut d_z)) + h.kernel.diag_gradient(x, &d);
    let mut vd = p.v.clone();
    scale_columns(&mut vd, &d);
    Pass2 {
        vdvt: mul(&vd, &t_view(&p.v)),
        kernel,
        d_z,
        sum_d: d.sum(),
    }
}

/// 𝓛 and its full gradient at `h` (gp.md §2.2-2.3, cost O(NM² + NMD + M³ + M²D)).
pub(crate) fn objective<K: Kernel>(
    data: &TrainData,
    h: &Hyper<K>,
    jitter: f64,
) -> Result<Evaluation> {
    let f = factor(data, h, jitter)?;
    let parts: Vec<Pass2> = data
        .blocks()
        .par_iter()
        .zip(f.blocks.par_iter())
        .map(|(&blk, p)| pass2(data, h, &f, p, blk))
        .collect();
    let z = f.z.points();
    let m = z.len();
    let mut s_mat = (&f.b_inv - DMatrix::identity(m, m)) * 0.5 + &f.u * f.u.transpose() * 0.5;
    let mut kernel = DVector::zeros(h.kernel.n_params());
    let mut d_z = DMatrix::zeros(z.dims(), m);
    let mut sum_d = 0.0;
    for p in &parts {
        s_mat += &p.vdvt;
        kernel += &p.kernel;
        d_z += &p.d_z;
        sum_d += p.sum_d;
    }
    let d_bu = mul(&mul(&t_view(&f.l_inv), &s_mat), &f.l_inv);
    let d_bu = (&d_bu + d_bu.transpose()) * 0.5; // ∂𝓛/∂B_u = L⁻ᵀSL⁻¹
    // K_M = k(Z, Z): Z enters both arguments, so its gradient is twice the first-argument one.
    let mut d_z_m = DMatrix::zeros(z.dims(), m);
    kernel += h
        .kernel
        .cross_gradient(z, z, &f.k_m, &d_bu, Some(&mut d_z_m));
    d_z += d_z_m * 2.0;
    let grad = HyperGrad {
        kernel,
        log_noise_variance: h.noise_variance * sum_d,
        pseudo_inputs: d_z.transpose(),
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
