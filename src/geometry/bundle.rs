//! Fluffy triangle bundles ([Zhong 2001], section 2.5, figure 7).
//!
//! A ring of `m` points is swept along the centreline (ring `i` around sample `i`). Between
//! consecutive rings L1, L2 the paper's bundle has `m + n` triangles (here `n = m`): each edge
//! of L1 with a randomly chosen vertex of L2, and each edge of L2 with a randomly chosen vertex
//! of L1. The chosen vertex is copied and pushed outward along its ring direction by a random
//! fraction of `fluffiness * radius`, so each triangle owns its apex: the random apexes make the
//! fibrous reflectance and the pushes the down around the yarn.
//!
//! Layout of one yarn piece with `R` rings and `Q` ring pairs (`Q = R - 1` open, `R` closed):
//! vertices `[R*m ring vertices][Q*2m apex vertices]`, triangles `Q*2m` (pair `q` owns
//! triangles `q*2m..(q+1)*2m`: first the L1 edges, then the L2 edges), edges
//! `[R*m ring edges][2 per triangle: corner 1 -> apex, apex -> corner 0]`. Every triangle is
//! `(ring vertex, ring vertex, apex)` wound so its normal points away from the yarn axis.
//!
//! Randomness is drawn from a generator seeded by (seed, course, wale) of the stitch that owns
//! the ring pair, in ring order: the result does not depend on threads, on other stitches, or
//! on which piece a stitch ends up in. One 64-bit draw per triangle gives its apex pick (16
//! bits: uniform to 1 part in 1000 for up to 64 ring points), push (24 bits) and shade (24
//! bits): the draws were most of the per-frame time of an animated knit when each took its own
//! (45 ms -> 25 ms for the positions of 10,000 stitches on 2 cores).
//!
//! A span that keeps only some of its piece's full-density samples (a coarser level of
//! camera-driven detail) takes its draws from that same full-density stream
//! ([`FullDensityDraws`]): each of its triangles reuses the draw of the full-detail triangle
//! that starts at the same sample and ring angle, and its apex keeps that triangle's ring
//! angle, push and shade. A coarser level is so a subset of the fibres full detail builds, not
//! a fresh random set, and the image changes only where fibres are dropped.

use std::f32::consts::TAU;

use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::frames::{frame_from_tangent, ring_frame};
use super::plies::{ply_radius, twist};

/// Settings of the swept yarn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BundleSettings {
    /// Yarn radius, scene units.
    pub radius: f32,
    /// Points per ring, at least 3. Default: 6.
    pub ring_segments: usize,
    /// Outward push of apexes as a fraction of the radius (0 = a plain randomised tube).
    pub fluffiness: f32,
    /// Relative random brightness variation of vertex colours, in [0, 1].
    pub color_variation: f32,
    pub seed: u64,
    /// Plies twisted round each other, 1 (a plain tube) to [`super::plies::MAX_PLIES`]
    /// ([`super::plies`]).
    pub plies: usize,
    /// Full-density samples per stitch loop of the piece: the plies' twist is counted in
    /// them.
    pub samples_per_loop: usize,
}

/// Element counts of one piece's bundle (closed form, for preallocation and budgets).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BundleCounts {
    pub vertices: usize,
    pub triangles: usize,
    pub edges: usize,
}

/// Counts for a piece with `rings` rings of `m` points.
pub fn bundle_counts(rings: usize, m: usize, closed: bool) -> BundleCounts {
    let pairs = if closed {
        rings
    } else {
        rings.saturating_sub(1)
    };
    let triangles = pairs * 2 * m;
    BundleCounts {
        vertices: rings * m + triangles,
        triangles,
        edges: rings * m + 2 * triangles,
    }
}

/// One piece's slices of the output buffers, and where its vertices and edges start in the
/// whole mesh (indices written are global). Colours and topology are optional: the
/// per-frame path of an animated knit writes positions only.
pub struct PieceBuffers<'a> {
    pub vertex_base: usize,
    pub edge_base: usize,
    /// `3 * vertices` floats.
    pub positions: &'a mut [f32],
    /// `4 * vertices` floats, linear RGBA.
    pub colors: Option<&'a mut [f32]>,
    pub topology: Option<TopologyBuffers<'a>>,
}

