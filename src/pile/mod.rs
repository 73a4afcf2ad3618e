//! Warp-knitted plush: pile over a surface, drawn as view-dependent slices ([Zhang plush] by Zhang,
//! Jiang, Li and Cong; docs/design.md section 6).
//!
//! Two steps, so that following a camera is cheap:
//!
//! 1. [`PileField::new`] samples the surface once: pile roots in the cells of a grid of
//!    `courses x wales` stitches with `piles_per_stitch` piles each (each root placed at random
//!    within its cell, so the pile shows no rows), the fabric frame at each root, the pile
//!    direction (nominal lean, [`fractal_noise`] rotated into the fabric frame, bent by an
//!    optional [`press`] map) and the pile colour.
//! 2. [`PileField::build`] turns the field into mesh buffers for a [`View`] ([`slices`]:
//!    horizontal or vertical slices per pile). [`PileField::update`] (in place) and
//!    [`PileField::view`] (new buffers) redo only the slice choice and the positions for a new
//!    view: the topology, UVs and colours do not depend on the view.
//!
//! [`plush`] does both for one view.
//!
//! Frames: (u,v) is the surface's parameter domain (UV map for a mesh); the *fabric frame* at
//! a root has x along the course (the surface's u direction, projected into the tangent
//! plane), y along the wale (`z x x`) and z the surface normal; positions are in the
//! surface's object space, in scene units. Angles are radians.
//!
//! Every loop writes disjoint, precomputed pieces of its output and every random draw is keyed
//! by noise texel, so the output is bit-identical for any thread count.

pub mod field;
pub mod fractal_noise;
pub mod press;
pub mod slices;

pub use field::{plush, PileBuffers, PileField, PileStats, PileView, Plush};
pub use fractal_noise::{fractal_noise, NoiseField, NoiseParams};
pub use press::PressMap;
pub use slices::{horizontal_for, SliceCounts, View};

use crate::budget::MAX_MESH_ELEMENTS;
use crate::error::{KnitError, Result};
use crate::pattern::ColorImage;
use crate::pattern::ColorPattern;

/// Plush gauge used when neither counts nor a gauge are given: 48 wales and 64 courses per
/// 10 cm. Warp-knit plush is much finer than hand knitting (the paper's sample: 384 courses x
/// 240 wales).
pub const DEFAULT_PLUSH_GAUGE: (f32, f32) = (
    crate::settings::PLUSH_GAUGE_WALES.default_f32(),
    crate::settings::PLUSH_GAUGE_COURSES.default_f32(),
);
/// Default pile length: 2.5 stitch widths.
pub const DEFAULT_LENGTH_PER_STITCH_WIDTH: f32 = 2.5;
/// Default pile radius: 0.6 of the spacing between neighbouring piles (the smaller of the
/// spacings along u and v), so horizontal slices of neighbours overlap a little and a view
/// from above sees no fabric between them.
pub const DEFAULT_RADIUS_PER_PILE_SPACING: f32 = 0.6;
/// Default slices per pile.
pub const DEFAULT_SLICES: usize = crate::settings::SLICES.default_usize();
/// Most slices per pile.
pub const MAX_SLICES: usize = crate::settings::SLICES.max as usize;
/// Most piles per stitch.
pub const MAX_PILES_PER_STITCH: usize = crate::settings::PILES_PER_STITCH.max as usize;
/// Most stitches along one direction.
pub const MAX_STITCHES_PER_DIRECTION: usize = crate::gauge::MAX_STITCHES_PER_DIRECTION;
/// Default nominal lean: 30 degrees from the normal, towards -v (the pile brushed down the
/// wale, as plush is finished).
pub const DEFAULT_LEAN: (f32, f32) = (
    crate::settings::LEAN_ANGLE.default_f32(),
    crate::settings::LEAN_DIRECTION.default_f32(),
);
/// Default press strength: a full press (weight 1) bends the pile 90% of the way flat.
pub const DEFAULT_PRESS_STRENGTH: f32 = crate::settings::PRESS_STRENGTH.default_f32();
/// Default pile colour (linear RGB): a deep red velvet.
pub const DEFAULT_PILE_COLOR: [f32; 3] = [0.45, 0.06, 0.08];

