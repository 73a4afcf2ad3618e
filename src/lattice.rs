//! The stitch lattice: tile corners in the surface's (u,v) domain, one tile per stitch
//! (seed 000, section 2.3). Courses (rows) run along u and are stacked along v; wales
//! (columns) run along v.
//!
//! Node `(r, c)` is the bottom-left corner of the tile of stitch (course `r`, wale `c`).
//! Nodes exist for `r in 0..=courses + 1` (the extra row gives the top course its northern
//! neighbour `n4`) and `c in 0..=wales`. In a cyclic direction the last node column (row) is
//! the first one moved by one domain period, so coordinates may leave the domain: the
//! surface wraps them.

use glam::Vec2;

use crate::surface::UvRect;

/// How far, in rows, the sinker dips below a tile (k0) and the head reaches above it (k3).
/// The lattice is inset by this much on a non-cyclic v so every key point lies on the surface.
pub const ROW_OVERHANG: f32 = 0.35;

/// Tile corners in (u,v), regular: the elastic rest position of the fabric.
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
        }
    }

    /// Node `(r, c)`, `r <= courses + 1`, `c <= wales`.
    pub fn node(&self, r: usize, c: usize) -> Vec2 {
        self.nodes[r * (self.wales + 1) + c]
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

    /// The (u,v) of the centre of a tile (for colour images sampled per stitch).
    pub fn tile_center(&self, course: usize, wale: usize) -> Vec2 {
        self.origin + self.tile * Vec2::new(wale as f32 + 0.5, course as f32 + 0.5)
    }
}
