//! UV seams that close the surface round on itself: a tube knitted in the round.
//!
//! A tube (a sleeve, a torso, the side of a cylinder, a UV sphere) unwraps to a strip with a
//! seam: the edges along one side of the strip are, in 3D, the very edges along the other
//! side. Blender keeps one vertex there and gives it two (u,v), one per side; other tools
//! double the vertex at the same position. Either way nothing in the UV map says that a
//! course reaching the strip's right side runs on at its left, and a surface that did not
//! know it would knit the tube flat, as a sheet whose two selvages meet at the seam: a gap of
//! about a stitch column, a dark line down the sleeve.
//!
//! A UV map closes round along u when its seam is the bounding box's pair of vertical sides:
//! every UV edge lying along `u = min` has a twin along `u = max` at the same v whose ends
//! are the same 3D points, and the other way round. Then `eval(u + width, v) == eval(u, v)`
//! holds (the surface's cyclic contract) and the knit runs its courses round the tube with no
//! column lost. Likewise along v (a torus closes both ways). A seam that is not a pure shift
//! by the box's width (an island packed at an angle, or one of several islands) stays open:
//! that is the work of per-island stitch grids.

use glam::{Vec2, Vec3};

use super::UvRect;

/// How far (as a fraction of the UV box's size along the axis) a UV corner may lie off a side
/// of the box and still be on it, and how far the twins' other coordinates may differ.
/// Unwrapping writes seams at exactly 0 and 1; packing rescales them with rounding.
pub(super) const UV_TOLERANCE: f32 = 1e-5;

/// How far apart (as a fraction of the mesh's size) two ends of twin edges may lie in 3D and
/// still be one point: a mesh split at its seam (doubled vertices) keeps their positions to
/// within rounding.
const POSITION_TOLERANCE: f32 = 1e-5;

/// A UV triangle of the mesh: its vertices and their (u,v) in it.
#[derive(Debug, Clone, Copy)]
pub(super) struct SeamTriangle {
    pub vertices: [u32; 3],
    pub uv: [Vec2; 3],
}

