//! Keeps a cast-on or bind-off a yarn diameter clear of the fabric it finishes.
//!
//! The edges' key points ([`super::edges`]) are placed from the tuned offsets of the rows
//! they meet, so that each crossing has the side the interlock gives it. Between key points,
//! though, the edge's yarn and the fabric's may both be on their way from one side to the
//! other where they cross (a foot climbing from its sinker to its leg past a leg climbing to
//! its head), and the stitch irregularity moves such a crossing along both yarns to where
//! their depths meet: feather and fan's bind-off came within 0.025 diameters of the last
//! course at the add-on's irregularity (0.005).
//!
//! So the edge's samples are measured against the fabric's centreline where it could reach
//! them (the stitches of the edge's course and the courses beside it, over the columns its
//! loops can lean across), and the edge moves along the normal, never across:
//!
//! - **Sides.** Where the edge crosses a fabric yarn in (u, v), it keeps to the side the
//!   crossing's rule gives ([`super::crossings`]) from that yarn, near the crossing; from
//!   every other yarn near it, to the side it is on. So every crossing keeps its order and
//!   only its gap grows: a clearance won by flipping a loop is not on offer.
//! - **Room.** Each point of the edge's polyline (four a segment) keeps [`CLEARANCE`] from
//!   every fabric sample near it, or where yarns on both sides leave less room, as much as
//!   there is (the point then sits as far from both as it can).
//! - **Chain.** A bind-off loop's head keeps a diameter from the next loop's left leg where
//!   they cross, on the chain's side: both move. Without it, a sinker pushed back past the
//!   leg tops of linen stitch's last row dragged the next leg back through the head it holds
//!   (0.004 diameters apart). The yarn from the left leg top to the head keeps what a
//!   diameter leaves in depth where it passes near the next leg's top without crossing it
//!   (stockinette's bind-off sampled twice as densely: 0.949 diameters, 0.970 kept).
//! - **Moves.** A projected Jacobi iteration meets those bounds, relaxing the moves along
//!   the yarn after each sweep so that the edge bends rather than kinks. They take it no
//!   further out of the surface than the fabric's own yarn there: an edge is no thicker
//!   than the fabric it finishes.
//!
//! The fabric is never moved: it is the same, bit for bit, as with live loops. Measured at
//! the add-on's irregularity on a 12 cm sheet, feather and fan's edges went from 0.025 to
//! 0.39 diameters (the fabric's own closest pair is 0.34), twisted rib's 0.77 to 0.88, and
//! twisted cable rib's 0.51 to 0.79 (docs/design.md section 3.6).
//!
//! Units: samples in (u, v, lambda), lambda in scene units; distances in scene units, with
//! (u, v) steps mapped by the surface's tangents at the edge stitch.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::crossings::{edge_in_front, intersect};
use super::curvature::{clamp_offsets, stitch_curvature_radii};
use super::edges::Edge;
use super::knot_spacing::{course_leans_far, knot_spacing};
use super::stitch_shape::{landing, stitch_key_points};
use super::{CardinalSpline, NormalOffsets, SplineSampling, YarnPiece, KEY_POINTS};
use crate::lattice::Lattice;
use crate::pattern::StitchPattern;
use crate::surface::Surface;

/// How far an edge keeps from the fabric's yarn, in yarn diameters (centreline to
/// centreline: the yarns touch).
pub const CLEARANCE: f32 = 1.0;
/// Bisection steps for the room between yarns on both sides of an edge (to 2^-12 of the
/// clearance).
const BISECTIONS: usize = 12;
/// Sweeps of the constraint projection, and relaxation steps of the moves after each: the
/// moves spread a few samples either way, so the edge bends rather than kinks.
const SWEEPS: usize = 32;
const SMOOTHING: usize = 2;
/// Points measured per segment of the edge's polyline.
const SUBDIVISIONS: usize = 4;
/// Fabric points per loop to measure against, at least: the knit's own samples and points
/// along the chords between them, so that the gap is measured near its narrowest on the
/// polyline the knit draws.
const FABRIC_SAMPLES_PER_LOOP: usize = 32;
/// How many columns a fabric loop can lean across (a 4/4 cable leans four; twisted
/// decreases further), beyond which its yarn cannot pass an edge stitch.
const REACH: isize = 7;

