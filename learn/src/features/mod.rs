//! Motion features from consecutive sweeps (thesis Chapter 2): the height slice, reflection and
//! difference maps, single-link clusters, map patches and Gabor responses, and the importance
//! sampled training samples of thesis 3.1.1-3.1.2.

mod difference_map;
mod grid;
mod params;
mod reflection_map;
mod slice;
pub mod synthetic;

pub use difference_map::MapPair;
pub use grid::{GridMap, GridWindow};
pub use params::{FeatureParams, GaborParams};
pub use slice::{HeightSlice, SlicedBeam, SlicedPoint};
