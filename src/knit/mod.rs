//! The whole pipeline: surface -> lattice -> skeleton -> yarn bundles -> flat buffers in the
//! dtypes Blender's `foreach_set` takes (float32 positions and colours, int32 indices).
//!
//! One file per step:
//! - [`params`](self::KnitParams): the settings, their defaults and validation;
//! - `prepare`: [`PreparedKnit::new`] binds a knit to its surface's (u,v) layout once;
//! - `cull`: the yarn no camera view sees, culled ([`PreparedKnit::seen_triangles`]);
//! - `build`: [`PreparedKnit::build`] and the positions of a surface in any pose;
//! - `pose_clearance`: the yarn's clearance in any pose ([`PreparedKnit::clearance`]);
//! - `topology`: the skeleton measured (its (u,v) centrelines, the courses' interlock);
//! - `output`: what comes back ([`KnitOutput`], [`KnitStats`]).

mod build;
mod cull;
mod output;
mod params;
mod pose_clearance;
mod prepare;
mod topology;

pub use output::{measure, KnitOutput, KnitStats, UvYarn};
pub use params::*;
pub use prepare::check_budget;
// What the steps share with each other (each is pub(super) in its own file).
use build::*;

use std::time::Instant;

use crate::budget::OutputSize;
use crate::detail::{Level, Span};
use crate::error::Result;
use crate::geometry::{BundleCounts, BundleSettings, MeshSubset};
use crate::pattern::StitchPattern;
use crate::skeleton::{YarnPiece, YarnSkeleton};
use crate::surface::{Surface, UvRect};

/// Knits `pattern` over `surface`: [`PreparedKnit::new`] then [`PreparedKnit::build`].
pub fn knit(surface: &dyn Surface, pattern: &StitchPattern, p: &KnitParams) -> Result<KnitOutput> {
    let start = Instant::now();
    let prepared = PreparedKnit::new(surface, pattern, p)?;
    let mut out = prepared.build(surface)?;
    out.stats.seconds = start.elapsed().as_secs_f64();
    Ok(out)
}

/// A knit bound to a surface layout: everything that does not depend on where the surface
/// is in space, fixed once (stitch counts, yarn radius, stitch size and the tuned offsets,
/// lattice, which stitches are built, yarn pieces, buffer layout).
///
/// [`build`](Self::build) makes the whole output for a surface of that layout (the same
/// surface, or the same surface deformed: moved by an armature, a shape key, a modifier);
/// [`positions_into`](Self::positions_into) makes only the vertex positions, into a buffer
/// the caller keeps. Both run the same code, consume the same per-stitch random streams and
/// so give bit-identical positions, and the topology of every build is the same: this is
/// what lets a knit follow an animated surface without flicker, and lets a farm render frame
/// N alone and get what a whole sequence gets.
#[derive(Debug, Clone)]
pub struct PreparedKnit {
    params: KnitParams,
    pattern: StitchPattern,
    /// The skeleton: lattice, loop shapes and sampling (its one front door).
    skeleton: YarnSkeleton,
    pieces: Vec<YarnPiece>,
    /// Centreline samples per piece (full density).
    samples: Vec<usize>,
    /// First sample of each piece in the concatenated centrelines.
    piece_start: Vec<usize>,
    /// The bundles built: one per piece without camera-driven detail, one per run of
    /// stitches of one level with it.
    spans: Vec<Span>,
    /// Bundle settings of the full, mid and far levels.
    level_bundle: [BundleSettings; 3],
    /// Element counts per span.
    counts: Vec<BundleCounts>,
    /// Level of every stitch (row-major), with camera-driven detail.
    levels: Option<Vec<Level>>,
    total: OutputSize,
    /// The (u,v) layout the knit was prepared for.
    domain: UvRect,
    cyclic: (bool, bool),
    /// Everything but the per-build figures.
    stats: KnitStats,
    radius: f32,
    /// With `cull_hidden`: the triangles kept, of the whole mesh the spans make.
    hidden: Option<HiddenCulled>,
    /// The whole build `cull_hidden` made from the views, kept for the first
    /// [`build`](Self::build) of the same surface.
    first_build: FirstBuild,
    /// Every span's draws ([`crate::geometry::BundleProfile`]), made by the first
    /// [`positions_into`](Self::positions_into) and kept for the frames after it (about
    /// 5 bytes a vertex).
    span_profiles: std::sync::OnceLock<Vec<crate::geometry::BundleProfile>>,
}

/// The seen triangles of a knit that culls its hidden yarn.
#[derive(Debug, Clone)]
struct HiddenCulled {
    subset: MeshSubset,
    /// One bit per triangle of the whole mesh (see [`DetailParams::pinned_seen`]).
    seen: Vec<u8>,
}
