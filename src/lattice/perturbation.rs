//! Recursive random perturbation of stitch positions ([Zhong 2001], section 2.4; docs/design.md
//! section 4): the displacement field `D(r, c)` that moves lattice node `(r, c)` to
//! `origin + tile * ((c, r) + D(r, c))`, measured in tile units.
//!
//! # The paper's scheme, and the form it is computed in
//!
//! The paper subdivides the lattice recursively: a block's centre and edge midpoints are first
//! placed at their elastic position (the average of the block's corners, resp. of the edge's
//! two ends), then moved by a random amount of up to kappa times the block's stitch count in
//! that direction, with no motion across an edge that lies along one row or column (an edge
//! midpoint slides along its edge only); then the same happens in each of the four quarters.
//!
//! Averaging corners is exactly what bilinear interpolation does at a centre and at edge
//! midpoints, and the bilinear interpolant of a grid restricted to the grid refined by halving
//! is again bilinear on each sub-cell. So after all levels, the position of every node is the
//! sum over levels `l` of the bilinear interpolation of the random offsets `R_l` drawn at the
//! nodes that are new at level `l` (zero at the others):
//!
//! ```text
//! D = sum_l Bilinear_l(R_l)
//! ```
//!
//! That is the form computed here. It is local (a node needs four grid values per level),
//! needs no sequential recursion, and so runs in parallel with a result that is independent of
//! the evaluation order and thread count.
//!
//! # Level grids
//!
//! Along a non-cyclic direction with `N` tiles (nodes `0..=N`; along wales = u `N = wales`,
//! along courses = v `N = courses + 1`, because the lattice has the extra node row
//! `courses + 1`), level `l` has spacing `h_l = 16 >> l` (16, 8, 4, 2, 1: five levels), grid
//! nodes at the multiples of `h_l` below `N`, and the far boundary `N` appended (so the last
//! cell may be shorter). The grid is anchored at index 0, not stretched over `N`: adding rows
//! or columns at the far edge does not move any grid node, which is what makes the field
//! LOCAL. Precisely: at each level only the last grid node below `N` (whose neighbouring cell
//! changes width, hence its amplitude) and the nodes at and beyond `N` can change, so every
//! node at index `x <= N - 2 * 16` keeps its displacement bit for bit when the lattice grows
//! at the far edge ([`LOCALITY_RADIUS`]).
//!
//! Along a cyclic direction with `N` tiles (period `N`), level 0 has `K_0 = max(1,
//! round(N / 16))` equal cells of width `N / K_0`, level `l` has `K_l = K_0 * 2^l` cells, and
//! levels go on while the width `N / K_l` is at least one tile. Grid node `k` is node
//! `k mod K_l`: the field is periodic with period `N` exactly. Because `N / K_0 < 24`, this is
//! never more than five levels either. (No locality here: changing a tube's circumference
//! changes the whole tube anyway.)
//!
//! When the two directions have different numbers of levels, the one that ran out keeps its
//! last grid and adds no new nodes at the further levels.
//!
//! # Which nodes move, and how far
//!
//! At level 0 every grid node is new and moves in u and v. At level `l >= 1` a node is new in
//! u iff it was not a node of the level `l - 1` grid along u (its u index is odd), likewise in
//! v. A node new in both (a block centre) moves in u and v; a node new in u only (the midpoint
//! of an edge lying along a course) moves in u only; new in v only (midpoint of an edge along a
//! wale) moves in v only. So the u component moves exactly at the nodes new in u, and the v
//! component exactly at the nodes new in v.
//!
//! Each moving component is `R` uniform in `[-a, a)` with `a = 2 * kappa * w_min`, where
//! `w_min` is the smallest width of the level-grid cells adjacent to the node, in either
//! direction. For an interior node of a regular grid that is `h_l`, so `a = kappa * 2 h_l`:
//! kappa times the stitch count of the block whose midpoint the node is (the paper's rule).
//! On a non-cyclic direction the boundary nodes (index 0 and `N`) never move in that
//! direction's component, so the lattice's outline stays the domain's.
//!
//! # Why tiles cannot fold (the bound behind [`KAPPA_MAX`])
//!
//! On one cell of widths `w_u x w_v`, the bilinear interpolant `f` of corner values bounded by
//! `|f_ij| <= a_ij` has `df/du = ((f_10 - f_00)(1 - t) + (f_11 - f_01) t) / w_u`, a convex
//! combination of two corner differences, each at most `a_0 + a_1 <= 2 * (2 kappa w_u)`
//! (the cell is adjacent to each of its corners, so `w_min <= w_u` there), hence
//! `|df/du| <= 4 kappa`; and likewise `|df/dv| <= 4 kappa` because `w_min <= w_v` too (this
//! is why `w_min` looks at both directions). The piecewise bilinear field is continuous, so
//! between two lattice nodes one tile apart (in either direction, either component) one level
//! contributes at most `4 kappa`, and the zero boundary values only make values smaller, so
//! they do not break this. With at most `L = 5` levels, every edge of every tile differs from
//! its rest vector `(1, 0)` or `(0, 1)` by at most `eps = 20 kappa` per component.
//!
//! A tile whose edge vectors at a corner are `(1 + d1, e1)` and `(e2, 1 + d2)` with all
//! `|d|, |e| <= eps` has the corner cross product `(1 + d1)(1 + d2) - e1 e2 >=
//! (1 - eps)^2 - eps^2 = 1 - 2 eps`, the same at all four corners; when that is positive
//! everywhere the tile is convex and keeps its orientation, and its area (half the cross
//! products at two opposite corners, summed) is at least `1 - 2 eps` of the regular tile.
//! `eps < 1/2` needs `kappa < 1/40`.
//!
//! A sharper count: at levels `l >= 1`, two grid nodes adjacent along u are never both new in
//! u (one index is even), so the u component changes along u by at most `2 kappa` per tile
//! (same for v along v), giving `|d| <= (4 + 4 * 2) kappa = 12 kappa`, `|e| <= 20 kappa`:
//! cross `>= (1 - 12 kappa)^2 - (20 kappa)^2`, positive for `kappa < 1/32`.
//!
//! [`KAPPA_MAX`] `= 0.02` stays under both: `eps = 0.4`, every tile keeps at least 20 % of
//! its regular area (42 % by the sharper count), a margin that also covers the f32 rounding of
//! the stored level values and of the node positions. Randomness plays no part in this: it
//! holds for every seed, by construction.
//!
//! # Randomness
//!
//! Each value is a stateless hash of `(seed, level, u grid index (mod K on a cyclic u), v grid
//! index, component)`, SplitMix64 finalisers chained over the words, mapped to a uniform f64 in
//! `[-1, 1)`: bit-identical on every machine and independent of evaluation order and thread
//! count. Sums and interpolation are done in f64; the per-level grid values are stored in f32.

