//! # knitwear
//!
//! Knitwear on free-form surfaces, after Zhong, Xu, Guo and Shum, *Realistic and Efficient
//! Rendering of Free-form Knitwear* (MSR-TR-2000-33). Data flows one way; each module uses
//! only the ones above it in this table:
//!
//! | stage | module | what it holds |
//! |---|---|---|
//! | errors | [`error`] | the typed errors every stage returns |
//! | settings | [`settings`] | every user setting declared once: default, range, unit, doc |
//! | randomness | [`rng`] | the one seed mixer (SplitMix64) every random choice draws from |
//! | arithmetic | [`portable_math`] | the same float bits on every machine |
//! | buffers | [`output_buffer`] | preallocated output buffers handed to NumPy |
//! | threads | [`parallel`] | the private rayon pool and work splitting |
//! | cancellation | [`cancel`] | stopping long work on request (Ctrl-C, Esc) |
//! | budget | [`budget`] | output sizes and the memory budget check |
//! | gauge | [`gauge`] | stitch counts from a knitter's gauge |
//! | surface | [`surface`] | positions and normals over a (u,v) domain (NURBS grid or UV mesh) |
//! | pattern | [`pattern`] | stitch chart (knit/purl), colour chart and colour image |
//! | measure | [`metrics`] | clearance between yarns, optical cover |
//! | lattice | [`lattice`] | tile corners in (u,v), one tile per stitch |
//! | stitch size | [`tight_stitches`] | the tighter stitches' size the loop shapes are tuned for |
//! | skeleton | [`skeleton`] | key points, normal offsets, cardinal-spline yarn centrelines; entered through [`skeleton::YarnSkeleton`] |
//! | geometry | [`geometry`] | fluffy triangle bundles swept along the centrelines |
//! | pile | [`pile`] | warp-knit plush: fractal-noise pile directions, view-dependent slices |
//! | detail | [`detail`] | camera-driven level of detail and culling: what each stitch needs |
//! | visibility | [`visibility`] | which triangles any camera view sees (hidden-yarn culling) |
//! | pipeline | [`knit`] | the whole path, budget checks, NumPy-ready buffers |
//! | texture | [`texture`] | the knit drawn in (u,v) as an image: the cheap distant stand-in |
//!
//! `scripts/check_layers.py` (run by `scripts/test.sh`) holds the code to this table and
//! finds import circles between files.
//!
//! The Python bindings live in `src/python/`, behind the `python` cargo feature.

pub mod budget;
pub mod cancel;
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
pub mod rng;
pub mod settings;
pub mod skeleton;
pub mod surface;
pub mod texture;
pub mod tight_stitches;
pub mod visibility;

#[cfg(feature = "python")]
mod python;

pub use error::{KnitError, Result};
