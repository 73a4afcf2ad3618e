//! A triangle mesh with a UV map: (u,v) is the UV map, located through a uniform grid index
//! over the UV triangles (docs/design.md section 2). A (u,v) outside every UV island has no
//! surface.

use glam::{DVec3, Vec2, Vec3};

use super::pole_fans::{pole_fillers, FanTriangle};
use super::uv_seams::{closed_seams, SeamTriangle};
use super::{Surface, SurfacePoint, UvRect};
use crate::error::{KnitError, Result};

/// Barycentric tolerance of the point-in-triangle test: a (u,v) at most this far outside a
/// triangle, in barycentric units (fractions of the triangle's size), still counts as inside.
/// Points exactly on an edge shared by two triangles can round to just outside both; this
/// finds them. The barycentrics are then clamped, so the result lies on the triangle.
const BARYCENTRIC_TOLERANCE: f32 = 1e-5;

/// A UV triangle whose doubled area is at most this fraction of its longest edge squared
/// (a sliver thinner than about 1e-7 of its length) has no usable inverse in f32 and is
/// ignored by lookups: a degenerate UV triangle.
const DEGENERATE_UV_RATIO: f64 = 1e-7;

/// Lookup triangles per index cell the index aims for. Each triangle's box overlaps a few
/// cells, so a cell holds several candidates; 1 measured faster than 2 or 4 on a 100k mesh.
const TRIANGLES_PER_CELL: f64 = 1.0;
/// Most cells along one axis of the index (a very elongated UV map still gets a sane grid).
const MAX_CELLS_PER_AXIS: usize = 8192;

/// The affine map from (u,v) to the barycentrics `(l1, l2)` of one UV triangle:
/// `(l1, l2) = inv * (uv - origin)`, `l0 = 1 - l1 - l2`. The only data the point-in-triangle
/// test reads, packed into 24 bytes.
#[derive(Debug, Clone, Copy)]
struct BaryMap {
    origin: Vec2,
    /// Row-major inverse of the 2x2 matrix whose columns are the UV edges `uv1 - uv0`,
    /// `uv2 - uv0`.
    inv: [f32; 4],
}

impl BaryMap {
    /// The map of the UV triangle `uv`, with the inverse (row-major, f64) and the determinant
    /// of its edge matrix; `None` for a degenerate UV triangle ([`DEGENERATE_UV_RATIO`]).
    fn of(uv: [Vec2; 3]) -> Option<(Self, [f64; 4], f64)> {
        let [a, b, c] = uv.map(|p| p.as_dvec2());
        let (e1, e2) = (b - a, c - a);
        let det = e1.perp_dot(e2);
        let longest = e1
            .length_squared()
            .max(e2.length_squared())
            .max((c - b).length_squared());
        if det.abs() <= DEGENERATE_UV_RATIO * longest || !det.is_normal() {
            return None;
        }
        let inv = [e2.y / det, -e2.x / det, -e1.y / det, e1.x / det];
        let map = BaryMap {
            origin: uv[0],
            inv: inv.map(|x| x as f32),
        };
        Some((map, inv, det))
    }

    #[inline]
    fn barycentrics(&self, uv: Vec2) -> [f32; 3] {
        let d = uv - self.origin;
        let l1 = self.inv[0] * d.x + self.inv[1] * d.y;
        let l2 = self.inv[2] * d.x + self.inv[3] * d.y;
        [1.0 - l1 - l2, l1, l2]
    }
}

/// Corner positions and unit normals (or zero) of a lookup triangle, copied out of the
/// vertex arrays so interpolation touches one 72-byte record rather than six scattered ones.
#[derive(Debug, Clone, Copy)]
struct Corners {
    position: [Vec3; 3],
    normal: [Vec3; 3],
}

/// The rest of a lookup triangle (read rarely: nearest-point search, fallback normals).
#[derive(Debug, Clone, Copy)]
struct LookupTri {
    /// Index of the triangle in the input buffers (of a pole fan's filler: the first tooth it
    /// joins).
    index: u32,
    uv: [Vec2; 3],
    /// Unit normal used where the interpolated vertex normals cancel: the geometric normal
    /// oriented like the vertex normals (or their mean, for a triangle of zero 3D area).
    fallback_normal: Vec3,
}

