//! A surface sampled on a regular (u,v) grid: what Blender gives for a NURBS surface
//! evaluated by the depsgraph. Positions are bilinearly interpolated between samples; normals
//! are bilinearly blended and renormalised.

use glam::{Vec2, Vec3, Vec3A};

use super::{Surface, SurfacePoint, UvRect};
use crate::error::{KnitError, Result};

/// A last column (row) of a cyclic grid that lies within this fraction of the surface's size
/// (the diagonal of its bounding box) of the first one is a duplicated seam and is dropped.
/// Blender's cyclic NURBS tessellation repeats the first column; a genuine sample would be
/// many orders of magnitude further away.
const SEAM_TOLERANCE: f32 = 1e-6;

/// One grid sample: position and normal side by side in 32 aligned bytes (SIMD `Vec3A`), so
/// a pair of neighbouring samples fills one cache line and `eval`'s four samples come in two
/// to four lines.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Sample {
    position: Vec3A,
    /// Unit length: fixed at construction (see [`GridSurface::new`]).
    normal: Vec3A,
}

/// A surface sampled on a `rows x cols` grid over the (u,v) domain `[0,1] x [0,1]`, u along
/// columns and v along rows. Positions in scene units, object space.
///
/// Sample `(i, j)` sits at `u_j = j / (cols - 1)`, `v_i = i / (rows - 1)`, or, in a cyclic
/// direction, `u_j = j / cols` (the grid wraps from the last column back to the first).
#[derive(Debug, Clone)]
pub struct GridSurface {
    rows: usize,
    cols: usize,
    samples: Vec<Sample>,
    cyclic_u: bool,
    cyclic_v: bool,
    extent: (f32, f32),
}

