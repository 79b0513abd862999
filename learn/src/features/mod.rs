//! Motion features from consecutive sweeps (thesis Chapter 2): the ground estimate and the height
//! slice above it, reflection and difference maps, single-link clusters, map patches and Gabor responses, and the importance
//! sampled training samples of thesis 3.1.1-3.1.2.

mod beam_counts;
mod buffer_pool;
mod cell_samples;
mod cluster;
mod cluster_shape;
mod counts_view;
mod csv;
mod difference_map;
mod feature_kind;
mod gabor;
mod grid;
mod ground_cells;
mod ground_envelope;
mod ground_fit;
mod ground_grid;
mod ground_pits;
mod ground_slab;
mod importance_sampling;
mod line;
mod mirror;
mod params;
mod patch;
mod range_profile;
mod reflection_map;
mod render;
mod run_sampler;
mod sample_set;
mod scan_stream;
mod side_balance;
mod slice;
mod sliced_beam;
mod spread_kernel;
mod sweep_features;
mod synthetic_canopy;
mod synthetic_ground;
mod synthetic_scene;
mod synthetic_world;
mod top_n;
mod traced_counts;
mod training_sample;
mod unobserved_before;
mod valid_params;

pub(crate) use cell_samples::CellSamples;
pub use cluster::Clusters;
pub use cluster_shape::{ClusterShape, MIN_OBJECT_POINTS};
pub use csv::Alignment;
pub(crate) use difference_map::MapPair;
pub use feature_kind::FeatureKind;
pub use gabor::GaborBank;
pub use grid::{GridMap, GridWindow};
pub use ground_grid::GroundGrid;
pub use importance_sampling::importance_sample;
pub use params::{FeatureParams, GaborParams, GroundMode};
pub use patch::{PATCH_LEN, Patch};
pub use range_profile::{ObjectEnd, RangeProfile};
pub use render::write_png;
pub use sample_set::SampleSet;
pub use scan_stream::{FeaturedSweep, ScanStream};
pub use side_balance::SideBalanced;
pub use slice::{HeightSlice, SlicedPoint};
pub use sweep_features::{FeatureTiming, SweepFeatures};
pub use training_sample::TrainingSample;
pub use valid_params::FeatureValidParams;

/// Hand-made sweeps for tests, benchmarks and demos: boxes on flat or uneven ground under tree
/// canopies, scanned by an ideal spinning lidar (no noise, no rolling shutter).
pub mod synthetic {
    pub use super::synthetic_canopy::SyntheticCanopy;
    pub use super::synthetic_ground::{SyntheticGround, SyntheticRoad};
    pub use super::synthetic_scene::{SceneBox, SyntheticLidar, SyntheticScene, rotate_about};
    pub use super::synthetic_world::SyntheticWorld;
}
