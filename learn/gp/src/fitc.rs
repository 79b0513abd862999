//! The SPGP (FITC) and SPGP-HET negative log marginal likelihood (thesis eq. 3.30 with 3.27-3.28;
//! SPGP-HET replaces K_M by K_M + diag(h), eq. 3.34) in the stable O(NM²) form of gp.md §1, and its
//! analytic gradient by the adjoint method of gp.md §2.2-2.3. FITC is the case h = 0.
//!
//! Both passes run over fixed blocks of training rows in parallel and are reduced in block order,
//! so results are bit-identical whatever the number of threads.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use super::hyper::{Hyper, HyperGrad};
use super::kernel::{ScaledPoints, column_sqnorms, cross_covariance, inverse_squares};
use super::kernel::{scale_points, self_covariance};
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

fn pass1(
    data: &TrainData,
    side: &ScaledPoints,
    l_inv: &DMatrix<f64>,
    h: &Hyper,
    inv_sq: &DVector<f64>,
    (start, len): (usize, usize),
) -> Pass1 {
    let s = h.signal_variance;
    let x_sq = column_sqnorms(&data.xt_sq_block(start, len), inv_sq);
    let k = cross_covariance(side, &data.xt_block(start, len), &x_sq, s);
    let v = mul(l_inv, &k); // step 3: V = L⁻¹U
    let q = colsum_product(&v, &v);
    let g = q.map(|qn| (s - qn).max(0.0) + h.noise_variance); // step 4: λ clamped at 0
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
pub(crate) fn factor(data: &TrainData, h: &Hyper, jitter: f64) -> Result<Factors> {
    let inv_sq = inverse_squares(&h.lengthscales);
    let z = &h.pseudo_inputs;
    let m = z.nrows();
    let k_m = self_covariance(z, &inv_sq, h.signal_variance); // step 1
    let mut b_u = k_m.clone();
    if let Some(p) = &h.pseudo_noise {
        for i in 0..m {
            b_u[(i, i)] += p[i];
        }
    }
    let chol = cholesky_with_jitter(&b_u, jitter, "pseudo-input covariance K_M + diag(h)")?; // step 2
    let l_inv = lower_inverse(&chol.l, "chol(K_M + diag(h))")?;
    let side = scale_points(z, &inv_sq);
    let blocks: Vec<Pass1> = data
        .blocks()
        .par_iter()
        .map(|&blk| pass1(data, &side, &l_inv, h, &inv_sq, blk))
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
        k_m,
        l_inv,
        b_inv,
        u,
        jitter: chol.jitter,
        nlml,
        blocks,
    })
}

/// Pass 2 of one row block: the block's shares of V diag(d) Vᵀ, E X, r, Σ c'x², ΣE and Σd.
struct Pass2 {
    vdvt: DMatrix<f64>,
    ex: DMatrix<f64>,
    r: DVector<f64>,
    x_sq_c: DVector<f64>,
    sum_e: f64,
    sum_d: f64,
}

fn pass2(data: &TrainData, f: &Factors, p: &Pass1, (start, len): (usize, usize)) -> Pass2 {
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
    let mut e = mul(&t_view(&f.l_inv), &r_mat); // ∂𝓛/∂U = L⁻ᵀR
    e.component_mul_assign(&p.k); // E = ∂𝓛/∂U ∘ U
    let ex = mul(&e, &data.x_block(start, len));
    let c_prime = DVector::from_iterator(len, e.column_iter().map(|c| c.sum()));
    let mut vd = p.v.clone();
    scale_columns(&mut vd, &d);
    Pass2 {
        vdvt: mul(&vd, &t_view(&p.v)),
        ex,
        r: e.column_sum(),
        x_sq_c: data.xt_sq_block(start, len) * c_prime,
        sum_e: e.sum(),
        sum_d: d.sum(),
    }
}

/// 𝓛 and its full gradient at `h` (gp.md §2.2-2.3, cost O(NM² + NMD + M³ + M²D)).
pub(crate) fn objective(data: &TrainData, h: &Hyper, jitter: f64) -> Result<Evaluation> {
    let f = factor(data, h, jitter)?;
    let parts: Vec<Pass2> = data
        .blocks()
        .par_iter()
        .zip(f.blocks.par_iter())
        .map(|(&blk, p)| pass2(data, &f, p, blk))
        .collect();
    let (m, dims) = (h.pseudo_inputs.nrows(), data.dims());
    let mut s_mat = (&f.b_inv - DMatrix::identity(m, m)) * 0.5 + &f.u * f.u.transpose() * 0.5;
    let (mut ex, mut r, mut x_sq_c) = (
        DMatrix::zeros(m, dims),
        DVector::zeros(m),
        DVector::zeros(dims),
    );
    let (mut sum_e, mut sum_d) = (0.0, 0.0);
    for p in &parts {
        s_mat += &p.vdvt;
        ex += &p.ex;
        r += &p.r;
        x_sq_c += &p.x_sq_c;
        sum_e += p.sum_e;
        sum_d += p.sum_d;
    }
    let d_bu = mul(&mul(&t_view(&f.l_inv), &s_mat), &f.l_inv);
    let d_bu = (&d_bu + d_bu.transpose()) * 0.5; // ∂𝓛/∂B_u = L⁻ᵀSL⁻¹
    let f_mat = d_bu.component_mul(&f.k_m); // F = ∂𝓛/∂B_u ∘ K_M
    let f_row = f_mat.column_sum();
    let z = &h.pseudo_inputs;
    let fz = mul(&f_mat, z);
    let inv_sq = inverse_squares(&h.lengthscales);
    let mut d_z = DMatrix::zeros(m, dims);
    let mut d_log_l = DVector::zeros(dims);
    for d in 0..dims {
        let mut acc = x_sq_c[d];
        for i in 0..m {
            let zi = z[(i, d)];
            acc += r[i] * zi * zi - 2.0 * zi * ex[(i, d)] + 2.0 * f_row[i] * zi * zi
                - 2.0 * zi * fz[(i, d)];
            d_z[(i, d)] = inv_sq[d] * (ex[(i, d)] - r[i] * zi + 2.0 * (fz[(i, d)] - f_row[i] * zi));
        }
        d_log_l[d] = inv_sq[d] * acc;
    }
    let grad = HyperGrad {
        log_lengthscales: d_log_l,
        log_signal_variance: sum_e + f_mat.sum() + h.signal_variance * sum_d,
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
