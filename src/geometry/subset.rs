//! A subset of a built mesh's triangles, as a mesh of its own: the knit with its hidden
//! yarn culled ([`crate::visibility`]).
//!
//! The kept triangles keep their order; a vertex or an edge is kept when a kept triangle
//! uses it, and keeps its order too. So the subset is a pure function of the whole mesh's
//! topology and the keep mask: every build of a knit (any pose) gathers the same elements,
//! and the subset's topology is the same each time.

use rayon::prelude::*;

/// Marks an element not in the subset.
const DROPPED: u32 = u32::MAX;

/// Which triangles, vertices and edges of a whole mesh are kept, and where each lands.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MeshSubset {
    /// Kept triangles of the whole mesh, ascending.
    triangles: Vec<u32>,
    /// Kept vertices of the whole mesh, ascending.
    vertices: Vec<u32>,
    /// Whole-mesh vertex -> subset vertex, or `DROPPED`.
    vertex_index: Vec<u32>,
    /// Kept edges of the whole mesh, ascending.
    edges: Vec<u32>,
    /// Whole-mesh edge -> subset edge, or `DROPPED`.
    edge_index: Vec<u32>,
}

fn kept_of(used: &[bool]) -> (Vec<u32>, Vec<u32>) {
    let kept: Vec<u32> = (0..used.len() as u32)
        .filter(|&i| used[i as usize])
        .collect();
    let mut index = vec![DROPPED; used.len()];
    for (new, &old) in kept.iter().enumerate() {
        index[old as usize] = new as u32;
    }
    (kept, index)
}

impl MeshSubset {
    /// The subset of the triangles `keep` marks, of a mesh with `vertices` vertices,
    /// `edges` edges, `triangles` `(T, 3)` vertex indices and `corner_edges` `(3T,)`.
    pub fn new(
        keep: &[bool],
        triangles: &[i32],
        corner_edges: &[i32],
        vertices: usize,
        edges: usize,
    ) -> Self {
        let kept: Vec<u32> = (0..keep.len() as u32)
            .filter(|&t| keep[t as usize])
            .collect();
        let mut vertex_used = vec![false; vertices];
        let mut edge_used = vec![false; edges];
        for &t in &kept {
            let t = t as usize;
            for k in 3 * t..3 * t + 3 {
                vertex_used[triangles[k] as usize] = true;
                edge_used[corner_edges[k] as usize] = true;
            }
        }
        let (vertices, vertex_index) = kept_of(&vertex_used);
        let (edges, edge_index) = kept_of(&edge_used);
        Self {
            triangles: kept,
            vertices,
            vertex_index,
            edges,
            edge_index,
        }
    }

    /// Whole-mesh vertex -> subset vertex (`u32::MAX`: dropped).
    pub fn vertex_index(&self) -> &[u32] {
        &self.vertex_index
    }

    /// Vertices of the subset.
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    /// Triangles of the subset.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Edges of the subset.
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// Rows `vertices` of `whole` (rows of `width` values), into `out`.
    fn gather<T: Copy + Send + Sync>(rows: &[u32], whole: &[T], width: usize, out: &mut [T]) {
        out.par_chunks_exact_mut(width)
            .zip(rows.par_iter())
            .for_each(|(o, &r)| {
                let r = r as usize * width;
                o.copy_from_slice(&whole[r..r + width]);
            });
    }

    /// The kept vertices' 3-vectors (positions or normals, `(V, 3)` of the whole mesh) into
    /// `out` (`3 * vertex_count()`).
    pub fn gather_vectors(&self, whole: &[f32], out: &mut [f32]) {
        Self::gather(&self.vertices, whole, 3, out);
    }

