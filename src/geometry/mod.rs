//! Geometry swept along the yarn centrelines: fluffy triangle bundles ([Zhong 2001], section 2.5).

mod bundle;
mod frames;
pub mod plies;
mod subset;

pub use bundle::{
    build_bundle, bundle_counts, bundle_profile, piece_streams, stitch_seed, sweep_bundle,
    BundleCounts, BundleProfile, BundleSettings, EndTangents, FullDensityDraws, PieceBuffers,
    TopologyBuffers,
};
pub use frames::{frame_from_tangent, ring_frame};
pub use subset::{MeshSubset, SubsetBuffers};
