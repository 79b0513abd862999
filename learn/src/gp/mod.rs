//! Gaussian-process regression: full GP, SPGP (FITC) and SPGP-HET (thesis 3.1.3).
