//! Sampled surfaces: the first stage of the pipeline. A surface maps its (u,v) parameter
//! domain to positions and unit normals in scene units (the Blender object's local space).
//!
//! Two kinds, both built from plain buffers (no Blender types):
//! - [`GridSurface`]: positions and normals sampled on a regular (u,v) grid (a NURBS surface
//!   evaluated by Blender), bilinearly interpolated, optionally cyclic in u and/or v.
//! - [`MeshSurface`]: a triangle mesh with per-corner UVs; (u,v) is located through a uniform
//!   grid index over the UV triangles. A (u,v) outside every UV island has no surface.

mod grid;
mod mesh;
mod plane;
mod pole_fans;
mod uv_seams;

pub use grid::GridSurface;
pub use mesh::MeshSurface;
pub use plane::PlaneSurface;

use glam::{Vec2, Vec3};

use crate::error::{KnitError, Result};

/// Largest magnitude of a position coordinate or a UV a surface accepts. Beyond it, squared
/// lengths (spline frames, clearance, the UV index) would overflow f32. It matters because
/// Blender stores an infinite coordinate as the largest float (3.4e38) rather than infinity,
/// so an "infinite" vertex arrives here as a huge finite one.
pub const MAX_COORDINATE: f32 = 1e18;

/// The first value of `buf` that is not finite or is beyond [`MAX_COORDINATE`], as its index
/// and a description of what is wrong with it.
pub(crate) fn first_bad_coordinate(buf: &[f32]) -> Option<(usize, String)> {
    buf.iter().enumerate().find_map(|(k, &x)| {
        if !x.is_finite() {
            Some((k, format!("{x}")))
        } else if x.abs() > MAX_COORDINATE {
            Some((
                k,
                format!(
                    "{x:e}, too large (coordinates must be within +-{MAX_COORDINATE:e}; \
                     Blender stores an infinite coordinate as 3.4e38)"
                ),
            ))
        } else {
            None
        }
    })
}

/// [`first_bad_coordinate`] as a surface error, `describe(k)` naming float index `k`.
pub(crate) fn check_coordinates(buf: &[f32], describe: impl Fn(usize) -> String) -> Result<()> {
    match first_bad_coordinate(buf) {
        Some((k, what)) => Err(KnitError::Surface(format!(
            "{} is {what} (float index {k})",
            describe(k)
        ))),
        None => Ok(()),
    }
}

/// A point of the surface: position (scene units) and unit normal, both in object space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    pub position: Vec3,
    pub normal: Vec3,
}

/// An axis-aligned rectangle of the (u,v) domain: `[min.x, max.x] x [min.y, max.y]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UvRect {
    pub min: Vec2,
    pub max: Vec2,
}

impl UvRect {
    pub fn size(&self) -> Vec2 {
        self.max - self.min
    }
}

/// What every stage after sampling needs from a surface. Implementations are immutable and
/// shared across rayon threads; `eval` must be a pure function of `uv` (determinism).
pub trait Surface: Send + Sync {
    /// The (u,v) domain stitches are laid out over. Grid: `[0,1] x [0,1]`. Mesh: the bounding
    /// rectangle of all UVs.
    fn domain(&self) -> UvRect;
    /// Whether u (resp. v) wraps around: `eval(u + domain width, v) == eval(u, v)`.
    fn cyclic_u(&self) -> bool;
    fn cyclic_v(&self) -> bool;
    /// Position and unit normal at (u,v), or `None` where there is no surface (a mesh's (u,v)
    /// outside every UV island). Outside the domain of a non-cyclic grid the value is clamped
    /// to the border.
    fn eval(&self, uv: Vec2) -> Option<SurfacePoint>;
    /// Like `eval`, but where there is no surface, the value at the nearest point of the
    /// nearest UV triangle (for spline samples that stray just outside an island between key
    /// points that are inside it). Always finite.
    fn eval_nearest(&self, uv: Vec2) -> SurfacePoint;
    /// Mean length, in scene units, of the surface along u across the whole domain width, and
    /// along v across the whole domain height (what a tape measure laid along a course, and
    /// along a wale, would read). Used to turn a knitter's gauge into stitch counts.
    fn extent(&self) -> (f32, f32);
}
