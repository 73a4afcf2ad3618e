//! The UV gaps of a pole fan, closed.
//!
//! A UV sphere (Blender's, and most tools') has one vertex at each pole and a fan of
//! triangles round it. In the UV map the pole vertex takes a different (u,v) in each
//! triangle of its fan, the middle of that triangle's column on the map's top (or bottom)
//! edge, so the fan's triangles stand in the UV map as a row of teeth with a triangular gap
//! between each two. In 3D there is no gap: two neighbouring teeth share the edge from the
//! pole to their common ring vertex. A stitch whose key points fell in a gap had no surface
//! under them, so the courses round a pole broke into single stitches, each finished as a
//! little ring (a 32 x 16 sphere at the default gauge: 52 of its 106 yarn pieces).
//!
//! A gap is closed with a filler triangle, in UV the gap itself and in 3D the shared edge:
//! corners (pole, ring vertex, pole). A (u,v) in the gap so lies on that edge, between the
//! two teeth, and the courses run on round the pole. Only the gaps of a pole are closed: a
//! vertex whose (u,v) differs from triangle to triangle, every one of them on one edge line
//! of the UV map's bounding box. An ordinary seam (an edge whose two ends both take other
//! (u,v) on each side) or two islands that touch at a corner stay open.

use std::collections::BTreeMap;

use glam::Vec2;

use super::UvRect;

/// A triangle of the mesh that a pole fan may hold: its input index, vertices and UVs.
#[derive(Debug, Clone, Copy)]
pub(super) struct FanTriangle {
    pub index: u32,
    pub vertices: [u32; 3],
    pub uv: [Vec2; 3],
}

/// A filler: the gap between two teeth of a pole fan, `vertices` (pole, ring vertex, pole)
/// with `uv` the gap's corners. `extends` is the input index of the first of the two teeth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Filler {
    pub extends: u32,
    pub vertices: [u32; 3],
    pub uv: [Vec2; 3],
}

/// A tooth on one side of the edge from a pole to a ring vertex: its input index and the
/// (u,v) it gives the pole and the ring vertex.
type Tooth = (u32, Vec2, Vec2);

/// Fewest distinct (u,v) a pole vertex takes (a fan of three teeth).
const MIN_TEETH: usize = 3;

/// The fillers that close the gaps of every pole fan among `triangles` (those with UV area,
/// in input order) of a UV map whose bounding box is `domain`. Deterministic: sorted by the
/// teeth's input indices.
pub(super) fn pole_fillers(triangles: &[FanTriangle], domain: UvRect) -> Vec<Filler> {
    let key = |uv: Vec2| (uv.x.to_bits(), uv.y.to_bits());
    // Every (u,v) each vertex takes.
    let mut corners: BTreeMap<u32, Vec<Vec2>> = BTreeMap::new();
    for t in triangles {
        for c in 0..3 {
            corners.entry(t.vertices[c]).or_default().push(t.uv[c]);
        }
    }
    let on_one_edge = |uvs: &[Vec2]| {
        let all = |f: &dyn Fn(Vec2) -> bool| uvs.iter().all(|&p| f(p));
        all(&|p| p.y == domain.max.y)
            || all(&|p| p.y == domain.min.y)
            || all(&|p| p.x == domain.max.x)
            || all(&|p| p.x == domain.min.x)
    };
    let poles: Vec<u32> = corners
        .iter_mut()
        .filter_map(|(&v, uvs)| {
            uvs.sort_by_key(|&p| key(p));
            uvs.dedup_by_key(|p| key(*p));
            (uvs.len() >= MIN_TEETH && on_one_edge(uvs)).then_some(v)
        })
        .collect();
    if poles.is_empty() {
        return Vec::new();
    }
    // The edges from each pole to its ring vertices, with the teeth on either side.
    let mut spokes: BTreeMap<(u32, u32), Vec<Tooth>> = BTreeMap::new();
    for t in triangles {
        for c in 0..3 {
            let pole = t.vertices[c];
            if poles.binary_search(&pole).is_err() {
                continue;
            }
            for d in [(c + 1) % 3, (c + 2) % 3] {
                spokes
                    .entry((pole, t.vertices[d]))
                    .or_default()
                    .push((t.index, t.uv[c], t.uv[d]));
            }
        }
    }
    let mut fillers: Vec<Filler> = spokes
        .into_iter()
        .filter_map(|((pole, ring), teeth)| {
            let [(a, pole_a, ring_a), (b, pole_b, ring_b)] = teeth[..] else {
                return None;
            };
            // The same (u,v) at the ring vertex, another at the pole: a gap between teeth.
            (key(ring_a) == key(ring_b) && key(pole_a) != key(pole_b)).then_some(Filler {
                extends: a.min(b),
                vertices: [pole, ring, pole],
                uv: [pole_a, ring_a, pole_b],
            })
        })
        .collect();
    fillers.sort_by_key(|f| (f.extends, f.vertices[1]));
    fillers
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tooth(index: u32, s: u32, segments: u32) -> FanTriangle {
        let u = |x: f32| x / segments as f32;
        FanTriangle {
            index,
            vertices: [1 + s, 1 + (s + 1) % segments, 0],
            uv: [
                Vec2::new(u(s as f32), 0.5),
                Vec2::new(u(s as f32 + 1.0), 0.5),
                Vec2::new(u(s as f32 + 0.5), 1.0),
            ],
        }
    }

    const DOMAIN: UvRect = UvRect {
        min: Vec2::ZERO,
        max: Vec2::ONE,
    };

    #[test]
    fn a_pole_fan_gets_one_filler_between_each_two_teeth() {
        let fan: Vec<FanTriangle> = (0..4).map(|s| tooth(s, s, 4)).collect();
        let fillers = pole_fillers(&fan, DOMAIN);
        // Four teeth round the pole (vertex 0); the seam between the last and the first
        // (ring vertex 1 at u = 0 and at u = 1) stays open.
        assert_eq!(fillers.len(), 3);
        let f = fillers[0];
        assert_eq!(f.extends, 0);
        assert_eq!(f.vertices, [0, 2, 0]);
        assert_eq!(
            f.uv,
            [
                Vec2::new(0.125, 1.0),
                Vec2::new(0.25, 0.5),
                Vec2::new(0.375, 1.0)
            ]
        );
    }

    #[test]
    fn a_vertex_off_the_maps_edge_is_no_pole() {
        // The same fan with its pole row below the top of the map: no pole.
        let fan: Vec<FanTriangle> = (0..4).map(|s| tooth(s, s, 4)).collect();
        let taller = UvRect {
            min: Vec2::ZERO,
            max: Vec2::new(1.0, 2.0),
        };
        assert!(pole_fillers(&fan, taller).is_empty());
    }
}
