//! The hyperparameters of a GP and the optimiser's parameter vector (gp.md §5.2): the kernel's θ
//! (for SE-ARD: log ℓ, log s), log(σ² − floor), raw pseudo-inputs Z (unless held fixed) and, for
//! SPGP-HET, logit(h / h_max).
//!
//! h is bounded by h_max = 10 × the (standardised, hence unit) target variance, gp.md §5.5 item 6:
//! an unbounded h_m silently deletes its pseudo-input and all-large h is the trivial all-noise fit.
//! For h ≪ h_max the logit coordinate is log h.

use nalgebra::{DMatrix, DVector};

use super::kernel::Kernel;

/// Largest magnitude of a log-parameter; keeps exp() finite when the optimiser strays.
const LOG_LIMIT: f64 = 40.0;

/// Upper bound of each pseudo-input noise h_m, in units of the standardised target variance.
pub(crate) const PSEUDO_NOISE_MAX: f64 = 10.0;

/// Kernel, noise and pseudo-input parameters in the (standardised) space of a fit.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Hyper<K> {
    /// The kernel with its hyperparameters.
    pub kernel: K,
    /// Observation noise variance σ².
    pub noise_variance: f64,
    /// Pseudo-inputs Z, one row each (M×D); empty for the full GP.
    pub pseudo_inputs: DMatrix<f64>,
    /// Per-pseudo-input noise h (SPGP-HET, thesis eq. 3.34); `None` for FITC.
    pub pseudo_noise: Option<DVector<f64>>,
}

/// Gradient of the NLML in the natural coordinates of each group.
#[derive(Debug, Clone)]
pub(crate) struct HyperGrad {
    /// ∂𝓛/∂θ of the kernel.
    pub kernel: DVector<f64>,
    /// ∂𝓛/∂log σ².
    pub log_noise_variance: f64,
    /// ∂𝓛/∂Z (M×D).
    pub pseudo_inputs: DMatrix<f64>,
    /// ∂𝓛/∂log h (SPGP-HET).
    pub log_pseudo_noise: Option<DVector<f64>>,
}

/// How a [`Hyper`] maps to a flat vector: [kernel θ, log(σ² − floor), Z (column-major, unless
/// held fixed), logit(h/h_max)].
#[derive(Debug, Clone)]
pub(crate) struct Layout<K> {
    /// The kernel whose θ leads the vector (its values are replaced on unpacking).
    pub kernel: K,
    /// Input dimension D.
    pub dims: usize,
    /// Number of pseudo-inputs M (0 for the full GP).
    pub pseudo: usize,
    /// Whether log h is part of the vector.
    pub het: bool,
    /// Lower bound on σ² (gp.md §1, numerical guard 2).
    pub noise_floor: f64,
    /// Pseudo-inputs held fixed (not in the vector), or `None` when they are optimised.
    pub fixed_pseudo_inputs: Option<DMatrix<f64>>,
}

impl<K: Kernel> Layout<K> {
    /// Number of kernel hyperparameters (the offset of log σ²).
    pub fn kernel_len(&self) -> usize {
        self.kernel.n_params()
    }

    /// Length of the flat vector.
    pub fn len(&self) -> usize {
        self.kernel_len() + 1 + self.free_pseudo_len() + if self.het { self.pseudo } else { 0 }
    }

    /// Number of pseudo-input coordinates in the vector (M·D, or 0 when they are held fixed).
    fn free_pseudo_len(&self) -> usize {
        if self.fixed_pseudo_inputs.is_some() {
            0
        } else {
            self.pseudo * self.dims
        }
    }

    /// The flat vector of `h`.
    pub fn pack(&self, h: &Hyper<K>) -> DVector<f64> {
        let mut v = Vec::with_capacity(self.len());
        v.extend(h.kernel.params());
        v.push((h.noise_variance - self.noise_floor).max(1e-300).ln());
        if self.fixed_pseudo_inputs.is_none() {
            v.extend(h.pseudo_inputs.iter().copied());
        }
        if let Some(p) = &h.pseudo_noise {
            let top = PSEUDO_NOISE_MAX * (1.0 - 1e-12);
            v.extend(p.iter().map(|x| {
                let h = x.clamp(1e-300, top);
                h.ln() - (PSEUDO_NOISE_MAX - h).ln()
            }));
        }
        DVector::from_vec(v)
    }

