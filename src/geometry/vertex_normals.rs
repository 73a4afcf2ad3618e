//! Smooth vertex normals of a whole mesh, for the vertices a subset of it keeps: what lets a
//! knit with its hidden yarn culled shade exactly as the whole knit does.
//!
//! A renderer shades a smooth mesh with vertex normals averaged over the triangles round
//! each vertex. Culling the hidden yarn drops some of those triangles, so the seen yarn's
//! normals would change; the add-on instead gives the culled mesh the whole mesh's normals
//! as custom normals. They are computed as Blender computes vertex normals: the sum of the
//! unit normals of the triangles at the vertex, each weighted by the triangle's angle at
//! that corner, normalised.

use glam::Vec3;
use rayon::prelude::*;

/// For each kept vertex, the corners of the whole mesh at it (`3 * triangle + corner`),
/// ascending: the triangles whose normals make its normal, in a fixed order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VertexCorners {
    start: Vec<u32>,
    corners: Vec<u32>,
}

impl VertexCorners {
    /// The corners at each of `kept` (whole-mesh vertex indices, ascending) of the whole
    /// mesh `triangles` `(T, 3)`. `index` maps a whole-mesh vertex to its place in `kept`
    /// (`u32::MAX`: not kept).
    pub fn new(triangles: &[i32], kept: usize, index: &[u32]) -> Self {
        let mut count = vec![0u32; kept + 1];
        for &v in triangles {
            let k = index[v as usize];
            if k != u32::MAX {
                count[k as usize + 1] += 1;
            }
        }
        for i in 0..kept {
            count[i + 1] += count[i];
        }
        let start = count;
        let mut fill = start.clone();
        let mut corners = vec![0u32; start[kept] as usize];
        for (c, &v) in triangles.iter().enumerate() {
            let k = index[v as usize];
            if k != u32::MAX {
                corners[fill[k as usize] as usize] = c as u32;
                fill[k as usize] += 1;
            }
        }
        Self { start, corners }
    }

    /// The smooth normal of every kept vertex of the whole mesh with `positions` `(V, 3)`
    /// and `triangles` `(T, 3)`, into `out` (`(kept, 3)`). A vertex whose triangles all have
    /// no area gets +z.
    pub fn normals(&self, positions: &[f32], triangles: &[i32], out: &mut [f32]) {
        let at = |v: i32| {
            let v = 3 * v as usize;
            Vec3::new(positions[v], positions[v + 1], positions[v + 2])
        };
        out.par_chunks_exact_mut(3).enumerate().for_each(|(k, o)| {
            let (a, b) = (self.start[k] as usize, self.start[k + 1] as usize);
            let mut sum = Vec3::ZERO;
            for &c in &self.corners[a..b] {
                let (t, corner) = (c as usize / 3, c as usize % 3);
                let tri = &triangles[3 * t..3 * t + 3];
                let (p, prev, next) = (
                    at(tri[corner]),
                    at(tri[(corner + 2) % 3]),
                    at(tri[(corner + 1) % 3]),
                );
                let n = (at(tri[1]) - at(tri[0]))
                    .cross(at(tri[2]) - at(tri[0]))
                    .normalize_or_zero();
                let (e0, e1) = (
                    (next - p).normalize_or_zero(),
                    (prev - p).normalize_or_zero(),
                );
                let angle = e0.dot(e1).clamp(-1.0, 1.0).acos();
                sum += n * angle;
            }
            let n = sum.try_normalize().unwrap_or(Vec3::Z);
            o.copy_from_slice(&n.to_array());
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_vertex_shared_by_two_faces_takes_their_angle_weighted_mean() {
        // A roof: vertices 0 and 1 on the ridge along x; triangle (0, 2, 1) faces -y and
        // up, (0, 1, 3) faces +y and up, both at 45 degrees.
        let p = vec![0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 1.0, 0.0];
        let t = vec![0, 2, 1, 0, 1, 3];
        let index = vec![0, 1, 2, 3];
        let vc = VertexCorners::new(&t, 4, &index);
        let mut n = vec![0.0; 12];
        vc.normals(&p, &t, &mut n);
        // The ridge vertex 0 has equal corner angles in both: straight up.
        assert!((n[0]).abs() < 1e-6 && (n[1]).abs() < 1e-6 && (n[2] - 1.0).abs() < 1e-6);
        // A vertex of one face only takes that face's normal.
        let s = 0.5f32.sqrt();
        assert!(
            (n[7] + s).abs() < 1e-6 && (n[8] - s).abs() < 1e-6,
            "{:?}",
            &n[6..9]
        );
    }

    #[test]
    fn only_kept_vertices_are_computed_and_in_their_order() {
        let p = vec![0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 1.0, 0.0];
        let t = vec![0, 2, 1, 0, 1, 3];
        let all = VertexCorners::new(&t, 4, &[0, 1, 2, 3]);
        let mut whole = vec![0.0; 12];
        all.normals(&p, &t, &mut whole);
        // Keep vertices 1 and 3 only.
        let some = VertexCorners::new(&t, 2, &[u32::MAX, 0, u32::MAX, 1]);
        let mut kept = vec![0.0; 6];
        some.normals(&p, &t, &mut kept);
        assert_eq!(kept[..3], whole[3..6]);
        assert_eq!(kept[3..], whole[9..12]);
    }
}
