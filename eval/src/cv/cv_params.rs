//! Settings of a cross-validation run (thesis 4.3): folds, samples, GP size, priors, seed.

/// Settings of a cross-validation run; `Default` is the thesis setup with 5 folds.
#[derive(Debug, Clone, PartialEq)]
pub struct CvParams {
    /// Number of folds K.
    pub folds: usize,
    /// Importance-sampled samples per prior (thesis: 1,600).
    pub samples: usize,
    /// Pseudo-inputs per GP (thesis: 100).
    pub pseudo_inputs: usize,
    /// Optimiser iteration limit per GP.
    pub max_iters: usize,
    /// Map priors to compare (thesis: 0.01 and 0.5).
    pub priors: Vec<f64>,
    /// Seed of sampling, folds and GP initialisation.
    pub seed: u64,
    /// Train each fold on its samples and their mirror images, as `EstimatorParams` does.
    pub mirror_images: bool,
}

impl Default for CvParams {
    fn default() -> Self {
        Self {
            folds: 5,
            samples: 1600,
            pseudo_inputs: 100,
            max_iters: 200,
            priors: vec![0.01, 0.5],
            seed: 0,
            mirror_images: true,
        }
    }
}