use rayon::prelude::*;

use crate::error::{KnitError, Result};

/// The largest kappa [`Perturbation::new`] accepts: every tile keeps at least
/// `1 - 40 * kappa` (here 20 %) of its regular area, for every seed (see the module docs).
pub const KAPPA_MAX: f32 = crate::settings::KAPPA.max as f32;

/// Spacing, in tiles, of the coarsest level grid along a non-cyclic direction.
pub const LEVEL0_SPACING: usize = 16;

/// Most levels along any direction (spacings 16, 8, 4, 2, 1).
pub const MAX_LEVELS: usize = 5;

/// Nodes at least this many tiles away from the far edge of a non-cyclic direction keep
/// their displacement, bit for bit, when rows or columns are added at that edge.
pub const LOCALITY_RADIUS: usize = 2 * LEVEL0_SPACING;

/// Where the perturbation's hashes start, so they are unrelated to the other uses of `seed`
/// (per-stitch shading, pile noise): "lattice!" in ASCII.
const DOMAIN_TAG: u64 = 0x6C61_7474_6963_6521;

/// The random value of one component of one level-grid node: uniform in `[-1, 1)`, a pure
/// function of its arguments (no state, no platform dependence).
pub fn node_random(seed: u64, level: usize, iu: usize, iv: usize, component: usize) -> f64 {
    let mut z = crate::rng::splitmix64(seed ^ DOMAIN_TAG);
    for word in [level as u64, iu as u64, iv as u64, component as u64] {
        z = crate::rng::splitmix64(z ^ word);
    }
    // 53 random bits -> [0, 2) exactly representable -> [-1, 1).
    (z >> 11) as f64 * (1.0 / (1u64 << 52) as f64) - 1.0
}

