//! patchflow's Gaussian processes: regression with a full GP, SPGP (FITC) and SPGP-HET (Hess 2008,
//! thesis 3.1.3), and classification by probabilistic least squares on top of any of them (GPML
//! §6.5, for GP occupancy maps). Depends on no other patchflow crate.
//!
//! Every model takes any [`Kernel`]: SE-ARD by default (the thesis' kernel), Matérn 3/2, or a
//! product over groups of input columns such as space × time ([`Stationary`]), or DGPOM's
//! motion-adapted kernel over (x, y, t) ([`MotionAdapted`], reading a [`MotionField`]); a new
//! covariance function implements [`Kernel`] and works everywhere.
//!
//! ```
//! use nalgebra::{DMatrix, DVector};
//! use patchflow_gp::{GpKind, GpParams};
//!
//! let x = DMatrix::from_fn(40, 1, |i, _| i as f64 / 8.0);
//! let y = x.column(0).map(|v| v.sin());
//! let model = GpParams::new(GpKind::Spgp).pseudo_inputs(8).max_iters(50).fit(&x, &y)?;
//! let p = model.predict(&DMatrix::from_element(1, 1, 2.0))?;
//! assert!((p.mean[0] - 2f64.sin()).abs() < 0.1);
//! # Ok::<(), patchflow_gp::GpError>(())
//! ```

mod ard_distance;
mod ard_gradient;
mod batch_prediction;
mod blocked;
mod direct_gemm;
mod error;
mod exp;
mod fit;
mod fitc;
mod full;
mod gemm;
mod gemm_operands;
mod heap_warmup;
mod hyper;
mod init;
mod joint_prediction;
mod kernel;
mod lbfgs;
mod linalg;
mod log_range;
mod loo;
mod model;
mod model_file;
mod motion_adapted;
mod motion_adapted_kernel;
mod motion_field;
mod nonstationary_matern;
mod normal;
mod objective;
mod params;
mod pls;
mod shape;
mod simd;
mod sparse_posterior;
mod squashing;
mod stationary;
mod tile_kernel;
mod train_data;
mod transform;
mod triangular;

pub use error::{GpError, Result};
pub use full::FULL_GP_MAX_SAMPLES;
pub use joint_prediction::{Predicted, Readout};
pub use kernel::{Kernel, Points};
pub use log_range::LogRange;
pub use loo::LooMoments;
pub use model::{FitReport, GpModel, GpPrediction};
pub use model_file::{GP_MODEL_FORMAT, GP_MODEL_VERSION, GpModelRecord};
pub use motion_adapted::MotionAdapted;
pub use motion_field::{MotionField, transported};
pub use objective::GpObjective;
pub use params::{GpKind, GpParams, GpValidParams};
pub use pls::{PlsClassifier, PlsParams, PlsPrediction, PlsValidParams};
pub use shape::{Factor, Shape};
pub use squashing::Squashing;
pub use stationary::Stationary;
pub use transform::Standardiser;
