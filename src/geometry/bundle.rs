//! Fluffy triangle bundles ([Zhong 2001], section 2.5, figure 7).
//!
//! A ring of `m` points is swept along the centreline (ring `i` around sample `i`). Between
//! consecutive rings L1, L2 the paper's bundle has `m + n` triangles (here `n = m`): each edge
//! of L1 with an apex towards L2, and each edge of L2 with an apex towards L1. Each triangle
//! owns its apex, pushed outward along its ring direction by a random fraction of
//! `fluffiness * radius`: the pushes make the down around the yarn.
//!
//! The paper's triangles stand for strands of fibre, "elongated along the direction of the
//! yarn". An apex picked anywhere on the other ring cuts through the tube (the yarn read as
//! barbed wire), so here each triangle reaches two ring intervals along the yarn (L1's edges
//! to the ring after L2, L2's edges to the ring before L1) and its apex leans a random 0 to 1
//! segment past its edge's end, in the direction the plies turn (at an open end, where there
//! is no ring beyond, it stops on the end ring without a lean): every strand lies along the
//! tube's surface, slanting with the twist. At fluffiness 0 the triangles cover the whole
//! tube, with no gap: in (angle, length) on the tube, an edge's triangle and the triangle of
//! the same edge on the next ring, leaning the other way within a segment, overlap over the
//! whole interval between them.
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
//! that starts at the same sample and ring angle, and its apex keeps that triangle's lean
//! (the same angle round the yarn, in full-detail segments), push and shade. A coarser level
//! is so a subset of the fibres full detail builds, not a fresh random set, and the image
//! changes only where fibres are dropped. A coarser sampling's fibres reach only the next
//! ring ([`BundleSettings::two_intervals`]): its rings are already as far apart as two or
//! three of full detail's, and a strand over two of them would cut across the loop.

use std::f32::consts::TAU;

use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::frames::{frame_from_tangent, ring_frame};
use super::plies::{ply_radius, twist, twist_rate};

/// Apex angles per ring segment: an apex leans up to one segment past its edge's end in
/// steps of this fraction of a segment.
const APEX_STEPS: usize = 4;

/// The turn of ring `i` of a piece's rings of `m` points from its frame's first axis (the
/// surface normal across the yarn), radians: every other ring of a 3-point ring (the far
/// level's) turns half a segment, so the tube between two rings is an antiprism rather than
/// a prism.
///
/// The shading normals are the ring's directions, and across a face they turn from one
/// corner's to the next. A 3-point ring (the far level) with a corner out of the fabric
/// shows the camera over the fabric two faces whose outer halves shade as if turned away
/// from it: the far level read 8% darker in red than full detail in EEVEE (5.8% in
/// brightness). Every ring with a face out shows one face whose normals stay within 60
/// degrees of the fabric's, and read 6% brighter. Alternating, the tube's normals spread
/// round it as a round yarn's do: within 2.4% in every channel, and cover unchanged
/// (`tests/python/blender/test_detail.py`). An even ring is symmetric about the surface
/// normal either way and stays as it is, so full detail's default six is untouched. A
/// 5-point ring (the mid level's) is round enough as a prism: turned, it read 2.4% brighter
/// in green and blue lit; as it is, within 0.9%.
pub fn ring_phase(m: usize, i: usize) -> f32 {
    if m == 3 && i % 2 == 1 {
        std::f32::consts::PI / m as f32
    } else {
        0.0
    }
}

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
    /// Whether a fibre triangle reaches past the next ring to the one after it (full
    /// sampling) or stops at the next ring (a coarser level). A coarser level's rings are
    /// already two or three of full detail's apart: a strand over two of its intervals would
    /// span a third of a loop's turn, cut across the loop and shade as a back face.
    pub two_intervals: bool,
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
    /// `3 * vertices` floats: the shading normals, the swept tube's own (see
    /// [`build_bundle`]).
    pub normals: Option<&'a mut [f32]>,
    /// `3 * vertices` floats: the fibre directions, unit tangents of the tube along the
    /// plies' twist (see [`build_bundle`]).
    pub tangents: Option<&'a mut [f32]>,
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
            normals: None,
            tangents: None,
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

/// The unit direction of a fibre at a point of the tube out from the centreline along
/// `out` (unit, in the ring plane), where the yarn runs along `along` (unit) and the fibre
/// turns round the yarn by `around` per unit along it: perpendicular to `out`, slanted from
/// `along` by `atan(around)` towards the way the twist turns (`along x out`).
fn fibre_direction(along: Vec3, out: Vec3, around: f32) -> Vec3 {
    (along + around * along.cross(out))
        .try_normalize()
        .unwrap_or(along)
}

