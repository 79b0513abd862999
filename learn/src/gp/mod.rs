//! Gaussian-process regression: full GP, SPGP (FITC) and SPGP-HET (thesis 3.1.3).

mod fitc;
mod hyper;
mod kernel;
mod linalg;
mod sparse_posterior;
mod train_data;
mod full;
mod lbfgs;