/// Moves the samples `samples` (in (u, v, lambda), at the spline parameters `t`) of the edge
/// piece `piece` clear of the fabric, as the module says.
#[allow(clippy::too_many_arguments)]
pub fn keep_clear(
    surface: &dyn Surface,
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    sampling: &SplineSampling,
    piece: &YarnPiece,
    t: &[f32],
    samples: &mut [Vec3],
) {
    let n = samples.len();
    if n < 2 {
        return;
    }
    let clearance = CLEARANCE * offsets.diameter;
    let fabric = FabricNear::new(surface, lattice, pattern, offsets, sampling, piece);
    let stitch_of = |j: usize| ((t[j] / KEY_POINTS as f32) as usize).min(piece.stitches - 1);
    let period = lattice.tile.x * lattice.wales as f32;
    let segments = if piece.closed { n } else { n - 1 };
    // Segment j's ends, with their spline parameters (a closed ring comes back to its start
    // one period on).
    let ends = |j: usize| {
        let next = (j + 1) % n;
        let (mut b, mut tb) = (samples[next], t[next]);
        if next == 0 {
            b.x += period;
            tb = (KEY_POINTS * piece.stitches) as f32;
        }
        ((j, samples[j], t[j]), (next, b, tb))
    };
    // The fabric samples near each segment, found once for both passes below (finding
    // them was most of an edge's time, and a seventh of an animated knit's per frame), in
    // parallel: an edge is one long piece, which the other pieces' threads would otherwise
    // wait for (14,000 stitches: 9 of the cast-on's 15 ms per frame). Collected in order,
    // so the passes see the same lists on any thread count.
    let near: Vec<_> = (0..segments)
        .into_par_iter()
        .map(|j| {
            let ((_, a, _), (_, b, _)) = ends(j);
            fabric.pairs(a, b, &fabric.metrics[stitch_of(j)], clearance)
        })
        .collect();
    // Where the edge crosses the fabric, per fabric stitch: every point of the edge near a
    // crossing keeps to its side of the yarn there.
    let mut crossings = vec![Vec::new(); fabric.lines.len()];
    for (j, pairs) in near.iter().enumerate() {
        let (a, b) = ends(j);
        fabric.crossings(
            a,
            b,
            pairs,
            |t, f| edge_in_front(lattice, pattern, piece, t, f.course, f.wale, f.t),
            &mut crossings,
        );
    }
    let mut constraints = Vec::new();
    for (j, pairs) in near.iter().enumerate() {
        let (a, b) = ends(j);
        fabric.constraints(
            a,
            b,
            pairs,
            &fabric.metrics[stitch_of(j)],
            clearance,
            &crossings,
            &mut constraints,
        );
    }
    let chain = chain_crossings(
        lattice,
        pattern,
        piece,
        t,
        samples,
        &fabric.metrics,
        clearance,
    );
    if constraints.is_empty() && chain.is_empty() {
        return;
    }
    // Projected Jacobi iteration on the moves (lambda only: the gaps across, in (u, v), stay
    // as they are): each sweep asks the two samples of every unmet constraint to move just
    // far enough (in proportion to their weight at its point), moves each sample by the
    // mean of what it is asked, then relaxes the moves along the yarn, which spreads each
    // into a smooth bump. Where yarns on both sides leave less room than the clearance,
    // the asks balance and the edge settles between them.
    let mut moves = vec![0.0f32; n];
    let mut next_moves = vec![0.0f32; n];
    let mut asked = vec![(0.0f32, 0u32); n];
    for _ in 0..SWEEPS {
        asked.fill((0.0, 0));
        for c in &constraints {
            let z =
                (1.0 - c.s) * (samples[c.a].z + moves[c.a]) + c.s * (samples[c.b].z + moves[c.b]);
            let short = c.bound - c.side * z;
            if short > 0.0 {
                let (wa, wb) = (1.0 - c.s, c.s);
                let k = c.side * short / (wa * wa + wb * wb);
                for (i, w) in [(c.a, wa), (c.b, wb)] {
                    if w > 0.0 {
                        asked[i].0 += k * w;
                        asked[i].1 += 1;
                    }
                }
            }
        }
        // The chain's own crossings: both yarns are the edge's, so both give way.
        for c in &chain {
            let z = |(a, b, s): (usize, usize, f32)| {
                (1.0 - s) * (samples[a].z + moves[a]) + s * (samples[b].z + moves[b])
            };
            let short = c.room - c.side * (z(c.head) - z(c.leg));
            if short > 0.0 {
                for ((a, b, s), sign) in [(c.head, c.side), (c.leg, -c.side)] {
                    let (wa, wb) = (1.0 - s, s);
                    let k = 0.5 * sign * short / (wa * wa + wb * wb);
                    for (i, w) in [(a, wa), (b, wb)] {
                        if w > 0.0 {
                            asked[i].0 += k * w;
                            asked[i].1 += 1;
                        }
                    }
                }
            }
        }
        for (m, &(sum, count)) in moves.iter_mut().zip(&asked) {
            if count > 0 {
                *m += sum / count as f32;
            }
        }
        for _ in 0..SMOOTHING {
            for i in 0..n {
                let (l, r) = if piece.closed {
                    ((i + n - 1) % n, (i + 1) % n)
                } else {
                    (i.saturating_sub(1), (i + 1).min(n - 1))
                };
                next_moves[i] = moves[i] + 0.25 * (moves[l] - 2.0 * moves[i] + moves[r]);
            }
            std::mem::swap(&mut moves, &mut next_moves);
        }
    }
    for (j, (q, m)) in samples.iter_mut().zip(moves).enumerate() {
        // The moves take the edge no further out of the surface, on either side, than the
        // fabric's own yarn near it (or the edge itself already stood): an edge is no
        // thicker than the fabric it finishes.
        let out = fabric.thickness.max(q.z.abs());
        q.z = (q.z + m).clamp(-out, out);
        clamp_offsets(std::slice::from_mut(q), fabric.radii[stitch_of(j)]);
    }
}

