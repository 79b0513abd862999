//! Motion features from consecutive sweeps (thesis Chapter 2).