/// What a bundle's random draws and its plies make of each vertex, wherever its centreline
/// lies: the part of [`build_bundle`] that does not move with the surface. An animated knit
/// draws it once ([`bundle_profile`]) and each frame only sweeps ([`sweep_bundle`]): the
/// draws and the plies' outline were half of the core's work on a frame (10,000 stitches,
/// 2 cores: 91 ms with them, 44 ms without; `benchmarks/bench_follow.py`).
///
/// Invariant: it belongs to one bundle's rings, closedness and settings; a sweep of another
/// bundle reads the wrong values.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BundleProfile {
    /// Per vertex, in the bundle's layout (ring points, then apexes): its distance from the
    /// centreline along its direction, scene units (the yarn radius times the plies' outline
    /// there, and for an apex its random push).
    radial: Vec<f32>,
    /// Per apex: how far it leans past its edge's end round the yarn, in apex steps
    /// (`0..=APEX_STEPS`).
    lean: Vec<u8>,
}

impl BundleProfile {
    /// Heap bytes it holds.
    pub fn bytes(&self) -> usize {
        4 * self.radial.capacity() + self.lean.capacity()
    }
}

/// The rings of one bundle and how its triangles reach between them (see the module docs).
#[derive(Debug, Clone, Copy)]
struct RingLayout {
    rings: usize,
    /// Points per ring.
    m: usize,
    /// Points per ring at full detail: the draws' rings.
    mf: usize,
    closed: bool,
    two_intervals: bool,
    /// Ring pairs (triangles `2m` each).
    pairs: usize,
}

impl RingLayout {
    fn new(
        rings: usize,
        closed: bool,
        settings: &BundleSettings,
        draws: Option<&FullDensityDraws>,
    ) -> Self {
        let m = settings.ring_segments;
        let counts = bundle_counts(rings, m, closed);
        Self {
            rings,
            m,
            mf: draws.map_or(m, |d| d.ring_segments),
            closed,
            two_intervals: settings.two_intervals,
            pairs: counts.triangles / (2 * m),
        }
    }

    /// The ring one past `j` along the yarn (`j` itself at an open end).
    fn after(&self, j: usize) -> usize {
        match (self.closed, j + 1 < self.rings) {
            (true, _) => (j + 1) % self.rings,
            (false, true) => j + 1,
            (false, false) => j,
        }
    }

    /// The ring one before `i` along the yarn (`i` itself at an open end).
    fn before(&self, i: usize) -> usize {
        match (self.closed, i > 0) {
            (true, _) => (i + self.rings - 1) % self.rings,
            (false, true) => i - 1,
            (false, false) => i,
        }
    }

    /// Half `half` of ring pair `i` (0: the edges of ring `i`, apexes towards the ring after
    /// the next; 1: the edges of the next ring, apexes towards the ring before `i`): its
    /// edges' ring, its apexes' ring, and whether they reach that far ring (and so lean).
    /// At an open end (or round a closed piece of two rings) the apex stops at the near ring,
    /// without a lean: one interval leaves no room to lean and stay closed.
    fn half(&self, i: usize, half: usize) -> (usize, usize, bool) {
        let j = (i + 1) % self.rings;
        let (edge_ring, near, far) = if half == 0 {
            (i, j, self.after(j))
        } else {
            (j, i, self.before(i))
        };
        let reaches = self.two_intervals && far != near && far != edge_ring;
        (edge_ring, if reaches { far } else { near }, reaches)
    }

    /// The angle round its ring (radians from the frame's first axis, before the ring's
    /// phase) of the apex of edge `k` in `half`, leaning `lean` apex steps; at full detail,
    /// also its index in the `APEX_STEPS * m` apex angles.
    fn apex_angle(&self, k: usize, half: usize, lean: usize) -> (f32, Option<usize>) {
        let m = self.m;
        if m == self.mf {
            // Up to one segment past the edge's leading end, in the plies' turn: at
            // [k + 1, k + 2] segments going forward, [k - 1, k] going back.
            let steps = APEX_STEPS * m;
            let q = if half == 0 {
                ((k + 1) * APEX_STEPS + lean) % steps
            } else {
                (k * APEX_STEPS + steps - lean) % steps
            };
            return (TAU * q as f32 / steps as f32, Some(q));
        }
        // A coarser level leans as far round the yarn as full detail does (in full-detail
        // segments): leaning by its own, wider segments would send the strand through the
        // tube, where it shades as a back face.
        let turn = lean as f32 / (APEX_STEPS * self.mf) as f32;
        let angle = if half == 0 {
            TAU * ((k + 1) as f32 / m as f32 + turn)
        } else {
            TAU * (k as f32 / m as f32 - turn)
        };
        (angle, None)
    }
}

/// The plies' twist at each ring: counted in the piece's full-density samples.
fn ply_twist(i: usize, settings: &BundleSettings, draws: Option<&FullDensityDraws>) -> f32 {
    match draws {
        Some(d) => twist(d.samples[i], settings.samples_per_loop),
        None => twist(i, settings.samples_per_loop),
    }
}