/// Where a bind-off loop's head crosses the next loop's left leg (the chain), and the side
/// the head keeps: the points a fraction of the way along the segments between two samples
/// (first sample, second, fraction) of the head and of the leg.
#[derive(Debug, Clone, Copy)]
struct ChainCrossing {
    head: (usize, usize, f32),
    leg: (usize, usize, f32),
    /// +1: the head in front of the leg (the next loop purled), -1 behind (knitted).
    side: f32,
    /// The depth they keep between them there (scene units): the clearance where they cross
    /// in (u, v), what it leaves where they pass nearer than it without crossing.
    room: f32,
}

/// The chain crossings of the bind-off `piece` (none for a cast-on): its samples `samples`
/// at spline parameters `t`, before any move. The edge keeps them a diameter apart on the
/// side [`super::crossings`] gives them while it moves clear of the fabric: a move that
/// spreads along the yarn from a sinker pushed back must not drag the next loop's leg through
/// the head it holds.
fn chain_crossings(
    lattice: &Lattice,
    pattern: &StitchPattern,
    piece: &YarnPiece,
    t: &[f32],
    samples: &[Vec3],
    metrics: &[Metric],
    clearance: f32,
) -> Vec<ChainCrossing> {
    let mut out = Vec::new();
    if piece.edge != Some(Edge::BindOff) || piece.stitches < 2 {
        return out;
    }
    let n = samples.len();
    let k = KEY_POINTS as f32;
    let period = lattice.tile.x * lattice.wales as f32;
    let segments = if piece.closed { n } else { n - 1 };
    // Each segment, with its stitch and its parameter within that stitch (at its start).
    let seg = |j: usize| {
        let next = (j + 1) % n;
        let mut b = samples[next];
        if next == 0 {
            b.x += period;
        }
        let stitch = ((t[j] / k) as usize).min(piece.stitches - 1);
        (samples[j], b, stitch, t[j] - stitch as f32 * k, next)
    };
    let heads: Vec<usize> = (0..segments)
        .filter(|&j| (2.0..4.0).contains(&seg(j).3))
        .collect();
    let legs: Vec<usize> = (0..segments)
        .filter(|&j| (0.5..2.5).contains(&seg(j).3))
        .collect();
    for &h in &heads {
        let (h0, h1, stitch, _, h_next) = seg(h);
        let following = stitch + 1;
        let wraps = following == piece.stitches;
        if wraps && !piece.closed {
            continue;
        }
        let following = following % piece.stitches;
        // The next loop's face, as the chain's rule reads it ([`super::crossings`]).
        let wale = (piece.first_wale + following) % lattice.wales;
        let knit = super::edges::worked_face(lattice, pattern, piece.course + 1, wale)
            == crate::pattern::Face::Knit;
        for &l in legs.iter().filter(|&&l| seg(l).2 == following) {
            let (mut l0, mut l1, _, _, l_next) = seg(l);
            if wraps {
                l0.x += period;
                l1.x += period;
            }
            // A crossing keeps the clearance in depth; a pass nearer than it in (u, v), the
            // rest of it.
            let metric = &metrics[stitch];
            let near = || {
                let (s, r) = metric.nearest(h0, h1, l0, l1);
                let planar = metric.length((h0.lerp(h1, s) - l0.lerp(l1, r)).truncate());
                (planar < clearance)
                    .then(|| (s, r, (clearance * clearance - planar * planar).sqrt()))
            };
            if let Some((s, r, room)) = intersect(h0, h1, l0, l1)
                .map(|(s, r, ..)| (s, r, clearance))
                .or_else(near)
            {
                out.push(ChainCrossing {
                    head: (h, h_next, s),
                    leg: (l, l_next, r),
                    side: if knit { -1.0 } else { 1.0 },
                    room,
                });
            }
        }
    }
    out
}

