//! Feature parameters checked once at the boundary (the linfa and egobox pattern the GP crate
//! follows with `GpParams` → `GpValidParams`): `FeatureParams::check` returns a
//! [`FeatureValidParams`], and every stage that runs per sweep takes that and checks nothing
//! again.

use std::ops::Deref;

use crate::{FeatureParams, Result};

/// [`FeatureParams`] that passed [`FeatureParams::check`]; reads as the parameters it wraps.
///
/// ```
/// use patchflow_learn::FeatureParams;
/// let checked = FeatureParams::default().check().unwrap();
/// assert_eq!(checked.cell_m, 0.10);
/// assert!(FeatureParams::with_prior(1.5).check().is_err());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct FeatureValidParams(FeatureParams);

impl FeatureParams {
    /// Checks the parameters once and returns them as [`FeatureValidParams`].
    pub fn check(&self) -> Result<FeatureValidParams> {
        self.validate()?;
        Ok(FeatureValidParams(self.clone()))
    }
}

impl FeatureValidParams {
    /// The checked parameters.
    pub fn params(&self) -> &FeatureParams {
        &self.0
    }
}

impl Deref for FeatureValidParams {
    type Target = FeatureParams;

    fn deref(&self) -> &FeatureParams {
        &self.0
    }
}