/// One piece's slices of the topology buffers.
pub struct TopologyBuffers<'a> {
    /// `3 * triangles` vertex indices.
    pub corner_verts: &'a mut [i32],
    /// `3 * triangles` edge indices (edge from corner k to corner k+1).
    pub corner_edges: &'a mut [i32],
    /// `2 * edges` vertex indices.
    pub edge_verts: &'a mut [i32],
}

impl<'a> PieceBuffers<'a> {
    /// Buffers that take positions only.
    pub fn positions_only(positions: &'a mut [f32]) -> Self {
        Self {
            vertex_base: 0,
            edge_base: 0,
            positions,
            colors: None,
            topology: None,
        }
    }
}

/// The low 24 bits of `bits` as a float in [0, 1), exactly.
fn unit24(bits: u64) -> f32 {
    (bits & 0xFF_FFFF) as f32 * (1.0 / 16_777_216.0)
}

/// A stable 64-bit mix of the seed and a stitch's (course, wale) (SplitMix64 finaliser).
pub fn stitch_seed(seed: u64, course: usize, wale: usize) -> u64 {
    crate::rng::cell_seed(seed, course, wale)
}

/// Tangent directions (any length) for the first and last ring of a bundle, where the
/// bundle is one span of a longer yarn and its end rings must lie in the planes the
/// neighbouring spans give them. `None`: from the bundle's own samples.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EndTangents {
    pub first: Option<Vec3>,
    pub last: Option<Vec3>,
}

/// Where a span's random draws come from when its rings sit on some of its piece's
/// full-density samples (see the module docs). With `ring_segments` and every sample kept it
/// gives exactly the draws of the whole piece's bundle.
#[derive(Debug, Clone, Copy)]
pub struct FullDensityDraws<'a> {
    /// The full-density sample under each ring of the span.
    pub samples: &'a [usize],
    /// Every full-density sample of the piece: the seed of its stitch's stream
    /// ([`stitch_seed`]) and its ring's slot in that stream (rings since the stitch began,
    /// in the piece's sample order).
    pub streams: &'a [(u64, u32)],
    /// Points per ring at full detail.
    pub ring_segments: usize,
}

/// Slots of a piece's full-density samples in their stitches' streams, as
/// [`build_bundle`] draws them over the whole piece: `seed_of(i)` is sample `i`'s stream seed.
pub fn piece_streams(samples: usize, seed_of: impl Fn(usize) -> u64) -> Vec<(u64, u32)> {
    let mut out: Vec<(u64, u32)> = Vec::with_capacity(samples);
    for i in 0..samples {
        let seed = seed_of(i);
        let slot = match out.last() {
            Some(&(prev, slot)) if prev == seed => slot + 1,
            _ => 0,
        };
        out.push((seed, slot));
    }
    out
}

/// The draws full detail makes at one ring of `m` points (slot `slot` of stream `seed`): `m`
/// colour draws, then the ring pair's `2m` triangle draws, as [`build_bundle`] makes them.
fn ring_draws((seed, slot): (u64, u32), m: usize, colours: &mut [u32], tris: &mut [u64]) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // One u32 per colour draw and two per triangle draw: 5m words per ring.
    rng.set_word_pos(5 * m as u128 * slot as u128);
    for c in colours.iter_mut() {
        *c = rng.next_u32();
    }
    for t in tris.iter_mut() {
        *t = rng.next_u64();
    }
}