/// That the point a fraction `s` of the way from sample `a` to sample `b` of an edge stays
/// on side `side` (+1 in front, -1 behind) of a fabric yarn, at least `bound` (signed
/// lambda: `side * lambda >= bound`).
#[derive(Debug, Clone, Copy)]
struct Constraint {
    a: usize,
    b: usize,
    s: f32,
    side: f32,
    bound: f32,
}

/// A sample of the fabric's centreline, with the stitch it belongs to and where in it.
#[derive(Debug, Clone, Copy)]
struct FabricSample {
    /// In (u, v, lambda), u unwrapped.
    p: Vec3,
    course: usize,
    /// The stitch's wale (in the domain).
    wale: usize,
    /// The spline parameter within the stitch, from 0 (its sinker) to 6.
    t: f32,
    /// The stitch's polyline in [`FabricNear::lines`], and this sample's index in it.
    line: usize,
    index: usize,
}

/// The surface's tangents at a stitch: maps a (u, v) step to its length in scene units.
struct Metric {
    du: Vec3,
    dv: Vec3,
}

impl Metric {
    fn at(surface: &dyn Surface, centre: Vec2, tile: Vec2) -> Self {
        let at = |uv: Vec2| {
            surface
                .eval(uv)
                .unwrap_or_else(|| surface.eval_nearest(uv))
                .position
        };
        let (h, k) = (0.5 * tile.x, 0.5 * tile.y);
        let here = at(centre);
        Self {
            du: (at(centre + Vec2::new(h, 0.0)) - here) / h,
            dv: (at(centre + Vec2::new(0.0, k)) - here) / k,
        }
    }

    fn length(&self, step: Vec2) -> f32 {
        self.map(step).length()
    }

    /// A step in (u, v) as a vector in the tangent plane (scene units).
    fn map(&self, step: Vec2) -> Vec3 {
        step.x * self.du + step.y * self.dv
    }

    /// Where segments `a0 a1` and `b0 b1`, in (u, v, lambda), come nearest in (u, v) by this
    /// metric: the fraction along each. For segments that do not cross, whose nearest
    /// points then include an end of one.
    fn nearest(&self, a0: Vec3, a1: Vec3, b0: Vec3, b1: Vec3) -> (f32, f32) {
        let r = self.map((a1 - a0).truncate());
        let (q, s) = (
            self.map((b0 - a0).truncate()),
            self.map((b1 - b0).truncate()),
        );
        // The fraction along `from + t dir` nearest `x`.
        let along = |from: Vec3, dir: Vec3, x: Vec3| {
            let l = dir.length_squared();
            if l > 0.0 {
                ((x - from).dot(dir) / l).clamp(0.0, 1.0)
            } else {
                0.0
            }
        };
        let gap = |(t, u): (f32, f32)| (t * r).distance_squared(q + u * s);
        [
            (0.0, along(q, s, Vec3::ZERO)),
            (1.0, along(q, s, r)),
            (along(Vec3::ZERO, r, q), 0.0),
            (along(Vec3::ZERO, r, q + s), 1.0),
        ]
        .into_iter()
        .min_by(|x, y| gap(*x).total_cmp(&gap(*y)))
        .unwrap_or((0.0, 0.0))
    }
}