    /// The hyperparameters of a flat vector.
    pub fn unpack(&self, v: &DVector<f64>) -> Hyper<K> {
        let (d, m, nk) = (self.dims, self.pseudo, self.kernel_len());
        let mut kernel = self.kernel.clone();
        kernel.set_params(&v.as_slice()[..nk]);
        let z0 = nk + 1;
        let pseudo_inputs = match &self.fixed_pseudo_inputs {
            Some(z) => z.clone(),
            None => DMatrix::from_column_slice(m, d, &v.as_slice()[z0..z0 + m * d]),
        };
        let h0 = z0 + self.free_pseudo_len();
        let sigmoid = |x: f64| 1.0 / (1.0 + (-x.clamp(-LOG_LIMIT, LOG_LIMIT)).exp());
        let pseudo_noise = self.het.then(|| {
            DVector::from_iterator(
                m,
                v.rows(h0, m).iter().map(|x| PSEUDO_NOISE_MAX * sigmoid(*x)),
            )
        });
        Hyper {
            kernel,
            noise_variance: self.noise_floor + v[nk].clamp(-LOG_LIMIT, LOG_LIMIT).exp(),
            pseudo_inputs,
            pseudo_noise,
        }
    }

    /// The flat gradient for the point `h`, chaining ∂/∂log σ² through the floor.
    pub fn pack_grad(&self, h: &Hyper<K>, g: &HyperGrad) -> DVector<f64> {
        let mut v = Vec::with_capacity(self.len());
        v.extend(g.kernel.iter().copied());
        // σ² = floor + e^θ, so ∂/∂θ = ∂/∂log σ² · (σ² − floor)/σ².
        v.push(g.log_noise_variance * (h.noise_variance - self.noise_floor) / h.noise_variance);
        if self.fixed_pseudo_inputs.is_none() {
            v.extend(g.pseudo_inputs.iter().copied());
        }
        if self.het {
            if let (Some(p), Some(hv)) = (&g.log_pseudo_noise, &h.pseudo_noise) {
                // h = h_max·sigmoid(θ): ∂/∂θ = ∂/∂log h · (1 − h/h_max).
                v.extend(
                    p.iter()
                        .zip(hv.iter())
                        .map(|(gi, hi)| gi * (1.0 - hi / PSEUDO_NOISE_MAX)),
                );
            } else {
                v.extend(std::iter::repeat_n(0.0, self.pseudo));
            }
        }
        DVector::from_vec(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Stationary;

    #[test]
    fn packing_and_unpacking_round_trips() {
        let kernel = Stationary::se(&[0.5, 2.0], 1.3);
        let layout = Layout {
            kernel: kernel.clone(),
            dims: 2,
            pseudo: 3,
            het: true,
            noise_floor: 1e-6,
            fixed_pseudo_inputs: None,
        };
        let h = Hyper {
            kernel,
            noise_variance: 0.02,
            pseudo_inputs: DMatrix::from_fn(3, 2, |i, j| i as f64 - j as f64 * 0.5),
            pseudo_noise: Some(DVector::from_vec(vec![0.1, 0.2, 0.3])),
        };
        let back = layout.unpack(&layout.pack(&h));
        assert_eq!(layout.pack(&h).len(), layout.len());
        assert!((back.noise_variance - 0.02).abs() < 1e-15);
        assert!((back.kernel.lengthscales() - h.kernel.lengthscales()).amax() < 1e-14);
        assert_eq!(back.pseudo_inputs, h.pseudo_inputs);
        let pn = back.pseudo_noise.expect("het layout keeps h");
        assert!((pn - DVector::from_vec(vec![0.1, 0.2, 0.3])).amax() < 1e-15);
    }
}
