//! Small helpers shared by the subcommands: parsing names given on the command line.

use patchflow_learn::{FeatureKind, GpKind};

/// `patch` or `gabor`.
pub fn parse_feature(text: &str) -> anyhow::Result<FeatureKind> {
    match text {
        "patch" => Ok(FeatureKind::Patch),
        "gabor" => Ok(FeatureKind::Gabor),
        other => anyhow::bail!("unknown feature '{other}' (expected patch or gabor)"),
    }
}

/// `full`, `spgp` or `spgp-het`.
pub fn parse_gp(text: &str) -> anyhow::Result<GpKind> {
    Ok(text.parse::<GpKind>()?)
}