/// A triangle mesh with per-corner UVs as a surface over its UV map. Positions in scene
/// units, object space; the (u,v) domain is the bounding rectangle of the UV triangles that
/// have area.
#[derive(Debug, Clone)]
pub struct MeshSurface {
    vertex_count: usize,
    triangle_count: usize,
    /// Triangles with UV area ("lookup triangles"), in input order (ascending
    /// `LookupTri::index`), then the fillers that close the gaps of pole fans
    /// ([`super::pole_fans`]); the three arrays are parallel. Hot data (what a lookup and an
    /// interpolation read) apart from cold: 136 bytes per triangle, plus about 24 in the
    /// index.
    bary: Vec<BaryMap>,
    corners: Vec<Corners>,
    tris: Vec<LookupTri>,
    domain: UvRect,
    /// Whether the UV map closes round along u and along v ([`super::uv_seams`]): lookups
    /// then take a (u,v) beyond the domain back into it by whole widths.
    cyclic: (bool, bool),
    extent: (f32, f32),
    /// The uniform grid over `domain`: `nx x ny` cells, row-major; cell `c` holds the lookup
    /// triangles `cell_tris[cell_start[c]..cell_start[c + 1]]`, ascending.
    nx: usize,
    ny: usize,
    /// Cells per unit of u and of v.
    cells_per_uv: Vec2,
    cell_start: Vec<u32>,
    cell_tris: Vec<u32>,
    /// How far outside a triangle (in UV units) a point may be and still be found: the
    /// barycentric tolerance of the largest triangle, at most.
    uv_tolerance: f32,
}