    /// The subset's buffers from the whole mesh's: positions `(V, 3)`, colours `(V, 4)`,
    /// triangles `(T, 3)`, corner edges `(3T,)` and edges `(E, 2)`, renumbered.
    pub fn apply(
        &self,
        positions: &[f32],
        colors: &[f32],
        triangles: &[i32],
        corner_edges: &[i32],
        edges: &[i32],
    ) -> SubsetBuffers {
        let mut out = SubsetBuffers {
            positions: crate::output_buffer::zeroed(3 * self.vertex_count()),
            colors: crate::output_buffer::zeroed(4 * self.vertex_count()),
            triangles: crate::output_buffer::zeroed(3 * self.triangle_count()),
            corner_edges: crate::output_buffer::zeroed(3 * self.triangle_count()),
            edges: crate::output_buffer::zeroed(2 * self.edge_count()),
        };
        Self::gather(&self.vertices, positions, 3, &mut out.positions);
        Self::gather(&self.vertices, colors, 4, &mut out.colors);
        let renumber = |rows: &[u32], whole: &[i32], width: usize, index: &[u32], o: &mut [i32]| {
            o.par_chunks_exact_mut(width)
                .zip(rows.par_iter())
                .for_each(|(o, &r)| {
                    let r = r as usize * width;
                    for (k, v) in o.iter_mut().enumerate() {
                        *v = index[whole[r + k] as usize] as i32;
                    }
                });
        };
        renumber(
            &self.triangles,
            triangles,
            3,
            &self.vertex_index,
            &mut out.triangles,
        );
        renumber(
            &self.triangles,
            corner_edges,
            3,
            &self.edge_index,
            &mut out.corner_edges,
        );
        renumber(&self.edges, edges, 2, &self.vertex_index, &mut out.edges);
        out
    }
}

/// A subset's buffers (see [`MeshSubset::apply`]).
#[derive(Debug, Clone, Default)]
pub struct SubsetBuffers {
    pub positions: Vec<f32>,
    pub colors: Vec<f32>,
    pub triangles: Vec<i32>,
    pub corner_edges: Vec<i32>,
    pub edges: Vec<i32>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles sharing edge 1-2 of a quad 0-1-2-3; edges 0:(0,1) 1:(1,2) 2:(2,0)
    /// 3:(2,3) 4:(3,1).
    fn quad() -> (Vec<i32>, Vec<i32>, Vec<i32>) {
        let tri = vec![0, 1, 2, 1, 3, 2];
        let ce = vec![0, 1, 2, 4, 3, 1];
        let edges = vec![0, 1, 1, 2, 2, 0, 2, 3, 3, 1];
        (tri, ce, edges)
    }

    #[test]
    fn dropping_a_triangle_drops_what_only_it_used() {
        let (tri, ce, edges) = quad();
        let s = MeshSubset::new(&[false, true], &tri, &ce, 4, 5);
        assert_eq!(
            (s.vertex_count(), s.triangle_count(), s.edge_count()),
            (3, 1, 3)
        );
        let pos: Vec<f32> = (0..12).map(|i| i as f32).collect();
        let col: Vec<f32> = (0..16).map(|i| i as f32).collect();
        let b = s.apply(&pos, &col, &tri, &ce, &edges);
        // Vertices 1, 2, 3 -> 0, 1, 2; edges 1, 3, 4 -> 0, 1, 2.
        assert_eq!(
            b.positions,
            vec![3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0]
        );
        assert_eq!(b.colors[..4], [4.0, 5.0, 6.0, 7.0]);
        assert_eq!(b.triangles, vec![0, 2, 1]);
        assert_eq!(b.corner_edges, vec![2, 1, 0]);
        assert_eq!(b.edges, vec![0, 1, 1, 2, 2, 0]);
        let mut gathered = vec![0.0; 9];
        s.gather_vectors(&pos, &mut gathered);
        assert_eq!(gathered, b.positions);
    }

    #[test]
    fn keeping_everything_is_the_whole_mesh() {
        let (tri, ce, edges) = quad();
        let s = MeshSubset::new(&[true, true], &tri, &ce, 4, 5);
        let pos: Vec<f32> = (0..12).map(|i| i as f32).collect();
        let col = vec![0.5; 16];
        let b = s.apply(&pos, &col, &tri, &ce, &edges);
        assert_eq!(
            (b.positions, b.triangles, b.corner_edges, b.edges),
            (pos, tri, ce, edges)
        );
    }
}
