//! Pile slices ([Zhang plush], section 2 and formulas (3)/(4); docs/design.md section 6): each
//! pile is drawn as `S` textured quads, horizontal or vertical, chosen per pile for the view.
//!
//! **The choice.** `alpha` is the angle between the pile direction `t` and the view ray `L`
//! from the pile's root to the eye, `r` the pile radius and `l` the *slice spacing* along the
//! pile (`pile length / S`: the paper's "distance between layers"). Seen from the eye, the pile
//! diameter projects to `2 r |cos alpha|` and the gap between two slices to `l sin alpha`;
//! horizontal slices leave no gap while `2 r |cos alpha| >= l sin alpha`, so they are used
//! then, vertical slices otherwise. We take `|cos alpha|` (the paper writes `cos alpha`): a
//! projected length does not change sign, and a pile seen from behind the fabric, nearly along
//! its axis, has no gaps either.
//!
//! **A band, not a line.** Applied as it stands, the criterion flips every pile at the same
//! angle, and where the angle sweeps smoothly across a frame (a close-up, the edge of a press)
//! the two kinds meet along a hard line: they differ in brightness (a horizontal stack shows
//! its light tips, a vertical one the darker roots along its side). So each pile carries its
//! own threshold `blend` in `[0, 1)` and takes horizontal slices only while
//! `2 r |cos alpha| >= (1 + (BLEND_BAND - 1) blend) l sin alpha`: at a ratio under 1 every
//! pile is vertical (horizontal would leave gaps), above [`BLEND_BAND`] every pile is
//! horizontal, and in between a growing share is, so the change reads as a gradient. The band
//! lies wholly on the side where vertical slices are gap-free too, so the blend costs no
//! cover. The thresholds are an ordered dither (Roberts' R2 sequence over the pile grid,
//! shifted per seed), not white noise: white noise clumps the minority kind into dark
//! specks, R2 spreads it evenly like a halftone.
//!
//! **Horizontal slices** (formula (3)): quad `i` (`0 <= i < S`) is centred on the pile axis at
//! `Pc = root + (i + 1/2) l t`, parallel to the fabric's tangent plane: corners
//! `Pc -/+ r a -/+ r b` with `a`, `b` the fabric frame's course and wale directions. UVs span
//! the quad; the material cuts the inscribed disc (round mask).
//!
//! **Vertical slices** (formula (4)): quad `i` contains the axis segment from
//! `Ps = root + i l t` to `Pe = root + (i + 1) l t` and faces the viewer: with
//! `R = normalize(t x L)`, corners `P0 = Ps - r R`, `P1 = Ps + r R`, `P2 = Pe + r R`,
//! `P3 = Pe - r R` (the quad's normal is `L`'s part across the pile, towards the eye).
//! The material keeps the whole quad (rectangular mask).
//!
//! **Fixed topology.** Both kinds emit exactly `S` quads of 4 vertices per pile in the same
//! corner order, so vertex, triangle and edge counts, the triangles, the edges, the UVs and the
//! colours never change with the view: a camera move rewrites positions and the mask only,
//! and an animated camera never changes the mesh topology. (One tall vertical quad per pile
//! would draw fewer triangles side-on but would change the topology whenever a pile flips.)
//!
//! **Layout.** Quad `q = pile * S + i` owns vertices `4q..4q+4` (corners 0..3, UVs (0,0),
//! (1,0), (1,1), (0,1)), triangles `2q` = (0,1,2) and `2q+1` = (0,2,3), and edges `5q..5q+5`
//! = (0,1), (1,2), (2,3), (3,0), (0,2). `corner_edges[k]` is the edge from corner k of a
//! triangle to the next corner.

use glam::Vec3;

use crate::error::{KnitError, Result};

/// Vertices, triangles and edges of one slice quad.
pub const VERTICES_PER_QUAD: usize = 4;
pub const TRIANGLES_PER_QUAD: usize = 2;
pub const EDGES_PER_QUAD: usize = 5;

/// Darkening of the pile colour at the root and lightening at the tip: the colour of slice `i`
/// is the base colour times `ROOT_SHADE + (TIP_SHADE - ROOT_SHADE) * (i + 1/2) / S`,
/// clamped to `[0, 1]`. Root pile sits in its neighbours' shadow (the paper draws no
/// shadows, so we bake a little); the tips catch the light.
pub const ROOT_SHADE: f32 = 0.45;
pub const TIP_SHADE: f32 = 1.15;