impl GridSurface {
    /// Builds a grid surface from row-major `(rows, cols, 3)` buffers:
    /// `positions[(i * cols + j) * 3 ..][..3]` is the point at `(u_j, v_i)` (scene units,
    /// object space), `normals` the normal there (any length; normalised here).
    ///
    /// In a cyclic direction, a last column (row) equal to the first within 1e-6 of the
    /// surface's size (its bounding-box diagonal) is a duplicated seam and is dropped, so
    /// `u_j = j / cols` holds for the remaining columns either way.
    ///
    /// A zero normal (a pole, where the surface pinches to a point) is rebuilt from the
    /// positions by finite differences; where those vanish too, it takes the normalised mean
    /// of the nearest valid normals (nearest in grid steps). No normal is ever NaN.
    ///
    /// Errors ([`KnitError::Surface`]): fewer than 2 x 2 samples, buffer lengths that do not
    /// match, a NaN or infinite value or a position beyond [`super::MAX_COORDINATE`] (named
    /// by its index), or a surface without area (zero length along u or along v).
    pub fn new(
        rows: usize,
        cols: usize,
        positions: &[f32],
        normals: &[f32],
        cyclic_u: bool,
        cyclic_v: bool,
    ) -> Result<Self> {
        if rows < 2 || cols < 2 {
            return Err(KnitError::Surface(format!(
                "a grid surface needs at least 2 x 2 samples, got {rows} x {cols}"
            )));
        }
        let expected = rows
            .checked_mul(cols)
            .and_then(|n| n.checked_mul(3))
            .ok_or_else(|| KnitError::Surface(format!("a {rows} x {cols} grid is too large")))?;
        for (name, buf) in [("positions", positions), ("normals", normals)] {
            if buf.len() != expected {
                return Err(KnitError::Surface(format!(
                    "{name} has {} floats, but a {rows} x {cols} grid needs {expected} \
                     (rows x cols x 3)",
                    buf.len()
                )));
            }
        }
        let sample = |k: usize| format!("(row {}, column {})", k / 3 / cols, k / 3 % cols);
        super::check_coordinates(positions, |k| {
            format!("position of grid sample {}", sample(k))
        })?;
        if let Some(k) = normals.iter().position(|x| !x.is_finite()) {
            return Err(KnitError::Surface(format!(
                "normal of grid sample {} is {} (float index {k})",
                sample(k),
                normals[k]
            )));
        }

        let point = |buf: &[f32], i: usize, j: usize| {
            let k = (i * cols + j) * 3;
            Vec3::new(buf[k], buf[k + 1], buf[k + 2])
        };

        // Size of the surface, for the seam tolerance: the diagonal of its bounding box.
        let (lo, hi) = (0..rows * cols).fold((Vec3::MAX, Vec3::MIN), |(lo, hi), k| {
            let p = point(positions, k / cols, k % cols);
            (lo.min(p), hi.max(p))
        });
        let tolerance = SEAM_TOLERANCE * (hi - lo).length();
        // Keep at least two distinct columns (rows) so interpolation has a cell to work in.
        let drop_u = cyclic_u
            && cols > 2
            && (0..rows).all(|i| {
                point(positions, i, cols - 1).distance(point(positions, i, 0)) <= tolerance
            });
        let drop_v = cyclic_v
            && rows > 2
            && (0..cols).all(|j| {
                point(positions, rows - 1, j).distance(point(positions, 0, j)) <= tolerance
            });
        let kept_cols = cols - usize::from(drop_u);
        let kept_rows = rows - usize::from(drop_v);

        let mut samples = Vec::with_capacity(kept_rows * kept_cols);
        for i in 0..kept_rows {
            for j in 0..kept_cols {
                samples.push(Sample {
                    position: point(positions, i, j).into(),
                    normal: point(normals, i, j).into(),
                });
            }
        }

        let mut grid = GridSurface {
            rows: kept_rows,
            cols: kept_cols,
            samples,
            cyclic_u,
            cyclic_v,
            extent: (0.0, 0.0),
        };
        grid.extent = grid.measure_extent();
        let (eu, ev) = grid.extent;
        if !(eu.is_finite() && ev.is_finite()) {
            return Err(KnitError::Surface(
                "the grid's coordinates are too large to measure (its length overflows)".into(),
            ));
        }
        if eu <= 0.0 || ev <= 0.0 {
            let along = if eu <= 0.0 {
                "u (every row is a single point)"
            } else {
                "v (every column is a single point)"
            };
            return Err(KnitError::Surface(format!(
                "the grid surface has no area: its length along {along} is zero"
            )));
        }
        grid.repair_normals();
        Ok(grid)
    }

    /// Number of sample rows (along v), after a duplicated seam row was dropped.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of sample columns (along u), after a duplicated seam column was dropped.
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// The stored sample at row `i`, column `j` (unit normal), or `None` out of range.
    pub fn sample(&self, i: usize, j: usize) -> Option<SurfacePoint> {
        if i >= self.rows || j >= self.cols {
            return None;
        }
        let s = self.samples[i * self.cols + j];
        Some(SurfacePoint {
            position: s.position.into(),
            normal: s.normal.into(),
        })
    }

    #[inline]
    fn at(&self, i: usize, j: usize) -> &Sample {
        &self.samples[i * self.cols + j]
    }

    /// Index of the neighbour of `k` (in a line of `n` samples) at offset `d` (-1 or +1):
    /// wraps when cyclic, clamps otherwise.
    fn step(k: usize, d: isize, n: usize, cyclic: bool) -> usize {
        let m = k as isize + d;
        if cyclic {
            m.rem_euclid(n as isize) as usize
        } else {
            m.clamp(0, n as isize - 1) as usize
        }
    }