/// A fabric sample near a point of an edge segment ([`FabricNear::pairs`]): the point's
/// index along the segment, the sample, the edge's lambda less the sample's, and their
/// distance across in (u, v), scene units.
type Pair<'a> = (usize, &'a FabricSample, f32, f32);

/// The fabric's centreline samples near an edge piece, by the column they lie in.
struct FabricNear {
    /// Samples of the courses beside the edge that lie in column `first + i` (their u over
    /// the tile width, floored; unwrapped: u continues past the seam of a cyclic u).
    columns: Vec<Vec<FabricSample>>,
    first: isize,
    /// Each stitch's samples in yarn order, for where the edge crosses it.
    lines: Vec<Vec<Vec3>>,
    /// The spline parameter between two samples of each line.
    steps: Vec<f32>,
    /// How far out of the surface the fabric's yarn here stands, on either side (the
    /// largest |lambda| of its samples).
    thickness: f32,
    /// The tile width in u.
    width: f32,
    /// Per stitch of the edge piece: the surface's tangents and curvature radii there.
    metrics: Vec<Metric>,
    radii: Vec<super::curvature::SideRadii>,
}

impl FabricNear {
    fn new(
        surface: &dyn Surface,
        lattice: &Lattice,
        pattern: &StitchPattern,
        offsets: &NormalOffsets,
        sampling: &SplineSampling,
        piece: &YarnPiece,
    ) -> Self {
        let wales = lattice.wales as isize;
        let first = piece.first_wale as isize - REACH;
        let last = (piece.first_wale + piece.stitches) as isize + REACH;
        let courses = piece.course.saturating_sub(1)..(piece.course + 2).min(lattice.courses);
        let on_fabric = |x: isize| lattice.cyclic_u || (0..wales).contains(&x);
        // Key points of stitch (course, x), x unwrapped, with the curvature clamp the
        // fabric's own sampling applies.
        let stitch = |course: usize, x: isize| -> [Vec3; KEY_POINTS] {
            let k = x.div_euclid(wales);
            let mut kp = stitch_key_points(
                lattice,
                pattern,
                offsets,
                course,
                x.rem_euclid(wales) as usize,
            );
            let shift = Vec3::new(k as f32 * lattice.tile.x * wales as f32, 0.0, 0.0);
            let centre = lattice.tile_center(course, x.rem_euclid(wales) as usize);
            clamp_offsets(
                &mut kp,
                stitch_curvature_radii(surface, centre, lattice.tile),
            );
            kp.map(|p| p + shift)
        };
        // Bucketed by where they lie: a leaning loop reaches columns beside its own.
        let mut columns = vec![Vec::new(); (last - first + 2 * REACH) as usize];
        let first_column = first - REACH;
        let mut lines = Vec::new();
        let mut steps = Vec::new();
        // Each course's samples-per-loop multiple, as the knit samples it
        // ([`super::sampling_density`]).
        let course_density: Vec<usize> = (0..lattice.courses)
            .map(|c| {
                let lean = (0..lattice.wales)
                    .map(|w| landing(lattice, pattern, c, w).abs_diff(w as isize))
                    .max()
                    .unwrap_or(0);
                super::sampling_density::density(lean)
            })
            .collect();
        // Which courses space their knots by their chords, as the knit draws them.
        let metric = sampling.metric(lattice);
        let far: Vec<bool> = courses
            .clone()
            .map(|c| course_leans_far(lattice, pattern, offsets, metric, c))
            .collect();
        for x in (first..last).filter(|&x| on_fabric(x)) {
            for course in courses.clone() {
                // The stitch between its neighbours, so that the spline's tangents at its
                // ends are the fabric's own.
                let mut kp = Vec::with_capacity(3 * KEY_POINTS);
                let before = on_fabric(x - 1);
                if before {
                    kp.extend(stitch(course, x - 1));
                }
                kp.extend(stitch(course, x));
                if on_fabric(x + 1) {
                    kp.extend(stitch(course, x + 1));
                }
                let spacing = far[course - courses.start]
                    .then(|| knot_spacing(&kp, metric, false, Vec3::ZERO));
                let spline = CardinalSpline {
                    points: &kp,
                    closed: false,
                    tension: sampling.tension,
                    period: Vec3::ZERO,
                    spacing: spacing.as_deref(),
                };
                let start = if before { KEY_POINTS as f32 } else { 0.0 };
                // The fabric as the knit draws it: the chords between its output samples
                // (which cut inside the spline where its depth turns fast), each measured
                // at several points.
                let chords = sampling.samples_per_loop.max(1) * course_density[course];
                let per_chord = FABRIC_SAMPLES_PER_LOOP.div_ceil(chords).max(1);
                let per_loop = chords * per_chord;
                let corner =
                    |i: usize| spline.eval(start + (i * KEY_POINTS) as f32 / chords as f32);
                let mut line = Vec::with_capacity(per_loop + 1);
                let mut from = corner(0);
                for j in 0..=per_loop {
                    let t = start + (j * KEY_POINTS) as f32 / per_loop as f32;
                    let (i, k) = (j / per_chord, j % per_chord);
                    let p = if k == 0 {
                        from = corner(i);
                        from
                    } else {
                        from.lerp(corner(i + 1), k as f32 / per_chord as f32)
                    };
                    line.push(p);
                    let c = (p.x / lattice.tile.x).floor() as isize - first_column;
                    if let Some(column) = usize::try_from(c).ok().and_then(|c| columns.get_mut(c)) {
                        column.push(FabricSample {
                            p,
                            course,
                            wale: x.rem_euclid(wales) as usize,
                            t: t - start,
                            line: lines.len(),
                            index: j,
                        });
                    }
                }
                lines.push(line);
                steps.push(KEY_POINTS as f32 / per_loop as f32);
            }
        }
        let (metrics, radii) = (0..piece.stitches)
            .map(|j| {
                let w = (piece.first_wale + j) % lattice.wales;
                let centre = lattice.tile_center(piece.course, w);
                (
                    Metric::at(surface, centre, lattice.tile),
                    stitch_curvature_radii(surface, centre, lattice.tile),
                )
            })
            .unzip();
        Self {
            columns,
            first: first_column,
            thickness: lines.iter().flatten().fold(0.0, |m, p| m.max(p.z.abs())),
            lines,
            steps,
            width: lattice.tile.x,
            metrics,
            radii,
        }
    }