/// Draws the random part of one yarn piece's bundle of `rings` rings (see the module docs
/// and [`BundleProfile`]) and, where `colors` is given (`4 * vertices` floats, linear RGBA),
/// writes its vertex colours: `owner(i)` is the (course, wale) of the stitch ring `i`
/// belongs to, `color_of(course, wale)` that stitch's linear RGB colour; `draws`: the
/// full-density stream for a span of a piece (`None`: the piece's own rings, drawn in
/// order).
pub fn bundle_profile(
    rings: usize,
    closed: bool,
    owner: &dyn Fn(usize) -> (usize, usize),
    color_of: &dyn Fn(usize, usize) -> [f32; 3],
    settings: &BundleSettings,
    draws: Option<&FullDensityDraws>,
    mut colors: Option<&mut [f32]>,
) -> BundleProfile {
    let layout = RingLayout::new(rings, closed, settings, draws);
    let (m, mf, pairs) = (layout.m, layout.mf, layout.pairs);
    let counts = bundle_counts(rings, m, closed);
    let r = settings.radius;
    let mut radial = vec![0.0f32; counts.vertices];
    let mut lean = vec![0u8; counts.triangles];
    let variation = settings.color_variation.clamp(0.0, 1.0);
    let shade = |bits: u64, c: [f32; 3]| -> [f32; 4] {
        let f = 1.0 + variation * (2.0 * unit24(bits) - 1.0);
        [c[0] * f, c[1] * f, c[2] * f, 1.0]
    };
    // The ring points' distances: the plies' outline at each.
    for i in 0..rings {
        let (phase, twist) = (ring_phase(m, i), ply_twist(i, settings, draws));
        for k in 0..m {
            let rho = ply_radius(settings.plies, TAU * k as f32 / m as f32 + phase, twist);
            radial[i * m + k] = r * rho;
        }
    }

    let apex_base = rings * m;
    // The full-detail ring point at (or just after) this level's point k.
    let full_k = |k: usize| (k * mf + m / 2) / m % mf;
    // A span's draws: the full-density stream's colour draws at each ring's sample (`mf`
    // per ring) and the triangle draws of the full-detail ring pairs its pairs start from.
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
            // every apex) is the same in a full build and a positions-only one.
            let bits = match draws {
                Some(_) => span_colours[full_k(k)],
                None => rng.next_u32(),
            };
            if let Some(colors) = colors.as_mut() {
                let v = i * m + k;
                colors[4 * v..4 * v + 4].copy_from_slice(&shade(bits as u64, color));
            }
        }
        if i >= pairs {
            continue;
        }
        for half in 0..2 {
            let (_, apex_ring, reaches) = layout.half(i, half);
            for k in 0..m {
                let tri = i * 2 * m + half * m + k;
                // One draw per triangle: 16 bits pick the apex, 24 the push, 24 the shade.
                let bits = match draws {
                    Some(_) if half == 0 => pair_draws[full_k(k)],
                    Some(_) => back_draws[mf + full_k(k)],
                    None => rng.next_u64(),
                };
                let steps = match reaches {
                    true => (((bits & 0xFFFF) * (APEX_STEPS as u64 + 1)) >> 16) as usize,
                    false => 0,
                };
                let push = 1.0 + settings.fluffiness * unit24(bits >> 16);
                let (angle, _) = layout.apex_angle(k, half, steps);
                let rho = ply_radius(
                    settings.plies,
                    angle + ring_phase(m, apex_ring),
                    ply_twist(apex_ring, settings, draws),
                );
                let av = apex_base + tri;
                radial[av] = r * push * rho;
                lean[tri] = steps as u8;
                if let Some(colors) = colors.as_mut() {
                    colors[4 * av..4 * av + 4].copy_from_slice(&shade(bits >> 40, color));
                }
            }
        }
    }
    BundleProfile { radial, lean }
}

/// Builds the bundle of one yarn piece into `out`: its draws ([`bundle_profile`], with the
/// colours where `out` takes them) swept along the centreline ([`sweep_bundle`]).
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
    let profile = bundle_profile(
        points.len(),
        closed,
        owner,
        color_of,
        settings,
        draws,
        out.colors.as_deref_mut(),
    );
    sweep_bundle(
        points, normals, closed, ends, settings, draws, &profile, out,
    );
}