    /// (mean row length along u, mean column length along v), summed in f64 so a million
    /// samples do not lose the last digits.
    fn measure_extent(&self) -> (f32, f32) {
        let (rows, cols) = (self.rows, self.cols);
        let seg = |a: &Sample, b: &Sample| f64::from(a.position.distance(b.position));
        let mut along_u = 0.0f64;
        for i in 0..rows {
            for j in 0..cols - 1 {
                along_u += seg(self.at(i, j), self.at(i, j + 1));
            }
            if self.cyclic_u {
                along_u += seg(self.at(i, cols - 1), self.at(i, 0));
            }
        }
        let mut along_v = 0.0f64;
        for j in 0..cols {
            for i in 0..rows - 1 {
                along_v += seg(self.at(i, j), self.at(i + 1, j));
            }
            if self.cyclic_v {
                along_v += seg(self.at(rows - 1, j), self.at(0, j));
            }
        }
        (
            (along_u / rows as f64) as f32,
            (along_v / cols as f64) as f32,
        )
    }

    /// Makes every normal unit length. Given normals are normalised; a degenerate one (zero,
    /// as Blender reports at a pole) is rebuilt from central differences of the positions,
    /// oriented like the valid normals around it; where the positions pinch too, it is the
    /// normalised mean of the nearest valid normals (grown outwards in grid steps); +Z only
    /// if the whole grid has no normal at all (a surface that is a line).
    fn repair_normals(&mut self) {
        let (rows, cols, cu, cv) = (self.rows, self.cols, self.cyclic_u, self.cyclic_v);
        let given: Vec<Option<Vec3>> = self
            .samples
            .iter()
            .map(|s| Vec3::from(s.normal).try_normalize())
            .collect();
        if given.iter().all(Option::is_some) {
            for (s, n) in self.samples.iter_mut().zip(&given) {
                s.normal = n.unwrap_or(Vec3::Z).into();
            }
            return;
        }

        // Pass 1: finite differences where the given normal is degenerate.
        let mut first: Vec<Option<Vec3>> = given.clone();
        for i in 0..rows {
            for j in 0..cols {
                let k = i * cols + j;
                if given[k].is_some() {
                    continue;
                }
                let p = |i: usize, j: usize| Vec3::from(self.at(i, j).position);
                let du = p(i, Self::step(j, 1, cols, cu)) - p(i, Self::step(j, -1, cols, cu));
                let dv = p(Self::step(i, 1, rows, cv), j) - p(Self::step(i, -1, rows, cv), j);
                if let Some(n) = du.cross(dv).try_normalize() {
                    // Orient like the given normals around it (the grid's own convention).
                    let mut around = Vec3::ZERO;
                    for di in -1..=1 {
                        for dj in -1..=1 {
                            let (a, b) = (Self::step(i, di, rows, cv), Self::step(j, dj, cols, cu));
                            around += given[a * cols + b].unwrap_or(Vec3::ZERO);
                        }
                    }
                    first[k] = Some(if n.dot(around) < 0.0 { -n } else { n });
                }
            }
        }

        // Pass 2: where the positions pinch too (a pole), grow the valid normals outwards one
        // grid step (8-neighbourhood) per layer: each sample takes the normalised mean of its
        // neighbours valid before this layer (the first of them if the mean cancels). Layers
        // are applied whole, so the result does not depend on visiting order; O(samples).
        let mut normals = first;
        let neighbours = |k: usize| {
            let (i, j) = (k / cols, k % cols);
            (-1isize..=1).flat_map(move |di| {
                (-1isize..=1).filter_map(move |dj| {
                    let a = i as isize + di;
                    let b = j as isize + dj;
                    let a = if cv { a.rem_euclid(rows as isize) } else { a };
                    let b = if cu { b.rem_euclid(cols as isize) } else { b };
                    let inside = (0..rows as isize).contains(&a) && (0..cols as isize).contains(&b);
                    (inside && (di, dj) != (0, 0)).then(|| a as usize * cols + b as usize)
                })
            })
        };
        let mut layer: Vec<usize> = (0..rows * cols)
            .filter(|&k| normals[k].is_none() && neighbours(k).any(|m| normals[m].is_some()))
            .collect();
        while !layer.is_empty() {
            let grown: Vec<(usize, Vec3)> = layer
                .iter()
                .map(|&k| {
                    let valid = neighbours(k).filter_map(|m| normals[m]);
                    let (sum, first) = valid.fold((Vec3::ZERO, None), |(sum, first), n| {
                        (sum + n, first.or(Some(n)))
                    });
                    (k, sum.try_normalize().or(first).unwrap_or(Vec3::Z))
                })
                .collect();
            for &(k, n) in &grown {
                normals[k] = Some(n);
            }
            layer = grown
                .iter()
                .flat_map(|&(k, _)| neighbours(k))
                .filter(|&m| normals[m].is_none())
                .collect();
            layer.sort_unstable();
            layer.dedup();
        }
        // None left only if nothing had a normal: a grid whose points all lie on a line.
        for (s, n) in self.samples.iter_mut().zip(normals) {
            s.normal = n.unwrap_or(Vec3::Z).into();
        }
    }
}