impl MeshSurface {
    /// Builds the surface from flat buffers: `positions` and `normals` are `(N, 3)` (scene
    /// units, object space; normals of any length), `triangles` is `(M, 3)` vertex indices,
    /// `uvs` is `(M, 3, 2)`, one (u,v) per triangle corner (Blender's per-loop UV layer).
    ///
    /// Triangles with (near-)zero UV area are kept out of lookups (degenerate UVs: they
    /// cover no (u,v)); triangles with zero 3D area are kept (they map their UV area to a
    /// point or a line).
    ///
    /// Errors ([`KnitError::Surface`]): lengths that do not match, an index out of range, a
    /// NaN or infinite value or a position or UV beyond [`super::MAX_COORDINATE`] (named by
    /// vertex or by triangle and corner), or no triangle with UV area.
    pub fn new(positions: &[f32], normals: &[f32], triangles: &[u32], uvs: &[f32]) -> Result<Self> {
        let bad = |msg: String| Err(KnitError::Surface(msg));
        if positions.len() % 3 != 0 {
            return bad(format!(
                "positions has {} floats, not a multiple of 3",
                positions.len()
            ));
        }
        if normals.len() != positions.len() {
            return bad(format!(
                "normals has {} floats but positions has {}: one normal per vertex",
                normals.len(),
                positions.len()
            ));
        }
        if triangles.len() % 3 != 0 {
            return bad(format!(
                "triangles has {} indices, not a multiple of 3",
                triangles.len()
            ));
        }
        let m = triangles.len() / 3;
        if m == 0 {
            return bad("the mesh has no triangles".into());
        }
        if u32::try_from(m).is_err() {
            return bad(format!(
                "the mesh has {m} triangles; at most {} are supported",
                u32::MAX
            ));
        }
        if uvs.len() != m * 6 {
            return bad(format!(
                "uvs has {} floats, but {m} triangles need {} (3 corners x 2)",
                uvs.len(),
                m * 6
            ));
        }
        let n = positions.len() / 3;
        super::check_coordinates(positions, |k| format!("position of vertex {}", k / 3))?;
        if let Some(k) = normals.iter().position(|x| !x.is_finite()) {
            return bad(format!(
                "normal of vertex {} is {} (float index {k})",
                k / 3,
                normals[k]
            ));
        }
        super::check_coordinates(uvs, |k| {
            format!("UV of triangle {} corner {}", k / 6, k / 2 % 3)
        })?;
        if let Some(k) = triangles.iter().position(|&i| i as usize >= n) {
            return bad(format!(
                "triangle {} corner {} refers to vertex {}, but the mesh has {n} vertices",
                k / 3,
                k % 3,
                triangles[k]
            ));
        }

        let positions: Vec<Vec3> = positions.chunks_exact(3).map(Vec3::from_slice).collect();
        let normals: Vec<Vec3> = normals
            .chunks_exact(3)
            .map(|c| Vec3::from_slice(c).try_normalize().unwrap_or(Vec3::ZERO))
            .collect();
        // Last resort for a triangle with no 3D area and no vertex normal.
        let mesh_normal = normals
            .iter()
            .sum::<Vec3>()
            .try_normalize()
            .unwrap_or(Vec3::Z);

        let mut bary = Vec::new();
        let mut tris = Vec::new();
        let mut fan = Vec::new();
        let mut corners = Vec::new();
        let (mut lo, mut hi) = (Vec2::MAX, Vec2::MIN);
        // Extent: UV-area-weighted sums of |ds/du| and |ds/dv| (docs/design.md section 2: gauge
        // is measured on the surface).
        let (mut weight, mut sum_du, mut sum_dv) = (0.0f64, 0.0f64, 0.0f64);
        for t in 0..m {
            let vertices = [triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]];
            let uv = [0, 1, 2].map(|c| Vec2::new(uvs[6 * t + 2 * c], uvs[6 * t + 2 * c + 1]));
            let Some((map, inv, det)) = BaryMap::of(uv) else {
                continue;
            };
            bary.push(map);

            let p = vertices.map(|i| positions[i as usize]);
            let vn = vertices.map(|i| normals[i as usize]);
            let vsum = vn[0] + vn[1] + vn[2];
            let fallback_normal = match (p[1] - p[0]).cross(p[2] - p[0]).try_normalize() {
                Some(g) if g.dot(vsum) < 0.0 => -g,
                Some(g) => g,
                None => vsum.try_normalize().unwrap_or(mesh_normal),
            };
            tris.push(LookupTri {
                index: t as u32,
                uv,
                fallback_normal,
            });
            fan.push(FanTriangle {
                index: t as u32,
                vertices,
                uv,
            });
            corners.push(Corners {
                position: p,
                normal: vn,
            });
            lo = lo.min(uv[0].min(uv[1]).min(uv[2]));
            hi = hi.max(uv[0].max(uv[1]).max(uv[2]));

            // Jacobian of (u,v) -> position: ds/du and ds/dv are the columns of
            // [P1 - P0, P2 - P0] * inverse([e1 e2]).
            let [p0, p1, p2] = p.map(|q| q.as_dvec3());
            let (f1, f2): (DVec3, DVec3) = (p1 - p0, p2 - p0);
            let ds_du = f1 * inv[0] + f2 * inv[2];
            let ds_dv = f1 * inv[1] + f2 * inv[3];
            let w = 0.5 * det.abs();
            weight += w;
            sum_du += w * ds_du.length();
            sum_dv += w * ds_dv.length();
        }
        if tris.is_empty() {
            return bad(format!(
                "none of the {m} triangles has any UV area: give the mesh a UV map \
                 (UV > Unwrap) first"
            ));
        }
        let domain = UvRect { min: lo, max: hi };
        let seam_triangles: Vec<SeamTriangle> = fan
            .iter()
            .map(|f| SeamTriangle {
                vertices: f.vertices,
                uv: f.uv,
            })
            .collect();
        let cyclic = closed_seams(&seam_triangles, &positions, domain);
        // The gaps between a pole fan's teeth (`super::pole_fans`), after every triangle of
        // the mesh, so that where one overlaps a triangle of the mesh the triangle wins. They
        // lie inside the domain and take no part in the extent: they map their UV area onto
        // an edge of the mesh.
        for f in pole_fillers(&fan, domain, cyclic) {
            let Some((map, _, _)) = BaryMap::of(f.uv) else {
                continue;
            };
            bary.push(map);
            let vn = f.vertices.map(|i| normals[i as usize]);
            tris.push(LookupTri {
                index: f.extends,
                uv: f.uv,
                fallback_normal: (vn[0] + vn[1] + vn[2])
                    .try_normalize()
                    .unwrap_or(mesh_normal),
            });
            corners.push(Corners {
                position: f.vertices.map(|i| positions[i as usize]),
                normal: vn,
            });
        }
        let size = domain.size();
        let extent = (
            (sum_du / weight * f64::from(size.x)) as f32,
            (sum_dv / weight * f64::from(size.y)) as f32,
        );
        if !(extent.0.is_finite() && extent.1.is_finite()) {
            return bad(
                "the mesh's coordinates are too large to measure (its length overflows)".into(),
            );
        }
        if extent.0 <= 0.0 || extent.1 <= 0.0 {
            let along = if extent.0 <= 0.0 { "u" } else { "v" };
            return bad(format!(
                "the mesh has no area: its length along {along} is zero (every UV triangle \
                 maps to a point or a line)"
            ));
        }

