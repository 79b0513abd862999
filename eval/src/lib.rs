//! patchflow's evaluation: ICP and constant-velocity Kalman baselines (thesis 3.2), metrics, the
//! five-situation benchmark (thesis 4.4), cross-validation tables (thesis 4.3), reports and plots.