/// Bytes of output per vertex: position (12) + colour (16) + UV (8) + mask (4).
pub const BYTES_PER_VERTEX: u64 = 40;
/// Bytes per triangle: corner vertices (12) + corner edges (12).
pub const BYTES_PER_TRIANGLE: u64 = 24;
/// Bytes per edge: two vertex indices.
pub const BYTES_PER_EDGE: u64 = 8;
/// Bytes per pile held while building: the field's geometry and colour, the staging copy and
/// the per-pile slice choice.
pub const BYTES_PER_PILE: u64 = 2 * 76 + 1;
/// Bytes per noise texel: base and fractal noise.
pub const BYTES_PER_TEXEL: u64 = 24;

/// The pile's nominal direction in the fabric frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Nominal {
    /// `angle` from the normal (`0..=pi/2`) towards `azimuth` (from the course direction x
    /// towards the wale direction y): `(sin a cos z, sin a sin z, cos a)`.
    Lean { angle: f32, azimuth: f32 },
    /// A vector in the fabric frame, normalised; it must not point into the fabric (z >= 0).
    Direction(glam::Vec3),
}

impl Nominal {
    /// The unit nominal direction `t` in the fabric frame.
    pub fn direction(&self) -> Result<glam::Vec3> {
        match *self {
            Nominal::Lean { angle, azimuth } => {
                if !(angle.is_finite()
                    && (0.0..=std::f32::consts::FRAC_PI_2).contains(&angle)
                    && azimuth.is_finite())
                {
                    return Err(KnitError::Parameter(format!(
                        "the lean angle must be 0..=pi/2 radians and its direction finite, not \
                         ({angle}, {azimuth})"
                    )));
                }
                Ok(fractal_noise::from_angles(angle, azimuth))
            }
            Nominal::Direction(d) => match d.try_normalize() {
                Some(t) if t.z >= 0.0 => Ok(t),
                _ => Err(KnitError::Parameter(format!(
                    "the nominal pile direction must be a finite non-zero vector with z >= 0 \
                     (not into the fabric), not {d}"
                ))),
            },
        }
    }

    /// Azimuth of the lean in the fabric plane (radians), the default press direction.
    pub fn azimuth(&self) -> f32 {
        match *self {
            Nominal::Lean { azimuth, .. } => azimuth,
            Nominal::Direction(d) if d.x != 0.0 || d.y != 0.0 => {
                crate::portable_math::atan2(d.y, d.x)
            }
            Nominal::Direction(_) => DEFAULT_LEAN.1,
        }
    }
}

/// Where the pile colours come from.
#[derive(Debug, Clone, PartialEq)]
pub enum PileColors {
    /// One linear RGB colour.
    Solid([f32; 3]),
    /// One linear RGB colour per stitch, `courses * wales` of them, stitch `(course, wale)` at
    /// `course * wales + wale`, course 0 at v = 0.
    PerStitch(Vec<[f32; 3]>),
    /// A colour pattern, repeated over the stitches.
    Pattern(ColorPattern),
    /// An image over (u,v), sampled at each pile root.
    Image(ColorImage),
}

/// Every setting of a plush build. Lengths in scene units, angles in radians.
#[derive(Debug, Clone)]
pub struct PileParams {
    /// Rows of stitches along v. Default: from the gauge.
    pub courses: Option<usize>,
    /// Stitches per row along u. Default: from the gauge.
    pub wales: Option<usize>,
    /// Wales and courses per 10 cm measured on the surface. Default: [`DEFAULT_PLUSH_GAUGE`].
    pub gauge: Option<(f32, f32)>,
    /// Piles per stitch, 1..=[`MAX_PILES_PER_STITCH`], laid out as a sub-grid of
    /// [`pile_grid`]. Default: 1.
    pub piles_per_stitch: usize,
    /// Default: [`DEFAULT_LENGTH_PER_STITCH_WIDTH`] stitch widths.
    pub pile_length: Option<f32>,
    /// Default: [`DEFAULT_RADIUS_PER_PILE_SPACING`] of the pile spacing.
    pub pile_radius: Option<f32>,
    /// Slices per pile, 1..=[`MAX_SLICES`]. Default: [`DEFAULT_SLICES`].
    pub slices: usize,
    /// Default: [`DEFAULT_LEAN`].
    pub nominal: Nominal,
    /// Largest deviation of a pile from the nominal direction, `0 <= theta_max < pi/4`.
    /// Default: [`fractal_noise::DEFAULT_THETA_MAX`].
    pub theta_max: f32,
    /// Sampling coefficients of the fractal noise. Default: `[1, 2, 4, 8]`.
    pub noise_scales: Vec<usize>,
    /// Noise texture `(width, height)` in texels, covering the whole (u,v) domain once.
    /// Default: one texel per pile.
    pub noise_size: Option<(usize, usize)>,
    pub seed: u64,
    pub colors: PileColors,
    /// Where pressed, the pile bends towards the fabric plane. Default: none.
    pub press: Option<PressMap>,
    /// `0..=1`. Default: [`DEFAULT_PRESS_STRENGTH`].
    pub press_strength: f32,
    /// Azimuth of pressed pile in the fabric plane. Default: the lean's azimuth.
    pub press_azimuth: Option<f32>,
    /// Threads of the private pool. Default: all cores.
    pub threads: Option<usize>,
    /// Refuse outputs larger than this. Default: [`crate::budget::DEFAULT_BUDGET_BYTES`].
    pub budget_bytes: u64,
}