/// Where a lattice index falls in one level's grid along one direction.
#[derive(Debug, Clone, Copy)]
struct Cell {
    j0: usize,
    j1: usize,
    /// Position inside the cell, 0 at `j0`, 1 at `j1`.
    t: f64,
}

/// One direction's grid at one level.
#[derive(Debug, Clone)]
struct AxisLevel {
    /// Distinct grid nodes (cyclic: `K`, node `K` being node 0; non-cyclic: `J + 1`).
    nodes: usize,
    /// Whether the node is new at this level (its component along this direction moves).
    fresh: Vec<bool>,
    /// Whether the node lies on the boundary of a non-cyclic direction (its component along
    /// this direction stays zero).
    fixed: Vec<bool>,
    /// Smallest width of the cells adjacent to the node along this direction.
    w_min: Vec<f64>,
    /// For every lattice index along this direction, its cell.
    cells: Vec<Cell>,
}

impl AxisLevel {
    /// Non-cyclic: `n` tiles (nodes `0..=n`), spacing `h`, level `level`.
    fn open(n: usize, h: usize, level: usize) -> Self {
        let last = n.div_ceil(h); // index of the node at n; >= 1 since n >= 1
        let pos = |j: usize| (j * h).min(n);
        let nodes = last + 1;
        let fresh = (0..nodes)
            .map(|j| level == 0 || (j < last && j % 2 == 1))
            .collect();
        let fixed = (0..nodes).map(|j| j == 0 || j == last).collect();
        let w_min = (0..nodes)
            .map(|j| {
                let left = (j > 0).then(|| pos(j) - pos(j - 1));
                let right = (j < last).then(|| pos(j + 1) - pos(j));
                left.into_iter().chain(right).min().unwrap_or(n) as f64
            })
            .collect();
        let cells = (0..=n)
            .map(|x| {
                let j0 = (x / h).min(last - 1);
                let (p0, p1) = (pos(j0), pos(j0 + 1));
                Cell {
                    j0,
                    j1: j0 + 1,
                    t: (x - p0) as f64 / (p1 - p0) as f64,
                }
            })
            .collect();
        Self {
            nodes,
            fresh,
            fixed,
            w_min,
            cells,
        }
    }

    /// Cyclic: period `n` tiles, `k` equal cells, lattice indices `0..count` (taken mod `n`).
    fn cyclic(n: usize, k: usize, count: usize, level: usize) -> Self {
        let fresh = (0..k).map(|j| level == 0 || j % 2 == 1).collect();
        let cells = (0..count)
            .map(|x| {
                // Exact integer arithmetic: position x lies at k * (x mod n) / n cells.
                let q = (x % n) * k;
                let j0 = q / n;
                Cell {
                    j0,
                    j1: (j0 + 1) % k,
                    t: (q - j0 * n) as f64 / n as f64,
                }
            })
            .collect();
        Self {
            nodes: k,
            fresh,
            fixed: vec![false; k],
            w_min: vec![n as f64 / k as f64; k],
            cells,
        }
    }

    /// The levels of one direction: `n` tiles, `count` lattice indices (`n + 1` when
    /// non-cyclic).
    fn levels(n: usize, cyclic: bool, count: usize) -> Vec<Self> {
        if cyclic {
            // round(n / 16), halves up, at least one cell.
            let k0 = ((n + LEVEL0_SPACING / 2) / LEVEL0_SPACING).max(1);
            (0..MAX_LEVELS)
                .map(|l| k0 << l)
                .take_while(|&k| k <= n)
                .enumerate()
                .map(|(l, k)| Self::cyclic(n, k, count, l))
                .collect()
        } else {
            debug_assert_eq!(count, n + 1);
            (0..MAX_LEVELS)
                .map(|l| Self::open(n, LEVEL0_SPACING >> l, l))
                .collect()
        }
    }

