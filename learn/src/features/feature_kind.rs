//! Which feature vector the GPs read (thesis 2.2.2 and 2.2.3): the map patch's values or the
//! Gabor responses of its difference half.

use crate::features::gabor::GaborBank;
use crate::features::patch::Patch;

/// Which feature vector a point gets (thesis 2.2.2 and 2.2.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FeatureKind {
    /// The 242 patch values (difference map, then reflection map).
    Patch,
    /// The 16 Gabor responses of the difference half of the patch.
    Gabor,
}

impl FeatureKind {
    /// Column names of this feature, in value order.
    pub fn names(self) -> Vec<String> {
        match self {
            Self::Patch => Patch::feature_names(),
            Self::Gabor => GaborBank::feature_names(),
        }
    }
}
