//! # knitwear
//!
//! Knitwear on free-form surfaces, after Zhong, Xu, Guo and Shum, *Realistic and Efficient
//! Rendering of Free-form Knitwear* (MSR-TR-2000-33). Data flows one way; each module uses
//! only the ones above it in this list:
//!
//! | stage | module | what it holds |
//! |---|---|---|
//! | surface | [`surface`] | positions and normals over a (u,v) domain (NURBS grid or UV mesh) |
//! | pattern | [`pattern`] | stitch chart (knit/purl) and colour pattern |
//! | lattice | [`lattice`] | tile corners in (u,v), one tile per stitch |
//! | skeleton | [`skeleton`] | key points, normal offsets, cardinal-spline yarn centrelines |
//! | geometry | [`geometry`] | fluffy triangle bundles swept along the centrelines |
//! | pile | [`pile`] | warp-knit plush: fractal-noise pile directions, view-dependent slices |
//! | measure | [`metrics`] | clearance between yarns |
//! | detail | [`detail`] | camera-driven level of detail and culling: what each stitch needs |
//! | pipeline | [`knit`] | the whole path, budget checks, NumPy-ready buffers |
//! | texture | [`texture`] | the knit drawn in (u,v) as an image: the cheap distant stand-in |
//!
//! The Python bindings live in `src/python/`, behind the `python` cargo feature.

pub mod budget;
pub mod detail;
pub mod error;
pub mod gauge;
pub mod geometry;
pub mod knit;
pub mod lattice;
pub mod metrics;
pub mod output_buffer;
pub mod parallel;
pub mod pattern;
pub mod pile;
pub mod portable_math;
pub mod skeleton;
pub mod surface;
pub mod texture;
pub mod tight_stitches;
pub mod visibility;

#[cfg(feature = "python")]
mod python;

pub use error::{KnitError, Result};
