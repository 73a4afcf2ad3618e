//! The stitch lattice: tile corners in the surface's (u,v) domain, one tile per stitch
//! ([Zhong 2001], section 2.3). Courses (rows) run along u and are stacked along v; wales
//! (columns) run along v.
//!
//! Node `(r, c)` is the bottom-left corner of the tile of stitch (course `r`, wale `c`).
//! Nodes exist for `r in 0..=courses + 1` (the extra row gives the top course its northern
//! neighbour `n4`) and `c in 0..=wales`. In a cyclic direction the last node column (row) is
//! the first one moved by one domain period, so coordinates may leave the domain: the
//! surface wraps them.
//!
//! [`Lattice::perturbed`] moves every node by the recursive random perturbation of section
//! 2.4 ([`perturbation`]): tiles become general convex quadrilaterals that never fold.

pub mod perturbation;
pub mod row_heights;

use glam::{DVec2, Vec2};
use rayon::prelude::*;

use crate::error::Result;
use crate::surface::UvRect;

pub use perturbation::{Perturbation, KAPPA_MAX};
pub use row_heights::RowHeights;

/// How far, in rows, the sinker dips below a tile (k0) and the head reaches above it (k3).
/// The lattice is inset by this much on a non-cyclic v so every key point lies on the surface.
pub const ROW_OVERHANG: f32 = 0.35;

/// Tile corners in (u,v): regular (the elastic rest position of the fabric), or perturbed.
#[derive(Debug, Clone)]
pub struct Lattice {
    pub courses: usize,
    pub wales: usize,
    pub cyclic_u: bool,
    pub cyclic_v: bool,
    /// Tile size in (u,v) units.
    pub tile: Vec2,
    origin: Vec2,
    /// Row-major `(courses + 2) x (wales + 1)` node positions.
    nodes: Vec<Vec2>,
    /// Whether the nodes were moved off the regular grid (then tile centres are corner means).
    perturbed: bool,
    /// Whether the lattice is a window onto a larger fabric (a patch that offsets are tuned
    /// on) rather than a whole piece: see [`Lattice::window`].
    pub window: bool,
}

/// The four corners of a tile and the northern neighbour of its top-left corner, named as in
/// the paper's figure 4 (v points north).
#[derive(Debug, Clone, Copy)]
pub struct Tile {
    /// Top-left.
    pub n0: Vec2,
    /// Top-right.
    pub n1: Vec2,
    /// Bottom-right.
    pub n2: Vec2,
    /// Bottom-left.
    pub n3: Vec2,
    /// The lattice node north of `n0` (top-left corner of the tile above).
    pub n4: Vec2,
}

impl Lattice {
    /// A regular lattice of `courses x wales` tiles over `domain`. On a non-cyclic v the rows
    /// are inset by [`ROW_OVERHANG`] of a row at both ends, so sinkers of the first course and
    /// heads of the last stay inside the domain.
    pub fn regular(
        domain: UvRect,
        courses: usize,
        wales: usize,
        cyclic_u: bool,
        cyclic_v: bool,
    ) -> Self {
        let size = domain.size();
        let tile_u = size.x / wales as f32;
        let tile_v = if cyclic_v {
            size.y / courses as f32
        } else {
            size.y / (courses as f32 + 2.0 * ROW_OVERHANG)
        };
        let tile = Vec2::new(tile_u, tile_v);
        let origin = if cyclic_v {
            domain.min
        } else {
            domain.min + Vec2::new(0.0, ROW_OVERHANG * tile_v)
        };
        let cols = wales + 1;
        let mut nodes = Vec::with_capacity((courses + 2) * cols);
        for r in 0..courses + 2 {
            for c in 0..cols {
                nodes.push(origin + Vec2::new(c as f32 * tile_u, r as f32 * tile_v));
            }
        }
        Self {
            courses,
            wales,
            cyclic_u,
            cyclic_v,
            tile,
            origin,
            nodes,
            perturbed: false,
            window: false,
        }
    }