/// Where parameter `x` falls in a line of `n` samples: the two samples around it and the
/// blend weight of the second, in `[0, 1]`. Cyclic lines wrap (`u_j = j / n`); others clamp
/// (`u_j = j / (n - 1)`). A NaN or infinite `x` reads as 0, so `eval` never panics or
/// indexes out of range.
#[inline]
fn locate(x: f32, n: usize, cyclic: bool) -> (usize, usize, f32) {
    let x = if x.is_finite() { x } else { 0.0 };
    if cyclic {
        // In [0, 1]: exactly 1 for tiny negative x, which lands on the last cell with t = 1.
        let s = (x - x.floor()) * n as f32;
        let i0 = (s as usize).min(n - 1);
        let i1 = if i0 + 1 == n { 0 } else { i0 + 1 };
        (i0, i1, (s - i0 as f32).clamp(0.0, 1.0))
    } else {
        let s = x.clamp(0.0, 1.0) * (n - 1) as f32;
        let i0 = (s as usize).min(n - 2);
        (i0, i0 + 1, (s - i0 as f32).clamp(0.0, 1.0))
    }
}

impl Surface for GridSurface {
    fn domain(&self) -> UvRect {
        UvRect {
            min: Vec2::ZERO,
            max: Vec2::ONE,
        }
    }

    fn cyclic_u(&self) -> bool {
        self.cyclic_u
    }

    fn cyclic_v(&self) -> bool {
        self.cyclic_v
    }

    /// Always `Some`: a grid covers its whole domain (clamped outside it when not cyclic).
    #[inline]
    fn eval(&self, uv: Vec2) -> Option<SurfacePoint> {
        Some(self.eval_nearest(uv))
    }

    #[inline]
    fn eval_nearest(&self, uv: Vec2) -> SurfacePoint {
        let (j0, j1, tu) = locate(uv.x, self.cols, self.cyclic_u);
        let (i0, i1, tv) = locate(uv.y, self.rows, self.cyclic_v);
        let (s00, s01) = (self.at(i0, j0), self.at(i0, j1));
        let (s10, s11) = (self.at(i1, j0), self.at(i1, j1));
        let position = s00
            .position
            .lerp(s01.position, tu)
            .lerp(s10.position.lerp(s11.position, tu), tv);
        let blend = s00
            .normal
            .lerp(s01.normal, tu)
            .lerp(s10.normal.lerp(s11.normal, tu), tv);
        // Opposite normals across a cell (a fold) can cancel: take the nearest sample's.
        let normal = blend.try_normalize().unwrap_or_else(|| {
            let row = if tv < 0.5 { (s00, s01) } else { (s10, s11) };
            if tu < 0.5 {
                row.0.normal
            } else {
                row.1.normal
            }
        });
        SurfacePoint {
            position: position.into(),
            normal: normal.into(),
        }
    }

    /// (mean over rows of the polyline length along u, mean over columns of the polyline
    /// length along v), scene units; the wrap segment counts in a cyclic direction.
    fn extent(&self) -> (f32, f32) {
        self.extent
    }
}