/// Mask value per vertex: horizontal slices carry a round mask, vertical ones a rectangle.
pub const MASK_ROUND: f32 = 0.0;
pub const MASK_RECT: f32 = 1.0;

/// Width of the band over which piles change kind, as a ratio of the criterion's two sides
/// (see the module doc): from `2 r |cos alpha| = l sin alpha` to twice that. At the default
/// plush (`2 r / l` = 2.9) that is from 71 degrees off the pile's axis down to 55. Wide enough
/// that in the palm print's close-up the change spreads over about 60 px of 1024; a band of
/// 4 spread dark vertical piles over most of the unpressed cushion.
pub const BLEND_BAND: f32 = 2.0;

/// Where the pile is seen from. Coordinates in the surface's object space (scene units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum View {
    /// A perspective camera at `eye`: each pile has its own view ray, root to eye.
    Perspective { eye: Vec3 },
    /// An orthographic camera looking along `direction` (the camera's -Z axis in Blender);
    /// the view ray towards the viewer is `-direction` for every pile.
    Orthographic { direction: Vec3 },
    /// Every pile seen straight down its fabric normal (a preview without a camera: mostly
    /// horizontal slices).
    AlongNormal,
}

impl View {
    /// Refuses NaN, infinite or zero inputs.
    pub fn validate(&self) -> Result<()> {
        match *self {
            View::Perspective { eye } if !eye.is_finite() => Err(KnitError::Parameter(format!(
                "the eye must be a finite point, not {eye}"
            ))),
            View::Orthographic { direction }
                if !direction.is_finite() || direction.length_squared() == 0.0 =>
            {
                Err(KnitError::Parameter(format!(
                    "the view direction must be a finite non-zero vector, not {direction}"
                )))
            }
            _ => Ok(()),
        }
    }

    /// Unit vector from `root` towards the viewer (the paper's `L`). Falls back to the fabric
    /// normal where the eye sits on the root.
    #[inline]
    pub fn toward_viewer(&self, root: Vec3, normal: Vec3) -> Vec3 {
        match *self {
            View::Perspective { eye } => (eye - root).try_normalize().unwrap_or(normal),
            View::Orthographic { direction } => (-direction).try_normalize().unwrap_or(normal),
            View::AlongNormal => normal,
        }
    }
}

/// The paper's criterion: horizontal slices when `2 r |cos alpha| >= l sin alpha`, with
/// `cos alpha = t . L` for unit `t` (pile direction) and `L` (towards the viewer), `r` the
/// pile radius and `l` the slice spacing.
#[inline]
pub fn horizontal_for(t: Vec3, to_viewer: Vec3, radius: f32, spacing: f32) -> bool {
    horizontal_blended(t, to_viewer, radius, spacing, 0.0)
}

/// [`horizontal_for`] with the pile's place `blend` in `[0, 1)` across the [`BLEND_BAND`]:
/// horizontal when `2 r |cos alpha| >= (1 + (BLEND_BAND - 1) blend) l sin alpha`.
#[inline]
pub fn horizontal_blended(t: Vec3, to_viewer: Vec3, radius: f32, spacing: f32, blend: f32) -> bool {
    let c = t.dot(to_viewer).clamp(-1.0, 1.0);
    let s = (1.0 - c * c).max(0.0).sqrt();
    2.0 * radius * c.abs() >= (1.0 + (BLEND_BAND - 1.0) * blend) * spacing * s
}

/// Element counts of `piles` piles with `slices` quads each (closed forms).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SliceCounts {
    pub piles: u64,
    pub quads: u64,
    pub vertices: u64,
    pub triangles: u64,
    pub edges: u64,
    /// `3 * triangles`.
    pub corner_edges: u64,
}

impl SliceCounts {
    pub fn of(piles: u64, slices: u64) -> Self {
        let quads = piles.saturating_mul(slices);
        let triangles = quads.saturating_mul(TRIANGLES_PER_QUAD as u64);
        Self {
            piles,
            quads,
            vertices: quads.saturating_mul(VERTICES_PER_QUAD as u64),
            triangles,
            edges: quads.saturating_mul(EDGES_PER_QUAD as u64),
            corner_edges: triangles.saturating_mul(3),
        }
    }
}