    /// The fabric samples near the segment from `a` to `b` of the edge, measured at
    /// [`SUBDIVISIONS`] points along it: (point, fabric sample, lambda gap, distance across
    /// in (u, v)).
    fn pairs(&self, a: Vec3, b: Vec3, metric: &Metric, clearance: f32) -> Vec<Pair<'_>> {
        let mut pairs = Vec::new();
        for k in 0..SUBDIVISIONS {
            let q = a.lerp(b, k as f32 / SUBDIVISIONS as f32);
            for f in self.near(q) {
                let planar = metric.length(Vec2::new(q.x - f.p.x, q.y - f.p.y));
                if planar < clearance {
                    pairs.push((k, f, q.z - f.p.z, planar));
                }
            }
        }
        pairs
    }

    /// Where the segment from sample `a` to sample `b` of the edge (each with its index,
    /// point and spline parameter) crosses a fabric yarn near it in (u, v), added to `out`
    /// (per line of [`Self::lines`]: the point in (u, v) and whether the edge is in front
    /// there). The side is the one the crossing's rule gives (`front`: the edge in front of
    /// the fabric yarn at a fabric sample), or where no rule decides, the side it crosses on.
    fn crossings(
        &self,
        (_, a, ta): (usize, Vec3, f32),
        (_, b, tb): (usize, Vec3, f32),
        pairs: &[Pair],
        front: impl Fn(f32, &FabricSample) -> Option<bool>,
        out: &mut [Vec<(Vec2, bool)>],
    ) {
        let mut tried = std::collections::BTreeSet::new();
        for &(_, f, _, _) in pairs {
            let line = &self.lines[f.line];
            // Both of the sample's segments: the yarn may cross the edge on either side of
            // the one sample near it (a crossing between two samples farther than the
            // clearance from the edge's measured points was missed, and the edge, taking the
            // side it is on at each point, was asked to be on both sides of that yarn).
            for index in f.index.checked_sub(1).into_iter().chain([f.index]) {
                if index + 1 >= line.len() || !tried.insert((f.line, index)) {
                    continue;
                }
                let (f0, f1) = (line[index], line[index + 1]);
                let Some((s, r, ez, fz, _)) = intersect(a, b, f0, f1) else {
                    continue;
                };
                let ft = f.t + (index as f32 - f.index as f32 + r) * self.steps[f.line];
                let at = FabricSample { t: ft, ..*f };
                let above = front(ta + s * (tb - ta), &at).unwrap_or(ez >= fz);
                out[f.line].push((a.lerp(b, s).truncate(), above));
            }
        }
    }

    /// The constraints that keep the segment from sample `a` to sample `b` of the edge
    /// `clearance` from every fabric sample near it, one per measured point and side (the
    /// strictest). Near a crossing of a fabric yarn (`crossings`, from [`Self::crossings`]:
    /// the edge point within the clearance of it, the fabric sample within half of it), the
    /// edge keeps to the crossing's side of that yarn; elsewhere, to the side it is on.
    #[allow(clippy::too_many_arguments)]
    fn constraints(
        &self,
        (ia, a, _): (usize, Vec3, f32),
        (ib, b, _): (usize, Vec3, f32),
        pairs: &[Pair],
        metric: &Metric,
        clearance: f32,
        crossings: &[Vec<(Vec2, bool)>],
        out: &mut Vec<Constraint>,
    ) {
        if pairs.is_empty() {
            return;
        }
        let mut sided: Vec<(f32, f32, bool)> = Vec::new();
        for k in 0..SUBDIVISIONS {
            // Each fabric sample near this point: its lambda, its distance across, and
            // whether the edge passes in front of it.
            sided.clear();
            sided.extend(
                pairs
                    .iter()
                    .filter(|p| p.0 == k)
                    .map(|&(k, f, gap, planar)| {
                        let q = a.lerp(b, k as f32 / SUBDIVISIONS as f32).truncate();
                        // The crossing of this yarn nearest the sample, if both the sample
                        // and the point are within the clearance of it (the samples lie
                        // half a clearance apart, so the two beside a crossing can both be
                        // more than half of one from it).
                        let crossing = crossings[f.line]
                            .iter()
                            .map(|&(at, above)| (metric.length(f.p.truncate() - at), at, above))
                            .filter(|&(from_sample, at, _)| {
                                from_sample < clearance && metric.length(q - at) < clearance
                            })
                            .min_by(|x, y| x.0.total_cmp(&y.0))
                            .map(|(_, at, above)| (at, above));
                        (f.p.z, planar, crossing.map_or(gap >= 0.0, |c| c.1))
                    }),
            );
            if sided.is_empty() {
                continue;
            }
            // The lambdas the point may take to keep `c` from every sample: above the ones
            // it passes in front of, below the others.
            let range = |c: f32| {
                let (mut lo, mut hi) = (f32::MIN, f32::MAX);
                for &(z, planar, above) in &sided {
                    if planar < c {
                        let depth = (c * c - planar * planar).sqrt();
                        if above {
                            lo = lo.max(z + depth);
                        } else {
                            hi = hi.min(z - depth);
                        }
                    }
                }
                (lo, hi)
            };
            // The clearance, or where yarns on both sides leave less room, the most there is
            // (found by bisection): the point then sits as far from both as it can.
            let (mut lo, mut hi) = range(clearance);
            if lo > hi {
                let (mut fits, mut fails) = (0.0f32, clearance);
                for _ in 0..BISECTIONS {
                    let c = 0.5 * (fits + fails);
                    let (l, h) = range(c);
                    if l <= h {
                        fits = c;
                    } else {
                        fails = c;
                    }
                }
                (lo, hi) = range(fits);
                if lo > hi {
                    let mid = 0.5 * (lo + hi);
                    (lo, hi) = (mid, mid);
                }
            }
            let s = k as f32 / SUBDIVISIONS as f32;
            for (side, bound) in [(1.0, lo), (-1.0, -hi)] {
                if bound > f32::MIN {
                    out.push(Constraint {
                        a: ia,
                        b: ib,
                        s,
                        side,
                        bound,
                    });
                }
            }
        }
    }

    /// The fabric samples within a column of `q` along u: a yarn diameter is well under a
    /// stitch width.
    fn near(&self, q: Vec3) -> impl Iterator<Item = &FabricSample> + '_ {
        let c = (q.x / self.width).floor() as isize - self.first;
        let from = (c - 1).clamp(0, self.columns.len() as isize) as usize;
        let to = (c + 2).clamp(0, self.columns.len() as isize) as usize;
        self.columns[from..to].iter().flatten()
    }
}