    /// The regular lattice with every node moved by the recursive random perturbation of
    /// strength `kappa` ([Zhong 2001], section 2.4): node `(r, c)` is
    /// `origin + tile * ((c, r) + D(r, c))` with `D` the [`Perturbation`] field in tile units.
    ///
    /// - `kappa = 0` gives exactly [`Lattice::regular`].
    /// - Every tile stays a convex, positively oriented quadrilateral keeping at least
    ///   `1 - 40 * kappa` of its area, for every seed: by construction, see [`perturbation`].
    /// - Nodes on a non-cyclic side (columns 0 and `wales`, rows 0 and `courses + 1`) keep
    ///   that side's coordinate, bit for bit, so the lattice's outline stays the domain's.
    ///   Key points that extrapolate past a tile along v (the first course's sinkers, 0.35 of
    ///   a row below row 0; the last course's heads, 0.35 of a row above row `courses`) can
    ///   leave a non-cyclic v side by at most `0.35 * 12 kappa` resp. `0.65 * 12 kappa` of a
    ///   row (0.084 and 0.156 at [`KAPPA_MAX`]), because row 1 and row `courses` move in v;
    ///   across u they stay inside.
    /// - Along a non-cyclic direction the field is local: adding rows or columns at the far
    ///   edge leaves nodes [`perturbation::LOCALITY_RADIUS`] (32) or more tiles away from it
    ///   unchanged, bit for bit. Along a cyclic direction it has the period exactly.
    /// - The result depends only on the arguments: not on the machine or the thread count.
    ///
    /// Errors: [`crate::error::KnitError::Parameter`] for kappa outside `[0, KAPPA_MAX]` or
    /// not finite.
    pub fn perturbed(
        domain: UvRect,
        courses: usize,
        wales: usize,
        cyclic_u: bool,
        cyclic_v: bool,
        kappa: f32,
        seed: u64,
    ) -> Result<Self> {
        perturbation::check_kappa(kappa)?;
        let mut lattice = Self::regular(domain, courses, wales, cyclic_u, cyclic_v);
        if kappa == 0.0 || courses == 0 || wales == 0 {
            return Ok(lattice);
        }
        let field = Perturbation::new(courses, wales, cyclic_u, cyclic_v, kappa, seed)?;
        let origin = lattice.origin.as_dvec2();
        let tile = lattice.tile.as_dvec2();
        lattice
            .nodes
            .par_chunks_mut(wales + 1)
            .enumerate()
            .for_each(|(r, row)| {
                for (c, node) in row.iter_mut().enumerate() {
                    let d = field.displacement(r, c);
                    let moved =
                        (origin + tile * DVec2::new(c as f64 + d[0], r as f64 + d[1])).as_vec2();
                    // A component that does not move keeps the regular lattice's bits
                    // (boundary sides stay exactly on the domain's edge).
                    if d[0] != 0.0 {
                        node.x = moved.x;
                    }
                    if d[1] != 0.0 {
                        node.y = moved.y;
                    }
                }
            });
        lattice.perturbed = true;
        Ok(lattice)
    }

    /// The lattice with its rows made taller or shorter column by column, as `heights`
    /// says ([`RowHeights`]): every node moves along v by its displacement times the tile
    /// height. Nodes whose displacement is zero keep their bits (the first node row, the
    /// last one of a non-cyclic v, columns whose rows are all regular), so the outline of
    /// the fabric stays the domain's. Tiles keep their node order as long as every height is
    /// more than the perturbation can take away (heights of at least 0.5 against at most
    /// `12 kappa` = 0.24 rows at [`KAPPA_MAX`]).
    pub fn with_row_heights(mut self, heights: &RowHeights) -> Self {
        let d = heights.node_displacements(self.courses, self.wales, self.cyclic_u, self.cyclic_v);
        let tile_v = self.tile.y;
        for (node, d) in self.nodes.iter_mut().zip(&d) {
            if *d != 0.0 {
                node.y += d * tile_v;
                self.perturbed = true;
            }
        }
        self
    }

    /// The lattice as a window onto a larger fabric: its sides are not the fabric's edges,
    /// so a crossing the window holds only part of still crosses (the loops landing off it
    /// stay straight), where a piece of fabric knits it straight whole
    /// ([`crate::skeleton::stitch_shape::landing`]).
    pub fn window(mut self) -> Self {
        self.window = true;
        self
    }

    /// Node `(r, c)`, `r <= courses + 1`, `c <= wales`.
    pub fn node(&self, r: usize, c: usize) -> Vec2 {
        self.nodes[r * (self.wales + 1) + c]
    }

    /// Keeps key points on the fabric across a non-cyclic v: into the v range the regular
    /// lattice's sinkers and heads span (`ROW_OVERHANG` of a row beyond the first and last
    /// courses, which is the domain's edge). Only a perturbed lattice needs it: its second and
    /// second-to-last rows move, and a first-course sinker can then dip up to a tenth of a row
    /// below the edge, where a UV island ends and the stitch would be lost. A no-op on a regular
    /// lattice (bit for bit) and along a cyclic v.
    pub fn keep_on_fabric(&self, points: &mut [Vec2]) {
        if !self.perturbed || self.cyclic_v {
            return;
        }
        let lo = self.origin.y - ROW_OVERHANG * self.tile.y;
        let hi = self.origin.y + (self.courses as f32 + ROW_OVERHANG) * self.tile.y;
        for p in points {
            p.y = p.y.clamp(lo, hi);
        }
    }

    /// The corners of the tile of stitch (course, wale).
    pub fn tile(&self, course: usize, wale: usize) -> Tile {
        Tile {
            n0: self.node(course + 1, wale),
            n1: self.node(course + 1, wale + 1),
            n2: self.node(course, wale + 1),
            n3: self.node(course, wale),
            n4: self.node(course + 2, wale),
        }
    }

    /// The (u,v) of the centre of a tile, the mean of its four corners (for colour images
    /// sampled per stitch). On a regular lattice: `origin + tile * (wale + 1/2, course + 1/2)`.
    pub fn tile_center(&self, course: usize, wale: usize) -> Vec2 {
        if self.perturbed {
            let t = self.tile(course, wale);
            (t.n0 + t.n1 + t.n2 + t.n3) * 0.25
        } else {
            self.origin + self.tile * Vec2::new(wale as f32 + 0.5, course as f32 + 0.5)
        }
    }
}