impl Default for PileParams {
    fn default() -> Self {
        Self {
            courses: None,
            wales: None,
            gauge: None,
            piles_per_stitch: crate::settings::PILES_PER_STITCH.default_usize(),
            pile_length: None,
            pile_radius: None,
            slices: DEFAULT_SLICES,
            nominal: Nominal::Lean {
                angle: DEFAULT_LEAN.0,
                azimuth: DEFAULT_LEAN.1,
            },
            theta_max: fractal_noise::DEFAULT_THETA_MAX,
            noise_scales: fractal_noise::DEFAULT_SCALES.to_vec(),
            noise_size: None,
            seed: 0,
            colors: PileColors::Solid(DEFAULT_PILE_COLOR),
            press: None,
            press_strength: DEFAULT_PRESS_STRENGTH,
            press_azimuth: None,
            threads: None,
            budget_bytes: crate::budget::DEFAULT_BUDGET_BYTES,
        }
    }
}

/// How `n` piles per stitch are laid out: `(along u, along v)`, the factorisation of `n`
/// closest to square with the longer side along u (1: 1x1, 2: 2x1, 4: 2x2, 6: 3x2, 7: 7x1).
pub fn pile_grid(n: usize) -> (usize, usize) {
    let n = n.max(1);
    let mut a = (n as f64).sqrt() as usize;
    while a > 1 && n % a != 0 {
        a -= 1;
    }
    let a = a.max(1);
    (n / a, a)
}

fn human(bytes: u64) -> String {
    let gib = bytes as f64 / (1u64 << 30) as f64;
    if gib >= 1.0 {
        format!("{gib:.1} GiB")
    } else {
        format!("{:.0} MiB", bytes as f64 / (1u64 << 20) as f64)
    }
}

/// Bytes a build of `counts` with `texels` noise texels needs.
pub fn bytes_needed(counts: &SliceCounts, texels: u64) -> u64 {
    counts
        .vertices
        .saturating_mul(BYTES_PER_VERTEX)
        .saturating_add(counts.triangles.saturating_mul(BYTES_PER_TRIANGLE))
        .saturating_add(counts.edges.saturating_mul(BYTES_PER_EDGE))
        .saturating_add(counts.piles.saturating_mul(BYTES_PER_PILE))
        .saturating_add(texels.saturating_mul(BYTES_PER_TEXEL))
}

/// Refuses a build over the budget or beyond what a Blender mesh can index, before anything
/// is allocated.
pub fn check_budget(counts: &SliceCounts, texels: u64, budget_bytes: u64) -> Result<()> {
    let bytes = bytes_needed(counts, texels);
    if bytes > budget_bytes {
        return Err(KnitError::Budget(format!(
            "{} piles would need about {} ({} triangles), over the budget of {}: use fewer \
             stitches, piles per stitch or slices, or raise the budget",
            counts.piles,
            human(bytes),
            counts.triangles,
            human(budget_bytes)
        )));
    }
    if counts.corner_edges > MAX_MESH_ELEMENTS
        || counts.vertices > MAX_MESH_ELEMENTS
        || counts.edges > MAX_MESH_ELEMENTS
    {
        return Err(KnitError::Budget(format!(
            "{} piles would need {} triangles, more than a Blender mesh can index",
            counts.piles, counts.triangles
        )));
    }
    Ok(())
}