/// Writes the topology of quads `first_quad..first_quad + n` (where `n` follows from the
/// slice lengths): `triangles` `(6n)`, `corner_edges` `(6n)`, `edges` `(10n)`.
pub fn write_topology(
    first_quad: usize,
    triangles: &mut [i32],
    corner_edges: &mut [i32],
    edges: &mut [i32],
) {
    let n = triangles.len() / 6;
    for j in 0..n {
        let q = first_quad + j;
        let v = (VERTICES_PER_QUAD * q) as i32;
        let e = (EDGES_PER_QUAD * q) as i32;
        triangles[6 * j..6 * j + 6].copy_from_slice(&[v, v + 1, v + 2, v, v + 2, v + 3]);
        corner_edges[6 * j..6 * j + 6].copy_from_slice(&[e, e + 1, e + 4, e + 4, e + 2, e + 3]);
        edges[10 * j..10 * j + 10].copy_from_slice(&[
            v,
            v + 1,
            v + 1,
            v + 2,
            v + 2,
            v + 3,
            v + 3,
            v,
            v,
            v + 2,
        ]);
    }
}

/// The UVs of one pile's `S` quads: `(0,0), (1,0), (1,1), (0,1)` per quad, `(8S)`.
pub fn write_uvs(uvs: &mut [f32]) {
    for quad in uvs.chunks_exact_mut(8) {
        quad.copy_from_slice(&[0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0]);
    }
}

/// The colours of one pile's `S` quads, `(16S)`: `base` shaded from root to tip, alpha 1.
pub fn write_colors(base: [f32; 3], colors: &mut [f32]) {
    let s = colors.len() / 16;
    for (i, quad) in colors.chunks_exact_mut(16).enumerate() {
        let h = (i as f32 + 0.5) / s as f32;
        let f = ROOT_SHADE + (TIP_SHADE - ROOT_SHADE) * h;
        let c = [
            (base[0] * f).clamp(0.0, 1.0),
            (base[1] * f).clamp(0.0, 1.0),
            (base[2] * f).clamp(0.0, 1.0),
            1.0,
        ];
        for k in 0..VERTICES_PER_QUAD {
            quad[4 * k..4 * k + 4].copy_from_slice(&c);
        }
    }
}

/// One pile as the slice writer needs it (object space, scene units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PileGeometry {
    pub root: Vec3,
    /// Unit fabric frame at the root: course direction, wale direction, normal.
    pub a: Vec3,
    pub b: Vec3,
    pub normal: Vec3,
    /// Unit pile direction.
    pub t: Vec3,
    /// The pile's place across the [`BLEND_BAND`], in `[0, 1)`: drawn once per pile from the
    /// seed and its grid cell, so it never changes with the view.
    pub blend: f32,
}

/// Writes one pile's `S` quads for `view`: positions `(12S)` and mask `(4S)`. Returns whether
/// the slices are horizontal.
pub fn write_pile(
    p: &PileGeometry,
    view: &View,
    radius: f32,
    spacing: f32,
    positions: &mut [f32],
    mask: &mut [f32],
) -> bool {
    let l = view.toward_viewer(p.root, p.normal);
    let horizontal = horizontal_blended(p.t, l, radius, spacing, p.blend);
    let step = p.t * spacing;
    if horizontal {
        let (ra, rb) = (p.a * radius, p.b * radius);
        for (i, quad) in positions.chunks_exact_mut(12).enumerate() {
            let c = p.root + step * (i as f32 + 0.5);
            let corners = [c - ra - rb, c + ra - rb, c + ra + rb, c - ra + rb];
            for (k, q) in corners.iter().enumerate() {
                quad[3 * k..3 * k + 3].copy_from_slice(&q.to_array());
            }
        }
    } else {
        // Where t is parallel to L the criterion always picks horizontal slices, so the
        // fallback only guards against rounding.
        let rr = p.t.cross(l).try_normalize().unwrap_or(p.a) * radius;
        for (i, quad) in positions.chunks_exact_mut(12).enumerate() {
            let ps = p.root + step * i as f32;
            let pe = p.root + step * (i as f32 + 1.0);
            let corners = [ps - rr, ps + rr, pe + rr, pe - rr];
            for (k, q) in corners.iter().enumerate() {
                quad[3 * k..3 * k + 3].copy_from_slice(&q.to_array());
            }
        }
    }
    mask.fill(if horizontal { MASK_ROUND } else { MASK_RECT });
    horizontal
}