/// Builds the bundle of one yarn piece into `out`.
///
/// `points`/`normals`: the centreline and the surface normal under each sample; `owner[i]`:
/// (course, wale) of the stitch that sample `i` belongs to; `color_of(course, wale)`: the
/// stitch's linear RGB colour; `ends`: tangents for the end rings of a span (see
/// [`EndTangents`]; the default for a whole piece); `draws`: the full-density stream for a
/// span of a piece (`None`: the piece's own samples, drawn in order).
#[allow(clippy::too_many_arguments)]
pub fn build_bundle(
    points: &[Vec3],
    normals: &[Vec3],
    owner: &dyn Fn(usize) -> (usize, usize),
    color_of: &dyn Fn(usize, usize) -> [f32; 3],
    closed: bool,
    ends: EndTangents,
    settings: &BundleSettings,
    draws: Option<&FullDensityDraws>,
    out: &mut PieceBuffers,
) {
    let m = settings.ring_segments;
    let rings = points.len();
    let counts = bundle_counts(rings, m, closed);
    let pairs = counts.triangles / (2 * m);
    let r = settings.radius;
    let (cos, sin): (Vec<f32>, Vec<f32>) = (0..m)
        .map(|k| TAU * k as f32 / m as f32)
        .map(|a| {
            let (s, c) = crate::portable_math::sin_cos(a);
            (c, s)
        })
        .unzip();

    // The plies' twist at ring i: counted in the piece's full-density samples.
    let ply_twist = |i: usize| match draws {
        Some(d) => twist(d.samples[i], settings.samples_per_loop),
        None => twist(i, settings.samples_per_loop),
    };
    // Ring directions, kept for the apexes, and ring frames for apexes at full-detail angles.
    let mut dirs = vec![Vec3::ZERO; rings * m];
    let mut frames = vec![(Vec3::ZERO, Vec3::ZERO); if draws.is_some() { rings } else { 0 }];
    for i in 0..rings {
        let tangent = match i {
            0 => ends.first,
            _ if i + 1 == rings => ends.last,
            _ => None,
        };
        let (_, a, b) = match tangent {
            Some(t) => frame_from_tangent(t, normals[i]),
            None => ring_frame(points, normals, i, closed),
        };
        if let Some(f) = frames.get_mut(i) {
            *f = (a, b);
        }
        let twist = ply_twist(i);
        for k in 0..m {
            let d = cos[k] * a + sin[k] * b;
            dirs[i * m + k] = d;
            let rho = ply_radius(settings.plies, TAU * k as f32 / m as f32, twist);
            let p = points[i] + r * rho * d;
            out.positions[3 * (i * m + k)..3 * (i * m + k) + 3].copy_from_slice(&p.to_array());
        }
    }

    // Ring edges.
    if let Some(topo) = out.topology.as_mut() {
        for i in 0..rings {
            for k in 0..m {
                let e = i * m + k;
                topo.edge_verts[2 * e] = (out.vertex_base + i * m + k) as i32;
                topo.edge_verts[2 * e + 1] = (out.vertex_base + i * m + (k + 1) % m) as i32;
            }
        }
    }

    let variation = settings.color_variation.clamp(0.0, 1.0);
    let shade = |bits: u64, c: [f32; 3]| -> [f32; 4] {
        let f = 1.0 + variation * (2.0 * unit24(bits) - 1.0);
        [c[0] * f, c[1] * f, c[2] * f, 1.0]
    };

    let apex_base = rings * m;
    // A span's draws: the full-density stream's colour draws at each ring's sample (`mf`
    // per ring) and the triangle draws of the full-detail ring pairs its pairs start from.
    let mf = draws.map_or(m, |d| d.ring_segments);
    let (full_cos, full_sin): (Vec<f32>, Vec<f32>) = (0..mf)
        .map(|k| TAU * k as f32 / mf as f32)
        .map(|a| {
            let (s, c) = crate::portable_math::sin_cos(a);
            (c, s)
        })
        .unzip();
    // The full-detail ring point at (or just after) this level's point k.
    let full_k = |k: usize| (k * mf + m / 2) / m % mf;
    let mut span_colours = vec![0u32; if draws.is_some() { mf } else { 0 }];
    let mut pair_draws = vec![0u64; if draws.is_some() { 2 * mf } else { 0 }];
    let mut back_draws = pair_draws.clone();
    let mut back_colours = span_colours.clone();
    let mut current: Option<(usize, usize)> = None;
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    for i in 0..rings {
        let (course, wale) = owner(i);
        if let Some(d) = draws {
            let s = d.samples[i];
            ring_draws(d.streams[s], mf, &mut span_colours, &mut pair_draws);
            if i < pairs {
                // Half 1 (ring j's edges, apexes on ring i) of full detail sits in the pair
                // that ends at ring j's sample.
                let n = d.streams.len();
                let back = (d.samples[(i + 1) % rings] + n - 1) % n;
                if back == s {
                    back_draws.copy_from_slice(&pair_draws);
                } else {
                    ring_draws(d.streams[back], mf, &mut back_colours, &mut back_draws);
                }
            }
        } else if current != Some((course, wale)) {
            current = Some((course, wale));
            rng = ChaCha8Rng::seed_from_u64(stitch_seed(settings.seed, course, wale));
        }
        let color = color_of(course, wale);
        for k in 0..m {
            // Drawn whether or not colours are written, so the random stream (and with it
            // every apex position) is the same in a full build and a positions-only one.
            let bits = match draws {
                Some(_) => span_colours[full_k(k)],
                None => rng.next_u32(),
            };
            let c = shade(bits as u64, color);
            if let Some(colors) = out.colors.as_mut() {
                colors[4 * (i * m + k)..4 * (i * m + k) + 4].copy_from_slice(&c);
            }
        }
        if i >= pairs {
            continue;
        }
        let j = (i + 1) % rings;
        // Two halves: the edges of ring i with apexes on ring j, then the reverse.
        for half in 0..2 {
            let (edge_ring, apex_ring) = if half == 0 { (i, j) } else { (j, i) };
            for k in 0..m {
                let tri = i * 2 * m + half * m + k;
                // One draw per triangle: 16 bits pick the apex, 24 the push, 24 the shade.
                let bits = match draws {
                    Some(_) if half == 0 => pair_draws[full_k(k)],
                    Some(_) => back_draws[mf + full_k(k)],
                    None => rng.next_u64(),
                };
                let pick = (((bits & 0xFFFF) * mf as u64) >> 16) as usize;
                let push = 1.0 + settings.fluffiness * unit24(bits >> 16);
                let (apex_dir, apex_angle) = match frames.get(apex_ring) {
                    // At the full-detail ring angle, in this ring's frame.
                    Some(&(a, b)) => (
                        full_cos[pick] * a + full_sin[pick] * b,
                        TAU * pick as f32 / mf as f32,
                    ),
                    None => (dirs[apex_ring * m + pick], TAU * pick as f32 / m as f32),
                };
                let rho = ply_radius(settings.plies, apex_angle, ply_twist(apex_ring));
                let apex = points[apex_ring] + r * push * rho * apex_dir;
                let av = apex_base + tri;
                out.positions[3 * av..3 * av + 3].copy_from_slice(&apex.to_array());
                let ac = shade(bits >> 40, color);
                if let Some(colors) = out.colors.as_mut() {
                    colors[4 * av..4 * av + 4].copy_from_slice(&ac);
                }
                let Some(topo) = out.topology.as_mut() else {
                    continue;
                };

                let (v0, v1) = if half == 0 {
                    (edge_ring * m + k, edge_ring * m + (k + 1) % m)
                } else {
                    // Reversed so the face normal points outward (see the module docs).
                    (edge_ring * m + (k + 1) % m, edge_ring * m + k)
                };
                let ring_edge = edge_ring * m + k;
                let e1 = rings * m + 2 * tri;
                let e2 = e1 + 1;
                let vb = out.vertex_base;
                let eb = out.edge_base;
                topo.corner_verts[3 * tri] = (vb + v0) as i32;
                topo.corner_verts[3 * tri + 1] = (vb + v1) as i32;
                topo.corner_verts[3 * tri + 2] = (vb + av) as i32;
                topo.corner_edges[3 * tri] = (eb + ring_edge) as i32;
                topo.corner_edges[3 * tri + 1] = (eb + e1) as i32;
                topo.corner_edges[3 * tri + 2] = (eb + e2) as i32;
                topo.edge_verts[2 * e1] = (vb + v1) as i32;
                topo.edge_verts[2 * e1 + 1] = (vb + av) as i32;
                topo.edge_verts[2 * e2] = (vb + av) as i32;
                topo.edge_verts[2 * e2 + 1] = (vb + v0) as i32;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::plies::GROOVE_DEPTH;
    use super::*;

    fn straight_yarn(
        samples: &[usize],
        m: usize,
        draws: Option<&FullDensityDraws>,
    ) -> (Vec<f32>, Vec<f32>) {
        straight_yarn_of(samples, m, draws, 1)
    }

    fn straight_yarn_of(
        samples: &[usize],
        m: usize,
        draws: Option<&FullDensityDraws>,
        plies: usize,
    ) -> (Vec<f32>, Vec<f32>) {
        let points: Vec<Vec3> = samples
            .iter()
            .map(|&i| Vec3::new(i as f32, 0.0, 0.0))
            .collect();
        let normals = vec![Vec3::Z; samples.len()];
        let settings = BundleSettings {
            radius: 0.25,
            ring_segments: m,
            fluffiness: 0.8,
            color_variation: 0.2,
            seed: 9,
            plies,
            samples_per_loop: 16,
        };
        let counts = bundle_counts(samples.len(), m, false);
        let mut positions = vec![0.0; 3 * counts.vertices];
        let mut colors = vec![0.0; 4 * counts.vertices];
        let mut bufs = PieceBuffers::positions_only(&mut positions);
        bufs.colors = Some(&mut colors);
        build_bundle(
            &points,
            &normals,
            &|i| (0, samples[i] / 16),
            &|_, _| [0.5, 0.5, 0.5],
            false,
            EndTangents::default(),
            &settings,
            draws,
            &mut bufs,
        );
        (positions, colors)
    }

    /// Three plies: the ring points of a straight yarn lie on the outline of three plies
    /// (the yarn's radius over a ply, less in the grooves) and the grooves turn along the
    /// yarn; the topology and the colours are the single strand's.
    #[test]
    fn plies_groove_the_strand_and_turn_along_it() {
        let (n, m) = (32usize, 12usize);
        let all: Vec<usize> = (0..n).collect();
        let (round, round_colours) = straight_yarn_of(&all, m, None, 1);
        let (plied, plied_colours) = straight_yarn_of(&all, m, None, 3);
        assert_eq!(round.len(), plied.len());
        assert_eq!(round_colours, plied_colours);
        // Ring point k of ring i: its distance from the axis (the yarn runs along x).
        let radius = |buf: &[f32], i: usize, k: usize| {
            let v = 3 * (i * m + k);
            buf[v + 1].hypot(buf[v + 2])
        };
        for i in 0..n {
            let radii: Vec<f32> = (0..m).map(|k| radius(&plied, i, k)).collect();
            let (lo, hi) = radii
                .iter()
                .fold((f32::MAX, 0.0f32), |(lo, hi), &r| (lo.min(r), hi.max(r)));
            assert!(
                hi <= 0.25 + 1e-5 && lo >= 0.25 * (1.0 - GROOVE_DEPTH) - 1e-5,
                "{radii:?}"
            );
            assert!(hi - lo > 0.01, "ring {i} is round: {radii:?}");
            assert!((0..m).all(|k| (radius(&round, i, k) - 0.25).abs() < 1e-5));
        }
        // The deepest groove moves round the ring from one ring to the next.
        let deepest = |i: usize| {
            (0..m)
                .min_by(|&a, &b| radius(&plied, i, a).total_cmp(&radius(&plied, i, b)))
                .unwrap()
        };
        let moved = (1..n).filter(|&i| deepest(i) != deepest(i - 1)).count();
        assert!(moved >= n / 4, "the grooves do not turn: {moved} of {n}");
    }

    /// Drawn from the full-density stream, a span that keeps every sample is the whole
    /// piece's bundle bit for bit, and a coarser one keeps a subset of its fibres: each of
    /// its triangles has the push and shade of the full-detail triangle at the same sample.
    #[test]
    fn spans_keep_a_subset_of_the_full_detail_fibres() {
        let (n, m) = (64usize, 6usize);
        let all: Vec<usize> = (0..n).collect();
        let streams = piece_streams(n, |i| stitch_seed(9, 0, i / 16));
        let whole = straight_yarn(&all, m, None);
        let draws = FullDensityDraws {
            samples: &all,
            streams: &streams,
            ring_segments: m,
        };
        assert_eq!(whole, straight_yarn(&all, m, Some(&draws)));

        let coarse: Vec<usize> = (0..n).step_by(2).collect();
        let (mc, rings) = (3usize, coarse.len());
        let draws = FullDensityDraws {
            samples: &coarse,
            ..draws
        };
        let (pos, col) = straight_yarn(&coarse, mc, Some(&draws));
        let push = |p: &[f32], av: usize| Vec3::new(0.0, p[3 * av + 1], p[3 * av + 2]).length();
        for (i, &sample) in coarse.iter().enumerate().take(rings - 1) {
            for k in 0..mc {
                let tri = i * 2 * mc + k; // half 0: ring i's edges
                let full_tri = sample * 2 * m + 2 * k; // full point 2k at mc = 3
                let (av, fav) = (rings * mc + tri, n * m + full_tri);
                assert!((push(&pos, av) - push(&whole.0, fav)).abs() < 1e-6);
                assert_eq!(col[4 * av], whole.1[4 * fav], "shade of triangle {tri}");
            }
        }
    }

    /// A straight yarn along x: every apex must lie on its ring's plane, pushed out between 1
    /// and 1 + fluffiness radii, and the picks must cover the ring evenly.
    #[test]
    fn apexes_are_pushed_within_range_and_picked_evenly() {
        let (rings, m) = (400usize, 6usize);
        let points: Vec<Vec3> = (0..rings).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
        let normals = vec![Vec3::Z; rings];
        let settings = BundleSettings {
            radius: 0.25,
            ring_segments: m,
            fluffiness: 0.8,
            color_variation: 0.2,
            seed: 9,
            plies: 1,
            samples_per_loop: 16,
        };
        let counts = bundle_counts(rings, m, false);
        let mut positions = vec![0.0; 3 * counts.vertices];
        let mut colors = vec![0.0; 4 * counts.vertices];
        let mut bufs = PieceBuffers::positions_only(&mut positions);
        bufs.colors = Some(&mut colors);
        build_bundle(
            &points,
            &normals,
            &|i| (0, i / 16),
            &|_, _| [0.5, 0.5, 0.5],
            false,
            EndTangents::default(),
            &settings,
            None,
            &mut bufs,
        );
        let mut hits = vec![0usize; m];
        for tri in 0..counts.triangles {
            let av = rings * m + tri;
            let p = Vec3::from_slice(&positions[3 * av..3 * av + 3]);
            let ring = (p.x.round()) as usize;
            assert!(
                (p.x - ring as f32).abs() < 1e-5,
                "apex off its ring's plane"
            );
            let d = Vec3::new(0.0, p.y, p.z);
            let push = d.length() / settings.radius;
            assert!((1.0 - 1e-5..=1.8 + 1e-5).contains(&push), "push {push}");
            let angle = d.z.atan2(d.y).rem_euclid(TAU);
            hits[((angle / TAU * m as f32).round() as usize) % m] += 1;
            let shade = colors[4 * av] / 0.5;
            assert!((0.8 - 1e-6..=1.2 + 1e-6).contains(&shade), "shade {shade}");
        }
        let expected = counts.triangles as f32 / m as f32;
        for (k, &h) in hits.iter().enumerate() {
            assert!(
                (h as f32 - expected).abs() < 0.1 * expected,
                "ring vertex {k} picked {h} times, expected about {expected}"
            );
        }
    }
}
