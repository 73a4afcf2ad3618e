//! Smooth vertex normals of one swept bundle, from its known layout.
//!
//! A renderer shades a smooth mesh with vertex normals averaged over the triangles round each
//! vertex; Blender computes them as the sum of the unit normals of the triangles at the
//! vertex, each weighted by the triangle's angle at that corner, normalised. Computed here the
//! same way, they serve twice:
//! - a knit with its hidden yarn culled has lost some of those triangles, so it is given the
//!   whole knit's normals and shades exactly as the whole knit does;
//! - a knit that follows an animated source writes its normals with its positions each frame,
//!   and Blender, given them as custom normals, skips its own recompute on the next draw (on
//!   3M vertices, 35–100 ms of every frame of playback).
//!
//! The bundle's layout ([`super::bundle`]) is fixed, so no adjacency is built or kept: every
//! triangle is `(ring vertex, ring vertex, its own apex)`. An apex belongs to one triangle
//! and takes that triangle's normal; a ring vertex belongs to the two triangles on each side
//! of it on its own ring's edges (two on an open bundle's end ring). Bundles share no
//! vertices, so a bundle's normals depend on its positions alone, and the result is the same
//! for any thread count.

use glam::Vec3;

use crate::portable_math::acos_fast;

/// The smooth normal of every vertex of one bundle of `rings` rings of `m` points (`closed`:
/// the last ring pairs with the first), whose `positions` (`3 * vertices` floats, the bundle's
/// own slice, laid out as [`super::build_bundle`] writes it) are given, into `out` (as many
/// floats). A vertex whose triangles all have no area gets +z.
pub fn bundle_normals(positions: &[f32], rings: usize, m: usize, closed: bool, out: &mut [f32]) {
    let counts = super::bundle_counts(rings, m, closed);
    debug_assert_eq!(positions.len(), 3 * counts.vertices);
    debug_assert_eq!(out.len(), 3 * counts.vertices);
    let at = |v: usize| Vec3::new(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    let ring_vertices = rings * m;
    out[..3 * ring_vertices].fill(0.0);
    let pairs = counts.triangles / (2 * m).max(1);
    for i in 0..pairs {
        let j = (i + 1) % rings;
        for half in 0..2 {
            let edge_ring = if half == 0 { i } else { j };
            for k in 0..m {
                let tri = i * 2 * m + half * m + k;
                let (v0, v1) = if half == 0 {
                    (edge_ring * m + k, edge_ring * m + (k + 1) % m)
                } else {
                    (edge_ring * m + (k + 1) % m, edge_ring * m + k)
                };
                let av = ring_vertices + tri;
                let (p0, p1, pa) = (at(v0), at(v1), at(av));
                // The two edges from v0 and the one from v1 (the ring edge serves both).
                let (e01, e0a, e1a) = (p1 - p0, pa - p0, pa - p1);
                let n = e01.cross(e0a).normalize_or_zero();
                let apex = if n == Vec3::ZERO { Vec3::Z } else { n };
                out[3 * av..3 * av + 3].copy_from_slice(&apex.to_array());
                // Corner angles at v0 (between v0->v1 and v0->apex) and at v1 (between
                // v1->apex and v1->v0), from squared lengths: one root per corner. A
                // zero-length edge gives no weight (n is zero then too).
                let (s01, s0a, s1a) = (
                    e01.length_squared(),
                    e0a.length_squared(),
                    e1a.length_squared(),
                );
                let cos_at = |d: f32, sa: f32, sb: f32| {
                    let l = (sa * sb).sqrt();
                    if l > 0.0 {
                        (d / l).clamp(-1.0, 1.0)
                    } else {
                        1.0
                    }
                };
                let w0 = acos_fast(cos_at(e01.dot(e0a), s01, s0a));
                let w1 = acos_fast(cos_at(-e01.dot(e1a), s01, s1a));
                for (v, w) in [(v0, w0), (v1, w1)] {
                    let o = &mut out[3 * v..3 * v + 3];
                    o[0] += n.x * w;
                    o[1] += n.y * w;
                    o[2] += n.z * w;
                }
            }
        }
    }
    for o in out[..3 * ring_vertices].chunks_exact_mut(3) {
        let n = Vec3::from_slice(o).try_normalize().unwrap_or(Vec3::Z);
        o.copy_from_slice(&n.to_array());
    }
}

#[cfg(test)]
mod tests {
    use super::super::TopologyBuffers;
    use super::super::{build_bundle, bundle_counts, BundleSettings, EndTangents, PieceBuffers};
    use super::*;

    /// Blender's smooth normals of a whole mesh, from its triangles: the reference.
    fn mesh_normals(positions: &[f32], triangles: &[i32]) -> Vec<f32> {
        let at = |v: i32| Vec3::from_slice(&positions[3 * v as usize..3 * v as usize + 3]);
        let mut sum = vec![Vec3::ZERO; positions.len() / 3];
        for tri in triangles.chunks_exact(3) {
            let n = (at(tri[1]) - at(tri[0]))
                .cross(at(tri[2]) - at(tri[0]))
                .normalize_or_zero();
            for corner in 0..3 {
                let p = at(tri[corner]);
                let e0 = (at(tri[(corner + 1) % 3]) - p).normalize_or_zero();
                let e1 = (at(tri[(corner + 2) % 3]) - p).normalize_or_zero();
                sum[tri[corner] as usize] += n * e0.dot(e1).clamp(-1.0, 1.0).acos();
            }
        }
        sum.iter()
            .flat_map(|s| s.try_normalize().unwrap_or(Vec3::Z).to_array())
            .collect()
    }

    /// A wavy yarn of `rings` rings of `m` points, its positions and triangles.
    fn wavy_bundle(rings: usize, m: usize, closed: bool) -> (Vec<f32>, Vec<i32>) {
        let points: Vec<Vec3> = (0..rings)
            .map(|i| {
                let t = i as f32 / rings as f32 * std::f32::consts::TAU;
                Vec3::new(t.cos(), t.sin(), 0.3 * (3.0 * t).sin())
            })
            .collect();
        let normals = vec![Vec3::Z; rings];
        let settings = BundleSettings {
            radius: 0.1,
            ring_segments: m,
            fluffiness: 0.8,
            color_variation: 0.0,
            seed: 5,
            plies: 2,
            samples_per_loop: 16,
        };
        let c = bundle_counts(rings, m, closed);
        let mut positions = vec![0.0; 3 * c.vertices];
        let mut corner_verts = vec![0; 3 * c.triangles];
        let mut corner_edges = vec![0; 3 * c.triangles];
        let mut edge_verts = vec![0; 2 * c.edges];
        let mut bufs = PieceBuffers::positions_only(&mut positions);
        bufs.topology = Some(TopologyBuffers {
            corner_verts: &mut corner_verts,
            corner_edges: &mut corner_edges,
            edge_verts: &mut edge_verts,
        });
        build_bundle(
            &points,
            &normals,
            &|i| (0, i / 16),
            &|_, _| [0.5; 3],
            closed,
            EndTangents::default(),
            &settings,
            None,
            &mut bufs,
        );
        (positions, corner_verts)
    }

    #[test]
    fn the_layout_gives_the_normals_the_triangles_give() {
        for closed in [false, true] {
            for m in 3..=8 {
                let (positions, triangles) = wavy_bundle(40, m, closed);
                let want = mesh_normals(&positions, &triangles);
                let mut got = vec![f32::NAN; positions.len()];
                bundle_normals(&positions, 40, m, closed, &mut got);
                for (v, (g, w)) in got.chunks(3).zip(want.chunks(3)).enumerate() {
                    let d = Vec3::from_slice(g).distance(Vec3::from_slice(w));
                    assert!(
                        d < 1e-5,
                        "m {m}, closed {closed}, vertex {v}: {g:?} vs {w:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn normals_point_away_from_the_yarn() {
        let (positions, _) = wavy_bundle(24, 6, true);
        let mut n = vec![0.0; positions.len()];
        bundle_normals(&positions, 24, 6, true, &mut n);
        // Ring vertex (i, k) lies off its ring's centre on the same side as its normal.
        let centre = |i: usize| {
            (0..6)
                .map(|k| Vec3::from_slice(&positions[3 * (i * 6 + k)..]))
                .sum::<Vec3>()
                / 6.0
        };
        for i in 0..24 {
            for k in 0..6 {
                let v = i * 6 + k;
                let out = Vec3::from_slice(&positions[3 * v..]) - centre(i);
                assert!(
                    out.dot(Vec3::from_slice(&n[3 * v..])) > 0.0,
                    "ring {i}, point {k}"
                );
            }
        }
    }

    #[test]
    fn a_degenerate_bundle_gets_plus_z() {
        let c = bundle_counts(3, 4, false);
        let positions = vec![0.0; 3 * c.vertices];
        let mut n = vec![0.0; 3 * c.vertices];
        bundle_normals(&positions, 3, 4, false, &mut n);
        assert!(n.chunks(3).all(|v| v == [0.0, 0.0, 1.0]));
    }
}