    /// This grid with no new nodes: a direction that has run out of levels.
    fn stale(&self) -> Self {
        Self {
            fresh: vec![false; self.nodes],
            ..self.clone()
        }
    }
}

/// One level: both directions' grids and the random offsets `R_l` at the grid nodes (tile
/// units, row-major by v grid index).
#[derive(Debug, Clone)]
struct Level {
    u: AxisLevel,
    v: AxisLevel,
    offsets: Vec<[f32; 2]>,
}

/// The displacement field of a lattice of `courses x wales` tiles, in tile units: see the
/// module docs for the construction and the no-fold bound.
#[derive(Debug, Clone)]
pub struct Perturbation {
    courses: usize,
    wales: usize,
    levels: Vec<Level>,
}

/// Refuses a kappa outside `[0, KAPPA_MAX]` (NaN and infinities included).
pub fn check_kappa(kappa: f32) -> Result<()> {
    if kappa.is_finite() && (0.0..=KAPPA_MAX).contains(&kappa) {
        Ok(())
    } else {
        Err(KnitError::Parameter(format!(
            "irregularity (kappa) must be between 0 and {KAPPA_MAX}, not {kappa}: larger values \
             could fold stitches over each other"
        )))
    }
}

impl Perturbation {
    /// The field for `seed`. Errors: kappa outside `[0, KAPPA_MAX]` or not finite, or an empty
    /// lattice.
    pub fn new(
        courses: usize,
        wales: usize,
        cyclic_u: bool,
        cyclic_v: bool,
        kappa: f32,
        seed: u64,
    ) -> Result<Self> {
        Self::with_values(courses, wales, cyclic_u, cyclic_v, kappa, &|l, i, j, k| {
            node_random(seed, l, i, j, k)
        })
    }

    /// Like [`Perturbation::new`], with the random values in `[-1, 1]` given by
    /// `values(level, u index, v index, component)` instead of the hash (values outside are
    /// clamped). For tests that plant adversarial values: the no-fold bound holds for any.
    #[doc(hidden)]
    pub fn with_values(
        courses: usize,
        wales: usize,
        cyclic_u: bool,
        cyclic_v: bool,
        kappa: f32,
        values: &(dyn Fn(usize, usize, usize, usize) -> f64 + Sync),
    ) -> Result<Self> {
        check_kappa(kappa)?;
        if courses == 0 || wales == 0 {
            return Err(KnitError::Parameter(format!(
                "a lattice needs at least one course and one wale, not {courses} x {wales}"
            )));
        }
        let kappa = f64::from(kappa);
        let u_levels = AxisLevel::levels(wales, cyclic_u, wales + 1);
        let v_levels = if cyclic_v {
            AxisLevel::levels(courses, true, courses + 2)
        } else {
            AxisLevel::levels(courses + 1, false, courses + 2)
        };
        let count = u_levels.len().max(v_levels.len());
        let pick = |axis: &[AxisLevel], l: usize| match axis.get(l) {
            Some(a) => a.clone(),
            None => axis[axis.len() - 1].stale(),
        };
        let levels = (0..count)
            .map(|l| {
                let u = pick(&u_levels, l);
                let v = pick(&v_levels, l);
                let mut offsets = vec![[0.0f32; 2]; u.nodes * v.nodes];
                offsets
                    .par_chunks_mut(u.nodes)
                    .enumerate()
                    .for_each(|(j, row)| {
                        for (i, out) in row.iter_mut().enumerate() {
                            let a = 2.0 * kappa * u.w_min[i].min(v.w_min[j]);
                            let draw = |moves: bool, k: usize| {
                                if moves {
                                    (a * values(l, i, j, k).clamp(-1.0, 1.0)) as f32
                                } else {
                                    0.0
                                }
                            };
                            *out = [
                                draw(u.fresh[i] && !u.fixed[i], 0),
                                draw(v.fresh[j] && !v.fixed[j], 1),
                            ];
                        }
                    });
                Level { u, v, offsets }
            })
            .collect();
        Ok(Self {
            courses,
            wales,
            levels,
        })
    }