        let mut surface = MeshSurface {
            vertex_count: n,
            triangle_count: m,
            bary,
            corners,
            tris,
            domain,
            cyclic,
            extent,
            nx: 1,
            ny: 1,
            cells_per_uv: Vec2::ONE,
            cell_start: Vec::new(),
            cell_tris: Vec::new(),
            uv_tolerance: BARYCENTRIC_TOLERANCE * size.max_element(),
        };
        surface.build_index();
        Ok(surface)
    }

    /// Number of triangles given (including those with degenerate UVs).
    pub fn triangle_count(&self) -> usize {
        self.triangle_count
    }

    /// Number of triangles with UV area: those a (u,v) can be found in.
    pub fn uv_triangle_count(&self) -> usize {
        self.tris.len()
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// Cells of the UV index along u and v.
    pub fn index_cells(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The input index of the triangle `eval` takes `uv` from, or `None` where `eval` is
    /// `None`. Among triangles containing `uv` (overlapping UV islands) the lowest index wins;
    /// a triangle containing it exactly beats one containing it only within the tolerance
    /// (1e-5 in barycentric units) that finds points on shared edges.
    pub fn locate(&self, uv: Vec2) -> Option<usize> {
        self.find(uv).map(|(k, _)| self.tris[k].index as usize)
    }

    /// The closest point (in UV) to `uv` of all triangles with UV area, and the input index of
    /// its triangle: `uv` itself where `eval` finds it; otherwise what `eval_nearest` evaluates
    /// (lowest index on ties). `None` only for a NaN `uv`.
    pub fn nearest_uv(&self, uv: Vec2) -> Option<(Vec2, usize)> {
        if uv.is_nan() {
            return None;
        }
        if let Some(k) = self.locate(uv) {
            return Some((uv, k));
        }
        let (k, l) = self.nearest(self.clamp_far(uv));
        let t = &self.tris[k];
        Some((
            t.uv[0] * l[0] + t.uv[1] * l[1] + t.uv[2] * l[2],
            t.index as usize,
        ))
    }

    /// `uv` with NaN coordinates moved to the middle of the domain and coordinates further
    /// than 1000 domain sizes outside it clamped there (so squared UV distances stay finite).
    fn clamp_far(&self, uv: Vec2) -> Vec2 {
        let (lo, hi) = (self.domain.min, self.domain.max);
        let reach = 1000.0 * self.domain.size().max_element();
        let centre = (lo + hi) * 0.5;
        let fix = |x: f32, c: f32, a: f32, b: f32| {
            if x.is_nan() {
                c
            } else {
                x.clamp(a - reach, b + reach)
            }
        };
        Vec2::new(
            fix(uv.x, centre.x, lo.x, hi.x),
            fix(uv.y, centre.y, lo.y, hi.y),
        )
    }

    /// `uv` taken back into the domain by whole widths along each axis that closes round (a
    /// coordinate already inside, or not finite, is left as it is).
    #[inline]
    fn wrap(&self, uv: Vec2) -> Vec2 {
        let (lo, hi) = (self.domain.min, self.domain.max);
        let back = |x: f32, lo: f32, hi: f32, cyclic: bool| {
            if cyclic && x.is_finite() && (x < lo || x > hi) {
                lo + (x - lo).rem_euclid(hi - lo)
            } else {
                x
            }
        };
        Vec2::new(
            back(uv.x, lo.x, hi.x, self.cyclic.0),
            back(uv.y, lo.y, hi.y, self.cyclic.1),
        )
    }

    /// Chooses the index grid: about [`TRIANGLES_PER_CELL`] triangles per cell over the UV
    /// bounding box, coarsened while triangles spanning many cells would make the index larger
    /// than a fixed multiple of the triangle count (huge overlapping triangles).
    fn build_index(&mut self) {
        let count = self.tris.len();
        let size = self.domain.size().as_dvec2();
        let cells = (count as f64 / TRIANGLES_PER_CELL).max(1.0);
        let cell = (size.x * size.y / cells).sqrt();
        let axis = |len: f64| ((len / cell).ceil() as usize).clamp(1, MAX_CELLS_PER_AXIS);
        let (mut nx, mut ny) = (axis(size.x), axis(size.y));
        // An elongated box can give many more cells than triangles: bound the total.
        while nx * ny > 4 * count + 16 {
            nx = nx.div_ceil(2);
            ny = ny.div_ceil(2);
        }
        let budget = 16 * count + 1024;
        loop {
            self.nx = nx;
            self.ny = ny;
            self.cells_per_uv = Vec2::new(nx as f32 / size.x as f32, ny as f32 / size.y as f32);
            let total: usize = (0..count)
                .map(|k| {
                    let (x0, y0, x1, y1) = self.cell_range(k);
                    (x1 - x0 + 1) * (y1 - y0 + 1)
                })
                .sum();
            // A 1 x 1 grid holds each triangle once, which always fits (checked in `new`).
            if (total <= budget && u32::try_from(total).is_ok()) || (nx == 1 && ny == 1) {
                break;
            }
            nx = nx.div_ceil(2);
            ny = ny.div_ceil(2);
        }
        // Counting sort into CSR, triangles in ascending order within each cell.
        let mut start = vec![0u32; nx * ny + 1];
        for k in 0..count {
            let (x0, y0, x1, y1) = self.cell_range(k);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    start[y * nx + x + 1] += 1;
                }
            }
        }
        for c in 0..nx * ny {
            start[c + 1] += start[c];
        }
        let mut fill = start.clone();
        let mut entries = vec![0u32; start[nx * ny] as usize];
        for k in 0..count {
            let (x0, y0, x1, y1) = self.cell_range(k);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let slot = &mut fill[y * nx + x];
                    entries[*slot as usize] = k as u32;
                    *slot += 1;
                }
            }
        }
        self.cell_start = start;
        self.cell_tris = entries;
    }

    /// The cells (inclusive ranges) overlapped by lookup triangle `k`'s UV box, grown by the
    /// lookup tolerance so points on its edges are found from the neighbouring cell too.
    fn cell_range(&self, k: usize) -> (usize, usize, usize, usize) {
        let [a, b, c] = self.tris[k].uv;
        let grow = Vec2::splat(self.uv_tolerance);
        let (x0, y0) = self.cell_of(a.min(b).min(c) - grow);
        let (x1, y1) = self.cell_of(a.max(b).max(c) + grow);
        (x0, y0, x1, y1)
    }

    /// The index cell of `uv`, clamped into the grid (NaN reads as the first cell).
    #[inline]
    fn cell_of(&self, uv: Vec2) -> (usize, usize) {
        let g = (uv - self.domain.min) * self.cells_per_uv;
        // `max` maps NaN to 0; the float-to-int cast saturates.
        let x = (g.x.max(0.0) as usize).min(self.nx - 1);
        let y = (g.y.max(0.0) as usize).min(self.ny - 1);
        (x, y)
    }

    #[inline]
    fn cell(&self, x: usize, y: usize) -> &[u32] {
        let c = y * self.nx + x;
        &self.cell_tris[self.cell_start[c] as usize..self.cell_start[c + 1] as usize]
    }

    /// The lookup triangle containing `uv` and its barycentrics (see [`MeshSurface::locate`]).
    #[inline]
    fn find(&self, uv: Vec2) -> Option<(usize, [f32; 3])> {
        let uv = self.wrap(uv);
        let (lo, hi) = (self.domain.min, self.domain.max);
        let tol = self.uv_tolerance;
        // Also rejects NaN.
        if !(uv.x >= lo.x - tol && uv.x <= hi.x + tol && uv.y >= lo.y - tol && uv.y <= hi.y + tol) {
            return None;
        }
        let (x, y) = self.cell_of(uv);
        let mut within_tolerance = None;
        for &k in self.cell(x, y) {
            let k = k as usize;
            let l = self.bary[k].barycentrics(uv);
            let worst = l[0].min(l[1]).min(l[2]);
            if worst >= 0.0 {
                // Cells list triangles in ascending order: the first exact hit is the lowest.
                return Some((k, l));
            }
            if worst >= -BARYCENTRIC_TOLERANCE && within_tolerance.is_none() {
                within_tolerance = Some((k, l));
            }
        }
        within_tolerance
    }

    /// Position and normal at barycentrics `l` (clamped onto the triangle) of lookup
    /// triangle `k`.
    #[inline]
    fn interpolate(&self, k: usize, l: [f32; 3]) -> SurfacePoint {
        let l = l.map(|x| x.max(0.0));
        // The clamped weights sum to at least 1 (only negative ones were raised).
        let sum = l[0] + l[1] + l[2];
        let l = l.map(|x| x / sum);
        let Corners {
            position: p,
            normal: n,
        } = &self.corners[k];
        let position = p[0] * l[0] + p[1] * l[1] + p[2] * l[2];
        let normal = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2])
            .try_normalize()
            .unwrap_or_else(|| self.tris[k].fallback_normal);
        SurfacePoint { position, normal }
    }

    /// The closest point (in UV) of all lookup triangles to `uv`: the triangle (lowest index
    /// on ties) and the barycentrics of that point. Searches the index in square rings of
    /// cells around `uv`, stopping once no unvisited cell can hold anything closer; at most
    /// the whole grid.
    fn nearest(&self, uv: Vec2) -> (usize, [f32; 3]) {
        let uv = self.wrap(uv);
        let (cx, cy) = self.cell_of(uv);
        let (nx, ny) = (self.nx as isize, self.ny as isize);
        let (cx, cy) = (cx as isize, cy as isize);
        let cell_size = Vec2::ONE / self.cells_per_uv;
        let mut best: Option<(f32, usize, [f32; 3])> = None;
        for r in 0..=nx.max(ny) {
            let (x0, x1, y0, y1) = (cx - r, cx + r, cy - r, cy + r);
            for y in y0.max(0)..=y1.min(ny - 1) {
                // Rows strictly inside the square only add its left and right cells.
                let (row, step) = if y == y0 || y == y1 {
                    (x0..=x1, 1)
                } else {
                    (x0..=x1, (2 * r).max(1))
                };
                for x in row.step_by(step as usize) {
                    if x < 0 || x >= nx {
                        continue;
                    }
                    for &k in self.cell(x as usize, y as usize) {
                        let k = k as usize;
                        let (d2, l) = closest_on_triangle(&self.tris[k].uv, &self.bary[k], uv);
                        let better = match best {
                            None => true,
                            Some((bd, bk, _)) => d2 < bd || (d2 == bd && k < bk),
                        };
                        if better {
                            best = Some((d2, k, l));
                        }
                    }
                }
            }
            // Every unvisited cell lies beyond one of the square's open sides, inside the
            // grid: the squared distance to such a strip counts the along-axis gap and how far
            // `uv` lies outside the grid across it (large for a `uv` off the domain).
            let (lo, hi) = (self.domain.min, self.domain.max);
            let outside = |x: f32, a: f32, b: f32| (a - x).max(x - b).max(0.0);
            let (off_x, off_y) = (outside(uv.x, lo.x, hi.x), outside(uv.y, lo.y, hi.y));
            let strip = |gap: f32, across: f32| gap.max(0.0).powi(2) + across * across;
            let mut bound2 = f32::INFINITY;
            if x0 > 0 {
                bound2 = bound2.min(strip(uv.x - (lo.x + x0 as f32 * cell_size.x), off_y));
            }
            if x1 < nx - 1 {
                bound2 = bound2.min(strip(lo.x + (x1 + 1) as f32 * cell_size.x - uv.x, off_y));
            }
            if y0 > 0 {
                bound2 = bound2.min(strip(uv.y - (lo.y + y0 as f32 * cell_size.y), off_x));
            }
            if y1 < ny - 1 {
                bound2 = bound2.min(strip(lo.y + (y1 + 1) as f32 * cell_size.y - uv.y, off_x));
            }
            if bound2 == f32::INFINITY {
                break;
            }
            if best.is_some_and(|(d2, _, _)| d2 <= bound2) {
                break;
            }
        }
        // The full sweep visits every cell, and every lookup triangle is in some cell.
        let (_, k, l) = best.unwrap_or((0.0, 0, [1.0, 0.0, 0.0]));
        (k, l)
    }
}