/// Whether the UV map closes round along u and along v (see the module docs). `triangles`
/// are those with UV area, `positions` the mesh's vertices, `domain` their UV box.
pub(super) fn closed_seams(
    triangles: &[SeamTriangle],
    positions: &[Vec3],
    domain: UvRect,
) -> (bool, bool) {
    let (lo, hi) = positions
        .iter()
        .fold((Vec3::MAX, Vec3::MIN), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    let reach = POSITION_TOLERANCE * (hi - lo).max_element().max(f32::MIN_POSITIVE);
    (
        closes(triangles, positions, domain, 0, reach),
        closes(triangles, positions, domain, 1, reach),
    )
}

/// One side's edge: its ends' coordinates along the side (ascending) and 3D positions.
type SideEdge = ([f32; 2], [Vec3; 2]);

/// Whether the sides of `domain` across `axis` (0: the sides `u = min`, `u = max`) are one
/// seam (module docs); `reach` is how far apart twin ends may lie in 3D.
fn closes(
    triangles: &[SeamTriangle],
    positions: &[Vec3],
    domain: UvRect,
    axis: usize,
    reach: f32,
) -> bool {
    let along = 1 - axis;
    let (lo, hi) = (domain.min[axis], domain.max[axis]);
    let size = domain.size();
    let (off, across) = (UV_TOLERANCE * size[axis], UV_TOLERANCE * size[along]);
    let mut sides: [Vec<SideEdge>; 2] = [Vec::new(), Vec::new()];
    for t in triangles {
        for (i, j) in [(0, 1), (1, 2), (2, 0)] {
            let (a, b) = (t.uv[i], t.uv[j]);
            for (side, line) in [lo, hi].into_iter().enumerate() {
                if (a[axis] - line).abs() > off || (b[axis] - line).abs() > off {
                    continue;
                }
                if (a[along] - b[along]).abs() <= across {
                    continue; // no length along the side
                }
                let (pa, pb) = (
                    positions[t.vertices[i] as usize],
                    positions[t.vertices[j] as usize],
                );
                sides[side].push(if a[along] < b[along] {
                    ([a[along], b[along]], [pa, pb])
                } else {
                    ([b[along], a[along]], [pb, pa])
                });
            }
        }
    }
    let [low, high] = &mut sides;
    if low.is_empty() || low.len() != high.len() {
        return false;
    }
    // In order along the side; edges at the same place (two shells sharing one UV map, as a
    // Solidify modifier makes them) in order of their 3D ends, so that twins pair up.
    let key = |e: &SideEdge| {
        let [a, b] = e.1;
        [e.0[0], e.0[1], a.x, a.y, a.z, b.x, b.y, b.z]
    };
    for side in [&mut *low, &mut *high] {
        side.sort_by(|x, y| {
            key(x)
                .iter()
                .zip(key(y).iter())
                .map(|(p, q)| p.total_cmp(q))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        });
    }
    low.iter().zip(high.iter()).all(|(l, h)| {
        (0..2).all(|e| (l.0[e] - h.0[e]).abs() <= across && l.1[e].distance(h.1[e]) <= reach)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tube of `n` quads round and one along, unwrapped to `[0,1] x [0,1]`, its seam
    /// vertices shared (as Blender keeps them) or doubled; `shift` moves the seam's right
    /// side along v.
    fn tube(n: usize, doubled: bool, shift: f32) -> (Vec<SeamTriangle>, Vec<Vec3>) {
        let mut positions = Vec::new();
        for row in 0..2 {
            for k in 0..n {
                let a = std::f32::consts::TAU * k as f32 / n as f32;
                positions.push(Vec3::new(a.cos(), a.sin(), row as f32));
            }
        }
        let seam = positions.len() as u32;
        if doubled {
            positions.push(positions[0]);
            positions.push(positions[n]);
        }
        let mut triangles = Vec::new();
        for k in 0..n {
            let last = k + 1 == n;
            let next = |row: usize| match (last, doubled) {
                (false, _) => (row * n + k + 1) as u32,
                (true, false) => (row * n) as u32,
                (true, true) => seam + row as u32,
            };
            let (u0, u1) = (k as f32 / n as f32, (k + 1) as f32 / n as f32);
            let dv = if last { shift } else { 0.0 };
            let v = [k as u32, next(0), next(1), (n + k) as u32];
            let uv = [
                Vec2::new(u0, 0.0),
                Vec2::new(u1, dv),
                Vec2::new(u1, 1.0 + dv),
                Vec2::new(u0, 1.0),
            ];
            for [a, b, c] in [[0, 1, 2], [0, 2, 3]] {
                triangles.push(SeamTriangle {
                    vertices: [v[a], v[b], v[c]],
                    uv: [uv[a], uv[b], uv[c]],
                });
            }
        }
        (triangles, positions)
    }

    fn domain_of(triangles: &[SeamTriangle]) -> UvRect {
        let (mut min, mut max) = (Vec2::MAX, Vec2::MIN);
        for t in triangles {
            for p in t.uv {
                min = min.min(p);
                max = max.max(p);
            }
        }
        UvRect { min, max }
    }

    #[test]
    fn a_tube_closes_round_along_u_whether_its_seam_vertices_are_shared_or_doubled() {
        for doubled in [false, true] {
            let (t, p) = tube(8, doubled, 0.0);
            assert_eq!(
                closed_seams(&t, &p, domain_of(&t)),
                (true, false),
                "{doubled}"
            );
        }
    }

    #[test]
    fn two_shells_sharing_one_uv_map_close_round_together() {
        // A Solidify modifier's inner shell: the same map, every position scaled in x and y.
        let (outer, p) = tube(8, false, 0.0);
        let shift = p.len() as u32;
        let inner: Vec<SeamTriangle> = outer
            .iter()
            .map(|t| SeamTriangle {
                vertices: t.vertices.map(|v| v + shift),
                uv: t.uv,
            })
            .collect();
        // Listed so that the inner shell's edge comes first on the map's left side and last
        // on its right.
        let half = inner.len() / 2;
        let triangles: Vec<SeamTriangle> = inner[..half]
            .iter()
            .chain(&outer)
            .chain(&inner[half..])
            .copied()
            .collect();
        let shrunk = p.iter().map(|q| Vec3::new(0.9 * q.x, 0.9 * q.y, q.z));
        let positions: Vec<Vec3> = p.iter().copied().chain(shrunk).collect();
        assert_eq!(
            closed_seams(&triangles, &positions, domain_of(&triangles)),
            (true, false)
        );
    }

    #[test]
    fn a_seam_whose_sides_do_not_meet_at_the_same_v_stays_open() {
        let (t, p) = tube(8, false, 0.25);
        assert_eq!(closed_seams(&t, &p, domain_of(&t)), (false, false));
    }

    #[test]
    fn a_sheet_whose_sides_lie_apart_in_3d_stays_open() {
        let (t, mut p) = tube(8, true, 0.0);
        let seam = p.len() - 2;
        p[seam] += Vec3::new(0.0, 0.01, 0.0);
        assert_eq!(closed_seams(&t, &p, domain_of(&t)), (false, false));
    }
}
