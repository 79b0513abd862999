//! Motion features from consecutive sweeps (thesis Chapter 2): the height slice, reflection and
//! difference maps, single-link clusters, map patches and Gabor responses, and the importance
//! sampled training samples of thesis 3.1.1-3.1.2.

mod beam_counts;
mod cluster;
mod csv;
mod difference_map;
mod gabor;
mod grid;
mod line;
mod mirror;
mod params;
mod patch;
mod reflection_map;
mod render;
mod sampler;
mod samples;
mod sampling;
mod slice;
mod spread_kernel;
mod sweep_features;
pub mod synthetic;
mod top_n;

pub use cluster::Clusters;
pub use csv::{Alignment, META_COLUMNS};
pub use difference_map::MapPair;
pub use gabor::{GABOR_FILTERS, GaborBank, bank_energy};
pub use grid::{GridMap, GridWindow};
pub use params::{FeatureParams, GaborParams, MAX_MAP_SIDE_CELLS};
pub use patch::{PATCH_CELLS, PATCH_LEN, PATCH_SIDE, Patch};
pub use render::{render_png, write_png};
pub use samples::{Sample, SampleSet};
pub use sampling::importance_sample;
pub use slice::{HeightSlice, SlicedBeam, SlicedPoint};
pub use sweep_features::{FeatureKind, SweepFeatures};