/// Squared UV distance from `p` to triangle `uv` and the barycentrics of the closest point.
fn closest_on_triangle(uv: &[Vec2; 3], map: &BaryMap, p: Vec2) -> (f32, [f32; 3]) {
    let l = map.barycentrics(p);
    if l[0] >= 0.0 && l[1] >= 0.0 && l[2] >= 0.0 {
        return (0.0, l);
    }
    let mut best = (f32::INFINITY, [1.0, 0.0, 0.0]);
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let (a, b) = (uv[i], uv[j]);
        let e = b - a;
        let len2 = e.length_squared();
        let t = if len2 > 0.0 {
            ((p - a).dot(e) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let d2 = (a + e * t - p).length_squared();
        if d2 < best.0 {
            let mut w = [0.0; 3];
            w[i] = 1.0 - t;
            w[j] = t;
            best = (d2, w);
        }
    }
    best
}

impl Surface for MeshSurface {
    /// The bounding rectangle of the UV triangles that have area.
    fn domain(&self) -> UvRect {
        self.domain
    }

    fn cyclic_u(&self) -> bool {
        self.cyclic.0
    }

    fn cyclic_v(&self) -> bool {
        self.cyclic.1
    }

    #[inline]
    fn eval(&self, uv: Vec2) -> Option<SurfacePoint> {
        self.find(uv).map(|(k, l)| self.interpolate(k, l))
    }

    /// `eval`, or where that is `None`, the value at the closest point (in UV) of the closest
    /// UV triangle. A NaN coordinate reads as the middle of the domain; a coordinate further
    /// than 1000 domain sizes outside is clamped there first (so squared UV distances stay
    /// finite).
    fn eval_nearest(&self, uv: Vec2) -> SurfacePoint {
        if let Some(p) = self.eval(uv) {
            return p;
        }
        let (k, l) = self.nearest(self.clamp_far(uv));
        self.interpolate(k, l)
    }

    /// UV-area-weighted mean of |ds/du| over the triangles with UV area, times the domain
    /// width; likewise for v (scene units). Exact for an affinely mapped plane; for a curved
    /// surface, the mean length of the u (v) iso-lines across the domain.
    fn extent(&self) -> (f32, f32) {
        self.extent
    }
}