    /// Number of levels (at most [`MAX_LEVELS`]).
    pub fn level_count(&self) -> usize {
        self.levels.len()
    }

    /// `D(r, c)`, in tiles, for node `(r, c)`, `r <= courses + 1`, `c <= wales`.
    pub fn displacement(&self, r: usize, c: usize) -> [f64; 2] {
        assert!(
            r <= self.courses + 1 && c <= self.wales,
            "node ({r}, {c}) outside the lattice"
        );
        let mut d = [0.0f64; 2];
        for level in &self.levels {
            let cu = level.u.cells[c];
            let cv = level.v.cells[r];
            let n = level.u.nodes;
            let at = |i: usize, j: usize| level.offsets[j * n + i];
            let (g00, g10) = (at(cu.j0, cv.j0), at(cu.j1, cv.j0));
            let (g01, g11) = (at(cu.j0, cv.j1), at(cu.j1, cv.j1));
            for (k, dk) in d.iter_mut().enumerate() {
                let bottom = (1.0 - cu.t) * f64::from(g00[k]) + cu.t * f64::from(g10[k]);
                let top = (1.0 - cu.t) * f64::from(g01[k]) + cu.t * f64::from(g11[k]);
                *dk += (1.0 - cv.t) * bottom + cv.t * top;
            }
        }
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lattice_hash_is_uniform_in_range_and_pure() {
        let mut sum = 0.0;
        let n = 100_000;
        for i in 0..n {
            let x = node_random(7, 2, i, 3, 1);
            assert!((-1.0..1.0).contains(&x));
            assert_eq!(x.to_bits(), node_random(7, 2, i, 3, 1).to_bits());
            sum += x;
        }
        assert!((sum / n as f64).abs() < 0.01);
        assert_ne!(node_random(7, 2, 5, 3, 0), node_random(7, 2, 5, 3, 1));
        assert_ne!(node_random(7, 2, 5, 3, 0), node_random(8, 2, 5, 3, 0));
    }

    #[test]
    fn lattice_open_axis_grids_nest_and_end_at_n() {
        for n in 1..100 {
            let levels = AxisLevel::levels(n, false, n + 1);
            assert_eq!(levels.len(), MAX_LEVELS);
            for (l, lev) in levels.iter().enumerate() {
                let h = LEVEL0_SPACING >> l;
                assert_eq!(lev.nodes, n.div_ceil(h) + 1);
                assert!(lev.fixed[0] && lev.fixed[lev.nodes - 1]);
                for (x, cell) in lev.cells.iter().enumerate() {
                    assert!((0.0..=1.0).contains(&cell.t), "n {n} l {l} x {x}");
                    assert_eq!(cell.j1, cell.j0 + 1);
                }
                assert_eq!(lev.cells[n].t, 1.0);
                if l > 0 {
                    // A node is new iff it was not on the previous grid.
                    let prev: Vec<usize> = (0..levels[l - 1].nodes)
                        .map(|j| (j * 2 * h).min(n))
                        .collect();
                    for j in 0..lev.nodes {
                        assert_eq!(lev.fresh[j], !prev.contains(&(j * h).min(n)));
                    }
                }
            }
        }
    }

    #[test]
    fn lattice_cyclic_axis_levels() {
        for n in 1..200 {
            let levels = AxisLevel::levels(n, true, n + 2);
            let k0 = ((n as f64 / 16.0).round() as usize).max(1);
            assert_eq!(levels[0].nodes, k0, "n {n}");
            assert!(!levels.is_empty() && levels.len() <= MAX_LEVELS);
            for (l, lev) in levels.iter().enumerate() {
                assert_eq!(lev.nodes, k0 << l);
                assert!(lev.w_min[0] >= 1.0);
                assert_eq!(lev.cells[n].j0, 0);
                assert_eq!(lev.cells[n].t, 0.0);
            }
            let k_next = k0 << levels.len();
            assert!(levels.len() == MAX_LEVELS || k_next > n, "n {n}");
        }
    }
}