/// Sweeps a bundle whose draws are `profile` along the centreline `points` (with the
/// surface normal under each sample, `normals`) into `out`: positions, and the normals,
/// tangents and topology where `out` takes them (its colours are [`bundle_profile`]'s).
/// `closed`, `settings` and `draws` must be those `profile` was drawn with; `ends`: as in
/// [`build_bundle`].
///
/// The normals it writes are the swept tube's, not the triangles': each vertex's unit
/// direction out from its ring's centre in the ring's plane (a ring point's ring direction,
/// an apex's direction at its angle). The triangles are fibres lying on that tube, and
/// shading them as the tube (Gouraud shading with the cylinder's normals, as the paper does)
/// shows their randomness as texture, not as facets. They depend only on the ring frames, so
/// a culled knit and every frame of an animated one get them alike.
///
/// The tangents it writes are the fibres' directions at each vertex, for a material's
/// anisotropic highlight: unit, perpendicular to the vertex's normal, along the yarn and
/// slanted round it as the plies' helix through that point runs (slope round the yarn per
/// unit along it: the point's distance from the centreline, at most the yarn radius, times
/// [`super::plies::twist_rate`] over the span's length; an apex pushed out by the fluff
/// keeps the slant of the yarn's surface). A one-ply yarn slants the same way: its fibres
/// are twisted too. Like the normals they depend only on the centreline, so a culled knit
/// and every frame of an animated one get them alike.
#[allow(clippy::too_many_arguments)]
pub fn sweep_bundle(
    points: &[Vec3],
    normals: &[Vec3],
    closed: bool,
    ends: EndTangents,
    settings: &BundleSettings,
    draws: Option<&FullDensityDraws>,
    profile: &BundleProfile,
    out: &mut PieceBuffers,
) {
    let rings = points.len();
    let layout = RingLayout::new(rings, closed, settings, draws);
    let (m, pairs) = (layout.m, layout.pairs);
    let r = settings.radius;
    let radial = &profile.radial;
    debug_assert_eq!(radial.len(), bundle_counts(rings, m, closed).vertices);
    let (cos, sin): (Vec<f32>, Vec<f32>) = (0..m)
        .map(|k| TAU * k as f32 / m as f32)
        .map(|a| {
            let (s, c) = crate::portable_math::sin_cos(a);
            (c, s)
        })
        .unzip();

    // How fast the twist turns along this span, radians per scene unit: its full-density
    // samples' turns over its length. Even along the yarn, as real yarn's twist is: the
    // samples bunch where the yarn curves (eight times closer at a loop's head than along
    // its legs), and counted sample by sample the slant would swing with them.
    let turn_rate = match out.tangents {
        None => 0.0,
        Some(_) => {
            let sample_of = |i: usize| draws.map_or(i, |d| d.samples[i]);
            let full_samples = draws.map_or(rings, |d| d.streams.len());
            let mut length: f32 = points.windows(2).map(|w| (w[1] - w[0]).length()).sum();
            let samples = if closed {
                length += (points[0] - points[rings - 1]).length();
                full_samples
            } else {
                // A span of a closed piece may run on past its seam, where the samples'
                // numbers start again from 0.
                (sample_of(rings - 1) + full_samples - sample_of(0)) % full_samples.max(1)
            };
            twist_rate(samples, length, settings.samples_per_loop)
        }
    };
    // Ring frames, kept for the apexes (which sit between ring points).
    let mut frames = vec![(Vec3::ZERO, Vec3::ZERO); rings];
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
        let (phase_sin, phase_cos) = crate::portable_math::sin_cos(ring_phase(m, i));
        let (a, b) = (phase_cos * a + phase_sin * b, phase_cos * b - phase_sin * a);
        frames[i] = (a, b);
        for k in 0..m {
            let v = i * m + k;
            let d = cos[k] * a + sin[k] * b;
            if let Some(n) = out.normals.as_mut() {
                n[3 * v..3 * v + 3].copy_from_slice(&d.to_array());
            }
            if let Some(t) = out.tangents.as_mut() {
                let f = fibre_direction(a.cross(b), d, radial[v] * turn_rate);
                t[3 * v..3 * v + 3].copy_from_slice(&f.to_array());
            }
            let p = points[i] + radial[v] * d;
            out.positions[3 * v..3 * v + 3].copy_from_slice(&p.to_array());
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

    let apex_base = rings * m;
    // The apex angles of full detail: APEX_STEPS per ring segment.
    let steps = APEX_STEPS * m;
    let (apex_cos, apex_sin): (Vec<f32>, Vec<f32>) = (0..steps)
        .map(|q| TAU * q as f32 / steps as f32)
        .map(|a| {
            let (s, c) = crate::portable_math::sin_cos(a);
            (c, s)
        })
        .unzip();
    for i in 0..pairs {
        // Two halves: the edges of ring i with apexes on the ring after j, then the edges of
        // ring j with apexes on the ring before i (see the module docs).
        for half in 0..2 {
            let (edge_ring, apex_ring, _) = layout.half(i, half);
            let (a, b) = frames[apex_ring];
            let along = out.tangents.is_some().then(|| a.cross(b));
            for k in 0..m {
                let tri = i * 2 * m + half * m + k;
                let av = apex_base + tri;
                let (cos_a, sin_a) = match layout.apex_angle(k, half, profile.lean[tri] as usize) {
                    (_, Some(q)) => (apex_cos[q], apex_sin[q]),
                    (angle, None) => {
                        let (s, c) = crate::portable_math::sin_cos(angle);
                        (c, s)
                    }
                };
                let apex_dir = cos_a * a + sin_a * b;
                let apex = points[apex_ring] + radial[av] * apex_dir;
                out.positions[3 * av..3 * av + 3].copy_from_slice(&apex.to_array());
                if let Some(n) = out.normals.as_mut() {
                    n[3 * av..3 * av + 3].copy_from_slice(&apex_dir.to_array());
                }
                if let (Some(t), Some(along)) = (out.tangents.as_mut(), along) {
                    // A pushed-out strand keeps the slant of the surface it stands from.
                    let f = fibre_direction(along, apex_dir, radial[av].min(r) * turn_rate);
                    t[3 * av..3 * av + 3].copy_from_slice(&f.to_array());
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
            two_intervals: true,
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

    /// A straight yarn along x (rings at x = 0, 1, 2, ...) of `rings` rings of `m` points.
    fn straight_tube(rings: usize, m: usize, fluffiness: f32) -> (Vec<f32>, Vec<f32>) {
        let (positions, colors, _) = plied_tube(rings, m, fluffiness, 1);
        (positions, colors)
    }

    /// [`straight_tube`] of `plies` plies: its positions, colours and normals.
    fn plied_tube(
        rings: usize,
        m: usize,
        fluffiness: f32,
        plies: usize,
    ) -> (Vec<f32>, Vec<f32>, Vec<f32>) {
        let (positions, colors, normals, _) = plied_tube_shading(rings, m, fluffiness, plies);
        (positions, colors, normals)
    }

    /// [`plied_tube`], and its tangents.
    fn plied_tube_shading(
        rings: usize,
        m: usize,
        fluffiness: f32,
        plies: usize,
    ) -> (Vec<f32>, Vec<f32>, Vec<f32>, Vec<f32>) {
        let points: Vec<Vec3> = (0..rings).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
        let settings = BundleSettings {
            radius: 0.25,
            ring_segments: m,
            fluffiness,
            color_variation: 0.2,
            seed: 9,
            plies,
            samples_per_loop: 16,
            two_intervals: true,
        };
        let counts = bundle_counts(rings, m, false);
        let mut positions = vec![0.0; 3 * counts.vertices];
        let mut colors = vec![0.0; 4 * counts.vertices];
        let mut normals = vec![0.0; 3 * counts.vertices];
        let mut tangents = vec![0.0; 3 * counts.vertices];
        let mut bufs = PieceBuffers::positions_only(&mut positions);
        bufs.colors = Some(&mut colors);
        bufs.normals = Some(&mut normals);
        bufs.tangents = Some(&mut tangents);
        build_bundle(
            &points,
            &vec![Vec3::Z; rings],
            &|i| (0, i / 16),
            &|_, _| [0.5, 0.5, 0.5],
            false,
            EndTangents::default(),
            &settings,
            None,
            &mut bufs,
        );
        (positions, colors, normals, tangents)
    }

    /// A point of the straight tube as (angle round the axis in ring segments from ring
    /// point 0, in the ring's point order, in [0, m); distance along the axis).
    fn tube_coordinates(positions: &[f32], m: usize, v: usize) -> (f32, f32) {
        let angle = |v: usize| positions[3 * v + 2].atan2(positions[3 * v + 1]);
        let (a0, a1) = (angle(0), angle(1));
        let turn = if (a1 - a0).rem_euclid(TAU) < std::f32::consts::PI {
            1.0
        } else {
            -1.0
        };
        let segments = (turn * (angle(v) - a0)).rem_euclid(TAU) / TAU * m as f32;
        (segments % m as f32, positions[3 * v])
    }

    /// Every apex lies on the ring two intervals along the yarn from its edge (the end ring
    /// at an open end), leans 0 to 1 segment past its edge's end the way the plies turn,
    /// is pushed out between 1 and 1 + fluffiness radii, and every lean is drawn.
    #[test]
    fn apexes_lie_along_the_tube_two_rings_on_leaning_with_the_twist() {
        let (rings, m) = (400usize, 6usize);
        let (positions, colors) = straight_tube(rings, m, 0.8);
        let counts = bundle_counts(rings, m, false);
        let mut leans = [0usize; APEX_STEPS + 1];
        for tri in 0..counts.triangles {
            let (pair, half, k) = (tri / (2 * m), tri % (2 * m) / m, tri % m);
            // The end ring, without a lean, where the yarn ends first.
            let (want_ring, reaches) = if half == 0 {
                ((pair + 2).min(rings - 1), pair + 2 < rings)
            } else {
                (pair.saturating_sub(1), pair > 0)
            };
            let av = rings * m + tri;
            let p = Vec3::from_slice(&positions[3 * av..3 * av + 3]);
            assert!(
                (p.x - want_ring as f32).abs() < 1e-5,
                "triangle {tri}: apex at x = {}, not on ring {want_ring}",
                p.x
            );
            let push = Vec3::new(0.0, p.y, p.z).length() / 0.25;
            assert!((1.0 - 1e-5..=1.8 + 1e-5).contains(&push), "push {push}");
            // Segments past the edge's leading end: k + 1 going forward, k going back.
            let (angle, _) = tube_coordinates(&positions, m, av);
            let mut past = if half == 0 {
                angle - (k + 1) as f32
            } else {
                k as f32 - angle
            }
            .rem_euclid(m as f32);
            if past > 0.5 * m as f32 {
                past -= m as f32;
            }
            let lean = past * APEX_STEPS as f32;
            let most = if reaches { APEX_STEPS as f32 } else { 0.0 };
            assert!(
                lean > -1e-3 && lean <= most + 1e-3 && (lean - lean.round()).abs() < 1e-3,
                "triangle {tri} (half {half}, edge {k}): apex {past} segments past its edge"
            );
            if reaches {
                leans[lean.round() as usize] += 1;
            }
            let shade = colors[4 * av] / 0.5;
            assert!((0.8 - 1e-6..=1.2 + 1e-6).contains(&shade), "shade {shade}");
        }
        let expected = leans.iter().sum::<usize>() as f32 / leans.len() as f32;
        for (q, &n) in leans.iter().enumerate() {
            assert!(
                (n as f32 - expected).abs() < 0.1 * expected,
                "lean {q} drawn {n} times, expected about {expected}"
            );
        }
    }

    /// At fluffiness 0 the bundle is a closed tube: every point of the tube's surface from
    /// the first ring to the last, in (angle, length), lies in one of its triangles.
    #[test]
    fn fluffiness_zero_leaves_no_gap_in_the_tube() {
        let (rings, m) = (24usize, 6usize);
        let (positions, _) = straight_tube(rings, m, 0.0);
        let counts = bundle_counts(rings, m, false);
        // Every triangle in (angle, length), its angles unwrapped round its first corner, and
        // again one turn on (so that a point near angle 0 finds the triangles across it).
        let mut flat: Vec<[(f32, f32); 3]> = Vec::new();
        for tri in 0..counts.triangles {
            let (pair, half, k) = (tri / (2 * m), tri % (2 * m) / m, tri % m);
            let ring = pair + half;
            let (a, b) = (ring * m + k, ring * m + (k + 1) % m);
            let corners = [a, b, rings * m + tri].map(|v| tube_coordinates(&positions, m, v));
            let first = corners[0].0;
            let unwrapped = corners.map(|(angle, x)| {
                let mut angle = angle;
                while angle - first > 0.5 * m as f32 {
                    angle -= m as f32;
                }
                while first - angle > 0.5 * m as f32 {
                    angle += m as f32;
                }
                (angle, x)
            });
            flat.push(unwrapped);
            flat.push(unwrapped.map(|(angle, x)| (angle + m as f32, x)));
            flat.push(unwrapped.map(|(angle, x)| (angle - m as f32, x)));
        }
        let inside = |t: &[(f32, f32); 3], (px, py): (f32, f32)| {
            let cross = |(ax, ay): (f32, f32), (bx, by): (f32, f32)| {
                (bx - ax) * (py - ay) - (by - ay) * (px - ax)
            };
            let s = [cross(t[0], t[1]), cross(t[1], t[2]), cross(t[2], t[0])];
            s.iter().all(|&c| c >= -1e-5) || s.iter().all(|&c| c <= 1e-5)
        };
        let (na, nx) = (6 * m * 7, 8 * (rings - 1) * 5);
        for i in 0..na {
            for j in 0..=nx {
                let point = (
                    (i as f32 + 0.37) / na as f32 * m as f32,
                    j as f32 / nx as f32 * (rings - 1) as f32,
                );
                assert!(
                    flat.iter().any(|t| inside(t, point)),
                    "a gap in the tube at {point:?} (segments, rings)"
                );
            }
        }
    }

    /// The normals are the tube's: every vertex's, ring point or apex, is the unit direction
    /// from the centreline straight out to it (a straight yarn along x: `(0, y, z)`
    /// normalised), with plies and fluff, and the positions do not depend on whether they
    /// are written.
    #[test]
    fn normals_point_straight_out_from_the_centreline() {
        let (rings, m) = (40usize, 6usize);
        let (positions, _, normals) = plied_tube(rings, m, 0.8, 3);
        for v in 0..positions.len() / 3 {
            let p = Vec3::from_slice(&positions[3 * v..3 * v + 3]);
            let n = Vec3::from_slice(&normals[3 * v..3 * v + 3]);
            let out = Vec3::new(0.0, p.y, p.z).normalize();
            assert!(
                n.distance(out) < 1e-5,
                "vertex {v} at {p}: normal {n}, the tube's {out}"
            );
        }
        // The same yarn built without normals (`straight_yarn_of` sweeps it at fluffiness
        // 0.8 too): writing them leaves the positions as they are.
        let all: Vec<usize> = (0..rings).collect();
        assert_eq!(straight_yarn_of(&all, m, None, 3).0, positions);
    }

    /// The tangents are the fibres' directions: unit, across the normal, forward along the
    /// yarn, and slanted round it as the plies' helix through each vertex runs. On the
    /// straight tube (rings a unit apart, 16 per loop, 4 turns a loop: the grooves turn
    /// pi/2 radians per unit) a vertex at distance `rho` from the axis slants by
    /// `atan(min(rho, radius) * pi / 2)`, the way the grooves turn, at ring points and
    /// apexes alike.
    #[test]
    fn tangents_follow_the_plies_helix_across_the_normal() {
        let (rings, m) = (40usize, 6usize);
        for plies in [1, 3] {
            let (positions, _, normals, tangents) = plied_tube_shading(rings, m, 0.8, plies);
            let at = |buf: &[f32], v: usize| Vec3::from_slice(&buf[3 * v..3 * v + 3]);
            let mut slants = Vec::new();
            for v in 0..positions.len() / 3 {
                let (p, n, t) = (at(&positions, v), at(&normals, v), at(&tangents, v));
                assert!((t.length() - 1.0).abs() < 1e-5, "vertex {v}: tangent {t}");
                assert!(
                    t.dot(n).abs() < 1e-5,
                    "vertex {v}: tangent {t} on normal {n}"
                );
                let rho = Vec3::new(0.0, p.y, p.z).length().min(0.25);
                let slope = t.dot(Vec3::X.cross(n)) / t.x;
                assert!(
                    t.x > 0.0,
                    "vertex {v}: tangent {t} runs back along the yarn"
                );
                assert!(
                    (slope - rho * std::f32::consts::FRAC_PI_2).abs() < 1e-4,
                    "{plies} plies, vertex {v} at {p}: slope {slope}, helix {}",
                    rho * std::f32::consts::FRAC_PI_2
                );
                slants.push(slope.atan().to_degrees());
            }
            // Grooves spread the slant: about 21 degrees at the yarn's radius.
            let (lo, hi) = slants
                .iter()
                .fold((f32::MAX, f32::MIN), |(a, b), &s| (a.min(s), b.max(s)));
            assert!(
                lo > 10.0 && hi < 40.0,
                "{plies} plies: slants {lo}..{hi} degrees"
            );
        }
        // The grooves of a 3-ply tube turn the way the tangents slant: following a ring
        // point's tangent one unit along the yarn lands on the next ring's point with the
        // same radius (24 points a ring: pi/2 radians is 6 of them).
        let m = 24;
        let (positions, _, normals, tangents) = plied_tube_shading(rings, m, 0.0, 3);
        let at = |buf: &[f32], v: usize| Vec3::from_slice(&buf[3 * v..3 * v + 3]);
        let radius = |v: usize| Vec3::new(0.0, positions[3 * v + 1], positions[3 * v + 2]);
        for i in 0..rings - 1 {
            for k in 0..m {
                let v = i * m + k;
                let (n, t) = (at(&normals, v), at(&tangents, v));
                let turn = t.dot(Vec3::X.cross(n)) / t.x / radius(v).length();
                // Which way round is `k + 1`: towards x cross (out) or away from it.
                let next_point = radius(i * m + (k + 1) % m);
                let sense = next_point.dot(Vec3::X.cross(n)).signum();
                let step = (sense * turn * m as f32 / TAU).round() as isize;
                let landed = (i + 1) * m + (k as isize + step).rem_euclid(m as isize) as usize;
                assert!(
                    (radius(landed).length() - radius(v).length()).abs() < 1e-4,
                    "ring {i} point {k}: the tangent leads {step} points round, off the groove"
                );
            }
        }
    }

    /// A span of a closed piece that runs on past the piece's seam (its full-density samples
    /// 60..63 then 0..3 of 64) slants its fibres as any other span: the samples it spans
    /// are counted round the seam.
    #[test]
    fn a_span_across_a_closed_pieces_seam_slants_its_fibres_as_any_other() {
        let (n, m) = (64usize, 6usize);
        let samples: Vec<usize> = (60..64).chain(0..4).collect();
        let streams = piece_streams(n, |i| stitch_seed(9, 0, i / 16));
        let draws = FullDensityDraws {
            samples: &samples,
            streams: &streams,
            ring_segments: m,
        };
        // Rings a unit apart along x, one full-density sample apart.
        let points: Vec<Vec3> = (0..samples.len())
            .map(|i| Vec3::new(i as f32, 0.0, 0.0))
            .collect();
        let settings = BundleSettings {
            radius: 0.25,
            ring_segments: m,
            fluffiness: 0.0,
            color_variation: 0.2,
            seed: 9,
            plies: 1,
            samples_per_loop: 16,
            two_intervals: true,
        };
        let counts = bundle_counts(samples.len(), m, false);
        let mut positions = vec![0.0; 3 * counts.vertices];
        let mut normals = vec![0.0; 3 * counts.vertices];
        let mut tangents = vec![0.0; 3 * counts.vertices];
        let mut bufs = PieceBuffers::positions_only(&mut positions);
        bufs.normals = Some(&mut normals);
        bufs.tangents = Some(&mut tangents);
        build_bundle(
            &points,
            &vec![Vec3::Z; samples.len()],
            &|i| (0, samples[i] / 16),
            &|_, _| [0.5, 0.5, 0.5],
            false,
            EndTangents::default(),
            &settings,
            Some(&draws),
            &mut bufs,
        );
        let at = |buf: &[f32], v: usize| Vec3::from_slice(&buf[3 * v..3 * v + 3]);
        for v in 0..counts.vertices {
            let (n, t) = (at(&normals, v), at(&tangents, v));
            let slope = t.dot(Vec3::X.cross(n)) / t.x;
            // A quarter turn per unit at the yarn's radius, as on a span that does not wrap.
            assert!(
                (slope - 0.25 * std::f32::consts::FRAC_PI_2).abs() < 1e-4,
                "vertex {v}: slope {slope}"
            );
        }
    }

    /// Degrees between each triangle's shading normal at its centroid (its corners' normals
    /// averaged, as Gouraud shading interpolates them) and the round yarn's there (straight
    /// out from the axis), for the straight tube along x laid out as [`build_bundle`] writes.
    fn off_round(positions: &[f32], normals: &[f32], rings: usize, m: usize) -> Vec<f32> {
        let triangles = bundle_counts(rings, m, false).triangles;
        let at = |buf: &[f32], v: usize| Vec3::from_slice(&buf[3 * v..3 * v + 3]);
        (0..triangles)
            .map(|tri| {
                let (pair, half, k) = (tri / (2 * m), tri % (2 * m) / m, tri % m);
                let ring = pair + half;
                let corners = [ring * m + k, ring * m + (k + 1) % m, rings * m + tri];
                let centroid = corners.iter().map(|&v| at(positions, v)).sum::<Vec3>() / 3.0;
                let shading = corners.iter().map(|&v| at(normals, v)).sum::<Vec3>();
                let round = Vec3::new(0.0, centroid.y, centroid.z);
                shading.angle_between(round).to_degrees()
            })
            .collect()
    }

    /// Blender's smooth normals of the straight tube's triangles: at each vertex the unit
    /// normals of its triangles weighted by their angles there (an apex has one triangle).
    fn blender_normals(positions: &[f32], rings: usize, m: usize) -> Vec<f32> {
        let counts = bundle_counts(rings, m, false);
        let at = |v: usize| Vec3::from_slice(&positions[3 * v..3 * v + 3]);
        let mut sum = vec![Vec3::ZERO; counts.vertices];
        for tri in 0..counts.triangles {
            let (pair, half, k) = (tri / (2 * m), tri % (2 * m) / m, tri % m);
            let ring = pair + half;
            let (a, b) = (ring * m + k, ring * m + (k + 1) % m);
            let t = if half == 0 {
                [a, b, rings * m + tri]
            } else {
                [b, a, rings * m + tri]
            };
            let n = (at(t[1]) - at(t[0])).cross(at(t[2]) - at(t[0])).normalize();
            for c in 0..3 {
                let e0 = (at(t[(c + 1) % 3]) - at(t[c])).normalize();
                let e1 = (at(t[(c + 2) % 3]) - at(t[c])).normalize();
                sum[t[c]] += n * e0.angle_between(e1);
            }
        }
        sum.iter().flat_map(|s| s.normalize().to_array()).collect()
    }

    /// The faceting measure: the share of triangles whose shading strays more than 30
    /// degrees from the round yarn's. With the tube's normals no strand does, at any
    /// fluffiness; with the normals Blender computes from the same triangles many do, which
    /// is what read as facets and shards.
    #[test]
    fn the_tubes_normals_shade_every_strand_as_a_round_yarn() {
        let (rings, m) = (200usize, 6usize);
        let share = |angles: &[f32]| {
            angles.iter().filter(|&&a| a > 30.0).count() as f32 / angles.len() as f32
        };
        for fluffiness in [0.0, 0.5, 1.5] {
            let (positions, _, normals) = plied_tube(rings, m, fluffiness, 1);
            let ours = off_round(&positions, &normals, rings, m);
            let blender = off_round(&positions, &blender_normals(&positions, rings, m), rings, m);
            let worst = ours.iter().fold(0.0f32, |a, &b| a.max(b));
            assert!(
                share(&ours) == 0.0,
                "fluffiness {fluffiness}: a strand shades {worst} degrees off the round yarn"
            );
            assert!(
                share(&blender) > 0.15,
                "fluffiness {fluffiness}: Blender's normals stray on {} of the strands",
                share(&blender)
            );
        }
    }

    /// A 3-point ring alternates: every other ring turns half a segment round the yarn (an
    /// antiprism), while any other ring (mid's five, full detail's six) keeps every ring as
    /// its frame has it.
    #[test]
    fn a_three_point_ring_turns_half_a_segment_every_other_ring() {
        let angle = |positions: &[f32], v: usize| {
            let p = Vec3::from_slice(&positions[3 * v..3 * v + 3]);
            p.y.atan2(p.z) // round the x axis, from the surface normal (z)
        };
        for m in [3, 5, 6] {
            let (positions, _) = straight_yarn(&[0, 1, 2, 3], m, None);
            for ring in 0..4 {
                let expected = if m == 3 && ring % 2 == 1 {
                    std::f32::consts::PI / m as f32
                } else {
                    0.0
                };
                let first = angle(&positions, ring * m);
                assert!(
                    (first.abs() - expected).abs() < 1e-5,
                    "m {m}, ring {ring}: first point at {first} rad, expected {expected}"
                );
            }
        }
    }
}
