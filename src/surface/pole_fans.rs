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

/// How far (as a fraction of the UV box's size) a seam's two (u,v) of one ring vertex may be
/// off one box width apart: [`super::uv_seams`]'s tolerance.
const SEAM_TOLERANCE: f32 = super::uv_seams::UV_TOLERANCE;

/// Fewest distinct (u,v) a pole vertex takes (a fan of three teeth).
const MIN_TEETH: usize = 3;

/// The fillers that close the gaps of every pole fan among `triangles` (those with UV area,
/// in input order) of a UV map whose bounding box is `domain`. Deterministic: sorted by the
/// teeth's input indices.
///
/// Where the map closes round along an axis (`closed`, [`super::uv_seams`]), the gap across
/// its seam is closed too: the first and the last tooth give their common ring vertex (u,v)
/// one domain width apart, and the gap between them is cut by the seam into two halves, one
/// at each side of the map, each running from its tooth to the side (3D: the same edge).
pub(super) fn pole_fillers(
    triangles: &[FanTriangle],
    domain: UvRect,
    closed: (bool, bool),
) -> Vec<Filler> {
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
    let size = domain.size();
    let mut fillers: Vec<Filler> = Vec::new();
    for ((pole, ring), teeth) in spokes {
        let [(a, pole_a, ring_a), (b, pole_b, ring_b)] = teeth[..] else {
            continue;
        };
        if key(pole_a) == key(pole_b) {
            continue;
        }
        // The same (u,v) at the ring vertex, another at the pole: a gap between teeth.
        if key(ring_a) == key(ring_b) {
            fillers.push(Filler {
                extends: a.min(b),
                vertices: [pole, ring, pole],
                uv: [pole_a, ring_a, pole_b],
            });
            continue;
        }
        // The ring vertex on the seam: one width apart along a closed axis, at the same
        // place along the other.
        for axis in 0..2 {
            let open = if axis == 0 { !closed.0 } else { !closed.1 };
            let along = 1 - axis;
            let near = |x: f32, y: f32, scale: f32| (x - y).abs() <= SEAM_TOLERANCE * scale;
            if open
                || !near(ring_a[along], ring_b[along], size[along])
                || !near((ring_a[axis] - ring_b[axis]).abs(), size[axis], size[axis])
            {
                continue;
            }
            // Each tooth's half: from its pole corner to the side its ring vertex lies on,
            // turning the same way round the pole as a whole gap does (pole, ring, pole).
            let (first, second) = if ring_a[axis] < ring_b[axis] {
                ((b, pole_b, ring_b), (a, pole_a, ring_a))
            } else {
                ((a, pole_a, ring_a), (b, pole_b, ring_b))
            };
            let side = |(_, pole_uv, ring_uv): Tooth| {
                let mut p = pole_uv;
                p[axis] = ring_uv[axis];
                p
            };
            fillers.push(Filler {
                extends: first.0,
                vertices: [pole, ring, pole],
                uv: [first.1, first.2, side(first)],
            });
            fillers.push(Filler {
                extends: second.0,
                vertices: [pole, ring, pole],
                uv: [side(second), second.2, second.1],
            });
        }
    }
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
        let fillers = pole_fillers(&fan, DOMAIN, (false, false));
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
    fn a_map_closed_round_its_seam_closes_the_gap_across_it_in_two_halves() {
        let fan: Vec<FanTriangle> = (0..4).map(|s| tooth(s, s, 4)).collect();
        let fillers = pole_fillers(&fan, DOMAIN, (true, false));
        assert_eq!(fillers.len(), 5);
        let across: Vec<&Filler> = fillers.iter().filter(|f| f.vertices[1] == 1).collect();
        // Ring vertex 1 is at u = 0 in the first tooth and at u = 1 in the last: each half
        // runs from its tooth's pole corner to the side of the map.
        assert_eq!(across.len(), 2);
        assert_eq!((across[0].extends, across[1].extends), (0, 3));
        assert_eq!(
            across[0].uv,
            [
                Vec2::new(0.0, 1.0),
                Vec2::new(0.0, 0.5),
                Vec2::new(0.125, 1.0)
            ]
        );
        assert_eq!(
            across[1].uv,
            [
                Vec2::new(0.875, 1.0),
                Vec2::new(1.0, 0.5),
                Vec2::new(1.0, 1.0)
            ]
        );
        assert!(across.iter().all(|f| f.vertices == [0, 1, 0]));
    }

    #[test]
    fn a_vertex_off_the_maps_edge_is_no_pole() {
        // The same fan with its pole row below the top of the map: no pole.
        let fan: Vec<FanTriangle> = (0..4).map(|s| tooth(s, s, 4)).collect();
        let taller = UvRect {
            min: Vec2::ZERO,
            max: Vec2::new(1.0, 2.0),
        };
        assert!(pole_fillers(&fan, taller, (false, false)).is_empty());
    }
}
