//! Which yarn is in front where two yarns cross (docs/design.md sections 3 and 7): the interlock
//! of every course with the one below, and the order of crossed, twisted, slipped and
//! stranded yarn, as the stitch pattern says.
//!
//! Crossings are found in the (u, v) domain, where the normal offset lambda is the depth:
//! two centreline segments whose (u, v) projections intersect cross there, and the one with
//! the larger lambda at the intersection is in front. Each segment knows the stitch it belongs
//! to and which part of the loop it is (sinker, left leg, head, right leg).
//!
//! **The interlock.** Every loop L of a course is held by the stitch pulled through it, its
//! *puller* P: the stitch of the next course (the one after, under a slipped stitch) in the
//! column L lands in. Every crossing of a yarn of a later course U with L, where U is P's
//! course, is decided by P's face:
//!
//! - P's own legs (and head) pass L in front for a knit P, behind for a purl: the new loop
//!   was pulled through L from the back (knit) or the front (purl);
//! - a sinker of U (the yarn between two wales at the foot of its loops) passes L on the
//!   other side: behind the leg tops of L under a knit P, in front under a purl;
//! - any other loop of U that crosses L (a yarn-over's short legs, a loop leaning past it)
//!   lies on P's face side of it, as the fabric round P does.
//!
//! So stockinette has its upper course in front at about half of the crossings, stitch by
//! stitch; a course wholly in front of the one below (a roof shingle) fails half of them.
//! No crossing between a course and the course its loops hang from is left undecided.
//!
//! Beyond the interlock, each stitch states its own rule:
//! - two loops of one row that lean across each other (a cable) or are gathered by one
//!   decrease: the one with the higher layer in front;
//! - the crossed legs of a twisted stitch: the leg the yarn reaches first in front;
//! - a float past a slipped stitch and the loop it passes: the float in front when the yarn
//!   was held in front;
//! - a float of stranded colourwork behind the fabric, a bobble's ball in front of it, and
//!   each turn of the ball over the turns before it (the ball is coiled outward).
//!
//! Crossings of one course with itself or with courses further away that none of these
//! rules decide are counted as undecided.

use glam::{Vec2, Vec3};

use super::edges::Edge;
use super::stitch_shape::{carried_rise, group_on_fabric, knitted_form, landing};
use super::{YarnPiece, KEY_POINTS};
use crate::lattice::Lattice;
use crate::pattern::{Face, Form, StitchPattern};

/// The result: crossings decided by a rule, how many of them agree, and the rest.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CrossingOrder {
    /// Every decided crossing (the interlock's included).
    pub decided: usize,
    pub agree: usize,
    /// Crossings of a course with the course its loops hang from (always decided), and how
    /// many of them agree with the interlock rule.
    pub interlock_decided: usize,
    pub interlock_agree: usize,
    /// Crossings no rule decides (within one course, or courses further apart).
    pub undecided: usize,
    /// The independent check of docs/design.md section 7: interlock crossings bucketed by lower
    /// course and stitch-wide column; `buckets` of them hold a crossing, and
    /// `buckets_half_front` have the upper course in front at between a quarter and three
    /// quarters of theirs. A stacked course scores 0 here whatever its depths.
    pub buckets: usize,
    pub buckets_half_front: usize,
    /// Loops (of the fabric, slipped stitches' floats aside, and of its cast-on and bind-off),
    /// and those of them that nothing
    /// holds: no yarn is pulled through them (no interlock crossing agrees where they are
    /// the lower yarn; for a bind-off loop, no chain crossing agrees). The last loop of an
    /// open bind-off, its fastened-off end, is not counted. Live loops at an edge are free.
    pub loops: usize,
    pub free_loops: usize,
    /// Stitches pulled through a loop (all of the fabric's but yarn-overs, made stitches
    /// and slipped stitches, which are not), and those of them pulled through none: the
    /// first course's feet without a cast-on.
    pub feet: usize,
    pub free_feet: usize,
    /// The first disagreement found, described, for a test's message.
    pub first_disagreement: Option<String>,
}

impl CrossingOrder {
    /// The fraction of decided crossings that agree (1 when there are none).
    pub fn fraction(&self) -> f64 {
        ratio(self.agree, self.decided)
    }

    /// The fraction of interlock crossings that agree (1 when there are none).
    pub fn interlock(&self) -> f64 {
        ratio(self.interlock_agree, self.interlock_decided)
    }
}

fn ratio(a: usize, b: usize) -> f64 {
    if b == 0 {
        1.0
    } else {
        a as f64 / b as f64
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Part {
    Sinker,
    LeftLeg,
    Head,
    RightLeg,
}

#[derive(Debug, Clone, Copy)]
struct Seg {
    a: Vec3,
    b: Vec3,
    piece: usize,
    /// Index along the piece, for telling neighbours apart.
    index: usize,
    course: usize,
    wale: usize,
    part: Part,
    /// Part of a float of stranded colourwork.
    float: bool,
    /// Part of a bobble's ball.
    knot: bool,
    /// Part of a cast-on or bind-off ([`super::edges`]) of `course`.
    edge: Option<Edge>,
    /// The row the yarn is in: `course`, one less for a cast-on and one more for a bind-off.
    row: isize,
}

/// What decides a crossing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Rule {
    /// The interlock of a loop and the course pulled through it.
    Interlock,
    /// A stitch's own rule (cable layers, twisted legs, floats, bobbles).
    Stitch,
}

/// One crossing a rule decides: where it is on each yarn and which yarn the rule puts in
/// front. A yarn's place is its piece, the index of its centreline segment (sample `index`
/// to sample `index + 1` of the piece's line) and the fraction along that segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DecidedCrossing {
    pub a: (usize, usize, f32),
    pub b: (usize, usize, f32),
    /// Whether the rule puts yarn `a` in front.
    pub a_front: bool,
    /// The depths (lambda) of `a` and `b` where they cross.
    pub depths: (f32, f32),
}

/// A crossing found: the two segments, where along each, their depths, where in (u, v), and
/// the rule that decides it (`None`: undecided).
struct Found<'a> {
    s: &'a Seg,
    o: &'a Seg,
    along: (f32, f32),
    depths: (f32, f32),
    at: Vec2,
    expected: Option<(Rule, bool)>,
}

/// Items (segments) bucketed by the grid cells their bounding boxes cover, in item order
/// within each cell: a dense grid over the cells used, its lists packed one after another
/// (counted first, then filled: no per-cell allocation, no hashing).
struct CellGrid {
    /// The lowest cell used, and the grid's size in cells.
    origin: (i64, i64),
    size: (i64, i64),
    /// Where each cell's list starts in `items` (one more entry than cells).
    starts: Vec<u32>,
    items: Vec<u32>,
}

impl CellGrid {
    /// `boxes[i]`: the lowest and highest cell (x, y) item `i` covers, inclusive.
    fn new(boxes: impl Iterator<Item = ((i64, i64), (i64, i64))> + Clone) -> Self {
        let (mut lo, mut hi) = ((i64::MAX, i64::MAX), (i64::MIN, i64::MIN));
        for (a, b) in boxes.clone() {
            lo = (lo.0.min(a.0), lo.1.min(a.1));
            hi = (hi.0.max(b.0), hi.1.max(b.1));
        }
        if lo.0 > hi.0 {
            return Self {
                origin: (0, 0),
                size: (0, 0),
                starts: vec![0],
                items: Vec::new(),
            };
        }
        let size = (hi.0 - lo.0 + 1, hi.1 - lo.1 + 1);
        let index = |x: i64, y: i64| ((x - lo.0) * size.1 + (y - lo.1)) as usize;
        let mut starts = vec![0u32; (size.0 * size.1) as usize + 1];
        for (a, b) in boxes.clone() {
            for x in a.0..=b.0 {
                for y in a.1..=b.1 {
                    starts[index(x, y) + 1] += 1;
                }
            }
        }
        for c in 1..starts.len() {
            starts[c] += starts[c - 1];
        }
        let mut fill = starts.clone();
        let mut items = vec![0u32; *starts.last().unwrap_or(&0) as usize];
        for (i, (a, b)) in boxes.enumerate() {
            for x in a.0..=b.0 {
                for y in a.1..=b.1 {
                    let c = index(x, y);
                    items[fill[c] as usize] = i as u32;
                    fill[c] += 1;
                }
            }
        }
        Self {
            origin: lo,
            size,
            starts,
            items,
        }
    }

    /// The items in cell (x, y), in item order (none outside the grid).
    fn cell(&self, x: i64, y: i64) -> &[u32] {
        let (gx, gy) = (x - self.origin.0, y - self.origin.1);
        if !(0..self.size.0).contains(&gx) || !(0..self.size.1).contains(&gy) {
            return &[];
        }
        let c = (gx * self.size.1 + gy) as usize;
        &self.items[self.starts[c] as usize..self.starts[c + 1] as usize]
    }
}

/// Calls `visit` on every crossing of the (u, v) projections of `pieces`' centrelines
/// `lines` (in (u, v, lambda), `samples_per_loop` per stitch).
fn for_each_crossing(
    lattice: &Lattice,
    pattern: &StitchPattern,
    pieces: &[YarnPiece],
    lines: &[Vec<Vec3>],
    samples_per_loop: usize,
    mut visit: impl FnMut(Found),
) {
    let wales = lattice.wales;
    let period = lattice.tile.x * wales as f32;
    let segs = segments(lattice, pieces, lines, samples_per_loop);
    // A uniform grid over (u, v) with cells of one stitch.
    let cell = lattice.tile;
    let key = |p: Vec2| ((p.x / cell.x).floor() as i64, (p.y / cell.y).floor() as i64);
    let cells_of = |s: &Seg| {
        let (a, b) = (s.a.truncate(), s.b.truncate());
        (key(a.min(b)), key(a.max(b)))
    };
    let grid = CellGrid::new(segs.iter().map(cells_of));
    let columns = (period / cell.x).round() as i64;
    // Which (segment, wrap) pairs were already visited from segment `i`: a pair of segments
    // that share several cells is met in each. `seen[3 k + wrap + 1]` holds the last `i + 1`
    // that visited `k` at `wrap`, so the check is one load rather than a scan of the list of
    // pairs met (a quarter of this function's time in a first knit's tuning).
    let mut seen: Vec<usize> = vec![0; 3 * segs.len()];
    for (i, s) in segs.iter().enumerate() {
        let (k0, k1) = cells_of(s);
        for x in k0.0..=k1.0 {
            for y in k0.1..=k1.1 {
                let shifts: &[i64] = if lattice.cyclic_u { &[0, -1, 1] } else { &[0] };
                for &wrap in shifts {
                    for &k in grid.cell(x + wrap * columns, y) {
                        let k = k as usize;
                        let slot = 3 * k + (wrap + 1) as usize;
                        if k <= i || seen[slot] == i + 1 {
                            continue;
                        }
                        seen[slot] = i + 1;
                        let o = &segs[k];
                        if o.piece == s.piece && o.index.abs_diff(s.index) < 2 {
                            continue;
                        }
                        let off = Vec3::new(wrap as f32 * period, 0.0, 0.0);
                        let Some((ts, to, ls, lo_, at)) = intersect(s.a, s.b, o.a - off, o.b - off)
                        else {
                            continue;
                        };
                        visit(Found {
                            s,
                            o,
                            along: (ts, to),
                            depths: (ls, lo_),
                            at,
                            expected: expected(lattice, pattern, s, o),
                        });
                    }
                }
            }
        }
    }
}

/// Every crossing of `pieces` (centrelines `lines` in (u, v, lambda), `samples_per_loop` per
/// stitch) that a rule decides, with the side the rule puts each yarn on.
pub fn decided_crossings(
    lattice: &Lattice,
    pattern: &StitchPattern,
    pieces: &[YarnPiece],
    lines: &[Vec<Vec3>],
    samples_per_loop: usize,
) -> Vec<DecidedCrossing> {
    let mut out = Vec::new();
    for_each_crossing(lattice, pattern, pieces, lines, samples_per_loop, |f| {
        if let Some((_, a_front)) = f.expected {
            out.push(DecidedCrossing {
                a: (f.s.piece, f.s.index, f.along.0),
                b: (f.o.piece, f.o.index, f.along.1),
                a_front,
                depths: f.depths,
            });
        }
    });
    out
}

/// Measures the crossing order of `pieces`, whose centrelines in (u, v, lambda) are
/// `lines[i]` (as [`crate::skeleton::sample_piece_uv`] gives them, `samples_per_loop` per
/// stitch).
pub fn crossing_order(
    lattice: &Lattice,
    pattern: &StitchPattern,
    pieces: &[YarnPiece],
    lines: &[Vec<Vec3>],
    samples_per_loop: usize,
) -> CrossingOrder {
    let period = lattice.tile.x * lattice.wales as f32;
    let cell = lattice.tile;
    let columns = (period / cell.x).round() as i64;
    let mut result = CrossingOrder::default();
    // Interlock crossings per (lower course, column): (upper in front, all).
    let mut buckets: std::collections::BTreeMap<(isize, i64), (usize, usize)> =
        std::collections::BTreeMap::new();
    // Stitches by (row, wale) whose loop is held and whose foot is pulled through a loop.
    let mut held = std::collections::BTreeSet::new();
    let mut pulled = std::collections::BTreeSet::new();
    for_each_crossing(lattice, pattern, pieces, lines, samples_per_loop, |f| {
        let (s, o, at) = (f.s, f.o, f.at);
        let (ls, lo_) = f.depths;
        let s_in_front = ls > lo_;
        let Some((rule, s_front)) = f.expected else {
            result.undecided += 1;
            return;
        };
        result.decided += 1;
        let agree = s_in_front == s_front;
        result.agree += usize::from(agree);
        if agree && rule == Rule::Stitch && s.edge == Some(Edge::BindOff) && s.edge == o.edge {
            // The chain: the bind-off loop whose head the next one's leg passes.
            let head = if s.part == Part::Head { s } else { o };
            held.insert((head.row, head.wale));
        }
        if rule == Rule::Interlock {
            result.interlock_decided += 1;
            result.interlock_agree += usize::from(agree);
            let (upper_front, lower, upper_seg, lower_seg) = if s.row > o.row {
                (s_in_front, o.row, s, o)
            } else {
                (!s_in_front, s.row, o, s)
            };
            if agree {
                held.insert((lower_seg.row, lower_seg.wale));
                pulled.insert((upper_seg.row, upper_seg.wale));
            }
            let column = (at.x / cell.x).floor() as i64;
            let column = if lattice.cyclic_u {
                column.rem_euclid(columns)
            } else {
                column
            };
            let b = buckets.entry((lower, column)).or_default();
            b.0 += usize::from(upper_front);
            b.1 += 1;
        }
        if !agree && result.first_disagreement.is_none() {
            result.first_disagreement = Some(format!(
                "{:?} of stitch ({}, {}) and {:?} of stitch ({}, {}): \
                 expected the {} in front (depths {ls:.5} and {lo_:.5})",
                s.part,
                s.course,
                s.wale,
                o.part,
                o.course,
                o.wale,
                if s_front { "first" } else { "second" }
            ));
        }
    });
    for pc in pieces {
        if pc.float_color.is_some() || pc.bobble {
            continue;
        }
        let row = pc.course as isize
            + match pc.edge {
                Some(Edge::CastOn) => -1,
                Some(Edge::BindOff) => 1,
                None => 0,
            };
        for j in 0..pc.stitches {
            let wale = (pc.first_wale + j) % lattice.wales;
            let fastened = pc.edge == Some(Edge::BindOff) && !pc.closed && j + 1 == pc.stitches;
            let form = knitted_form(lattice, pattern, pc.course, wale);
            // A slipped stitch's float is no loop, nor is the cast-on's strand under a
            // yarn-over or a made stitch.
            let float = match pc.edge {
                None => matches!(form, Form::Slip { .. }),
                Some(Edge::CastOn) => matches!(form, Form::YarnOver | Form::MakeOne),
                Some(Edge::BindOff) => false,
            };
            if !fastened && !float {
                result.loops += 1;
                result.free_loops += usize::from(!held.contains(&(row, wale)));
            }
            let no_loop_below = matches!(
                knitted_form(lattice, pattern, pc.course, wale),
                Form::YarnOver | Form::MakeOne | Form::Slip { .. }
            );
            if pc.edge.is_none() && !no_loop_below {
                result.feet += 1;
                result.free_feet += usize::from(!pulled.contains(&(row, wale)));
            }
        }
    }
    result.buckets = buckets.len();
    result.buckets_half_front = buckets
        .values()
        .filter(|(front, all)| 4 * front >= *all && 4 * front <= 3 * all)
        .count();
    result
}

/// The centreline segments of `pieces`, each with its stitch and part of the loop.
fn segments(
    lattice: &Lattice,
    pieces: &[YarnPiece],
    lines: &[Vec<Vec3>],
    samples_per_loop: usize,
) -> Vec<Seg> {
    let wales = lattice.wales;
    let period = lattice.tile.x * wales as f32;
    let mut segs = Vec::new();
    for (pi, (pc, line)) in pieces.iter().zip(lines).enumerate() {
        let n = line.len();
        let count = if pc.closed { n } else { n.saturating_sub(1) };
        for j in 0..count {
            let t0 = pc.sample_t(j, samples_per_loop);
            let t1 = if j + 1 == n {
                (KEY_POINTS * pc.stitches) as f32
            } else {
                pc.sample_t(j + 1, samples_per_loop)
            };
            let tm = 0.5 * (t0 + t1);
            let q = (tm as usize) % KEY_POINTS;
            let mut stitch = tm as usize / KEY_POINTS;
            let part = match q {
                0 => Part::Sinker,
                1 => Part::LeftLeg,
                2 | 3 => Part::Head,
                4 => Part::RightLeg,
                _ => {
                    stitch += 1;
                    Part::Sinker
                }
            };
            let mut a = line[j];
            let mut b = line[(j + 1) % n];
            if pc.closed && j + 1 == n {
                b.x += period;
            }
            // Bring the segment's start into the domain's first period (cyclic u).
            if lattice.cyclic_u {
                let shift = (a.x / period).floor() * period;
                a.x -= shift;
                b.x -= shift;
            }
            // A sinker past the end of an open piece belongs to its last stitch.
            let stitch = if pc.closed {
                stitch % pc.stitches.max(1)
            } else {
                stitch.min(pc.stitches.saturating_sub(1))
            };
            segs.push(Seg {
                a,
                b,
                piece: pi,
                index: j,
                course: pc.course,
                wale: (pc.first_wale + stitch) % wales,
                part,
                float: pc.float_color.is_some(),
                knot: pc.bobble,
                edge: pc.edge,
                row: pc.course as isize
                    + match pc.edge {
                        Some(Edge::CastOn) => -1,
                        Some(Edge::BindOff) => 1,
                        None => 0,
                    },
            });
        }
    }
    segs
}

/// Where the (u, v) projections of segments `a0 a1` and `b0 b1` cross (not at an end): the
/// fraction along each, the depths (lambda) of each there, and the point in (u, v).
pub(super) fn intersect(
    a0: Vec3,
    a1: Vec3,
    b0: Vec3,
    b1: Vec3,
) -> Option<(f32, f32, f32, f32, Vec2)> {
    let (p, r) = (a0.truncate(), (a1 - a0).truncate());
    let (q, s) = (b0.truncate(), (b1 - b0).truncate());
    let denom = r.perp_dot(s);
    if denom.abs() < 1e-12 {
        return None;
    }
    let t = (q - p).perp_dot(s) / denom;
    let u = (q - p).perp_dot(r) / denom;
    let inside = |x: f32| (1e-4..=1.0 - 1e-4).contains(&x);
    (inside(t) && inside(u)).then_some((
        t,
        u,
        a0.z + t * (a1.z - a0.z),
        b0.z + u * (b1.z - b0.z),
        p + t * r,
    ))
}

/// The stitch (course, wale) pulled through the loop of stitch (`course`, `wale`): in the
/// column the loop lands in, one course up, and one more for each stitch slipped over it
/// ([`carried_rise`]). `None` for a loop of
/// the last course, which nothing holds.
fn puller(
    lattice: &Lattice,
    pattern: &StitchPattern,
    course: usize,
    wale: usize,
) -> Option<(usize, usize)> {
    let c = course + 1 + carried_rise(lattice, pattern, course, wale);
    if c >= lattice.courses {
        return None;
    }
    let w = landing(lattice, pattern, course, wale).rem_euclid(lattice.wales as isize) as usize;
    // A yarn-over or a made stitch is pulled through no loop: a loop under one (as knitted)
    // is held by nothing, and counts as free.
    let pulls = !matches!(
        knitted_form(lattice, pattern, c, w),
        Form::YarnOver | Form::MakeOne
    );
    pulls.then_some((c, w))
}

/// The part of a loop, and the stitch of its piece it belongs to, at spline parameter `t`
/// of a piece (six key points a stitch; the yarn past the right leg bottom is the next
/// stitch's sinker), as [`segments`] assigns them.
fn part_at(t: f32) -> (usize, Part) {
    let stitch = t.max(0.0) as usize / KEY_POINTS;
    match t.max(0.0) as usize % KEY_POINTS {
        0 => (stitch, Part::Sinker),
        1 => (stitch, Part::LeftLeg),
        2 | 3 => (stitch, Part::Head),
        4 => (stitch, Part::RightLeg),
        _ => (stitch + 1, Part::Sinker),
    }
}

/// Whether the rule puts the edge yarn of `edge` (at spline parameter `t` along it) in front
/// of the fabric yarn of a course's stitch (`course`, `wale`) at parameter `ft` within that
/// stitch (0 at its sinker, up to 6), where they cross; `None` where no rule decides. The
/// edges keep clear of the fabric on this side ([`super::edge_clearance`]).
pub(super) fn edge_in_front(
    lattice: &Lattice,
    pattern: &StitchPattern,
    edge: &YarnPiece,
    t: f32,
    course: usize,
    wale: usize,
    ft: f32,
) -> Option<bool> {
    let wales = lattice.wales;
    let seg = |piece: usize, course: usize, wale: usize, part: Part, edge: Option<Edge>| Seg {
        a: Vec3::ZERO,
        b: Vec3::ZERO,
        piece,
        index: 0,
        course,
        wale: wale % wales,
        part,
        float: false,
        knot: false,
        edge,
        row: course as isize,
    };
    let (stitch, part) = part_at(t);
    let stitch = if edge.closed {
        stitch % edge.stitches.max(1)
    } else {
        stitch.min(edge.stitches.saturating_sub(1))
    };
    let e = seg(0, edge.course, edge.first_wale + stitch, part, edge.edge);
    let (next, part) = part_at(ft);
    let f = seg(1, course, wale + next, part, None);
    at_edge(lattice, pattern, &e, &f).map(|(_, front)| front)
}

/// [`expected`] where `a` or `b` is part of an edge ([`super::edges`]).
///
/// - A cast-on loop under stitch (c, w) is held by that stitch: the interlock rule with
///   puller (c, w).
/// - A loop of the bind-off's course (or one a slipped stitch carries up to it) is held by the
///   bind-off loop over the column it lands in, worked as the pattern's next row: the
///   interlock rule with that puller.
/// - Each bind-off loop's head lies behind the legs of the next bind-off loop when that one
///   is knitted, in front when purled: the next loop is pulled through it (the chain).
fn at_edge(lattice: &Lattice, pattern: &StitchPattern, a: &Seg, b: &Seg) -> Option<(Rule, bool)> {
    let wales = lattice.wales;
    let knit = |course: usize, wale: usize| {
        super::edges::worked_face(lattice, pattern, course, wale % wales) == Face::Knit
    };
    let is_leg = |s: &Seg| matches!(s.part, Part::LeftLeg | Part::RightLeg);
    match (a.edge, b.edge) {
        (Some(Edge::BindOff), Some(Edge::BindOff)) if a.piece == b.piece => {
            let chain = |head: &Seg, leg: &Seg| {
                head.part == Part::Head && is_leg(leg) && leg.wale == (head.wale + 1) % wales
            };
            if chain(a, b) {
                Some((Rule::Stitch, !knit(b.course + 1, b.wale)))
            } else if chain(b, a) {
                Some((Rule::Stitch, knit(a.course + 1, a.wale)))
            } else {
                None
            }
        }
        (Some(_), Some(_)) => None,
        (Some(_), None) => edge_and_fabric(lattice, pattern, a, b),
        (None, Some(_)) => edge_and_fabric(lattice, pattern, b, a).map(|(r, f)| (r, !f)),
        (None, None) => None,
    }
}

/// Whether the edge yarn `e` should be in front of the fabric yarn `f` where they cross.
fn edge_and_fabric(
    lattice: &Lattice,
    pattern: &StitchPattern,
    e: &Seg,
    f: &Seg,
) -> Option<(Rule, bool)> {
    let wales = lattice.wales;
    let cell = |course: usize, wale: usize| pattern.stitch(course, wale % wales);
    // A bind-off works every stitch of the row it stands for, its slips too, with the face
    // the edge gives them ([`super::edges::worked_face`]).
    let face = |course: usize, wale: usize| match e.edge {
        Some(Edge::BindOff) => super::edges::worked_face(lattice, pattern, course, wale % wales),
        _ => cell(course, wale).face,
    };
    // The interlock's rule for the side of upper yarn `upper` against a loop whose puller
    // is `p`: the puller's own legs on its face side, the sinkers of its course on the other,
    // any other loop of its course on the face side.
    let upper_front = |upper: &Seg, p: (usize, usize)| {
        let knit = face(p.0, p.1) == Face::Knit;
        if upper.part == Part::Sinker {
            !knit
        } else if upper.wale == p.1 {
            face(p.0, upper.wale) == Face::Knit
        } else {
            knit
        }
    };
    match e.edge? {
        Edge::CastOn => {
            // Under a slipped stitch the loop is carried up to the next course (and on, under
            // each stitch slipped again), which holds it; each slipped stitch's float passes
            // it on the side the yarn was held.
            let rise = super::edges::cast_on_rise(lattice, pattern, e.course, e.wale);
            let puller = (e.course + rise, e.wale);
            if f.course == puller.0 {
                return Some((Rule::Interlock, !upper_front(f, puller)));
            }
            match cell(f.course, f.wale).form {
                Form::Slip { yarn_front }
                    if f.course < e.course + rise
                        && f.course >= e.course
                        && f.part != Part::Sinker
                        && e.part != Part::Sinker =>
                {
                    Some((Rule::Stitch, !yarn_front))
                }
                _ => None,
            }
        }
        Edge::BindOff => {
            let rise = carried_rise(lattice, pattern, f.course, f.wale);
            if f.course + 1 + rise != e.course + 1 {
                return None;
            }
            let x = landing(lattice, pattern, f.course, f.wale).rem_euclid(wales as isize) as usize;
            Some((Rule::Interlock, upper_front(e, (e.course + 1, x))))
        }
    }
}

/// Whether `a` should be in front of `b` where they cross, and the rule that says so.
fn expected(lattice: &Lattice, pattern: &StitchPattern, a: &Seg, b: &Seg) -> Option<(Rule, bool)> {
    // A float of stranded colourwork runs behind the fabric, a bobble's ball in front of it.
    if a.float || b.float {
        return (a.float != b.float).then_some((Rule::Stitch, b.float));
    }
    if a.knot || b.knot {
        if a.knot && b.knot && a.piece == b.piece {
            // A ball's turns coil outward from its rim (`super::bobbles`): seen from the
            // front, where one turn crosses an earlier one it lies over it.
            return Some((Rule::Stitch, a.index > b.index));
        }
        return (a.knot != b.knot).then_some((Rule::Stitch, a.knot));
    }
    if a.edge.is_some() || b.edge.is_some() {
        return at_edge(lattice, pattern, a, b);
    }
    // The stitch as knitted: a loop whose crossing or decrease the edge cuts is knitted
    // straight, in no layer, as its key points are (`stitch_shape::stitch_key_points`).
    let cell = |s: &Seg| {
        let mut c = pattern.stitch(s.course, s.wale);
        if !group_on_fabric(lattice, pattern, s.course, s.wale) {
            c.land_offset = 0;
            c.land_layer = 0;
        }
        c
    };
    let (ca, cb) = (cell(a), cell(b));
    let slip = |c: crate::pattern::Stitch| match c.form {
        Form::Slip { yarn_front } => Some(yarn_front),
        _ => None,
    };
    // A float past a slipped stitch and the loop it passes (not where the yarn goes in and
    // out of the float, whose side the yarn is changing).
    if a.course != b.course && a.part != Part::Sinker && b.part != Part::Sinker {
        if let Some(front) = slip(ca) {
            return Some((Rule::Stitch, front));
        }
        if let Some(front) = slip(cb) {
            return Some((Rule::Stitch, !front));
        }
    }
    if a.course != b.course {
        let (upper, lower, a_upper) = if a.course > b.course {
            (a, b, true)
        } else {
            (b, a, false)
        };
        if let Some(p) = puller(lattice, pattern, lower.course, lower.wale) {
            if p.0 == upper.course {
                let knit = pattern.stitch(p.0, p.1).face == Face::Knit;
                let own = (upper.course, upper.wale) == p;
                let upper_front = if upper.part == Part::Sinker {
                    !knit
                } else if own {
                    cell(upper).face == Face::Knit
                } else {
                    knit
                };
                return Some((Rule::Interlock, upper_front == a_upper));
            }
        }
        return None;
    }
    // Loops of one row crossing or stacked: the higher layer in front.
    if a.wale != b.wale
        && a.part != Part::Sinker
        && b.part != Part::Sinker
        && ca.land_layer != cb.land_layer
        && ca.land_layer != 0
        && cb.land_layer != 0
    {
        return Some((Rule::Stitch, ca.land_layer > cb.land_layer));
    }
    // The crossed legs of a twisted stitch.
    let is_leg = |s: &Seg| matches!(s.part, Part::LeftLeg | Part::RightLeg);
    if a.piece == b.piece
        && a.wale == b.wale
        && ca.form == Form::Twisted
        && is_leg(a)
        && is_leg(b)
        && a.part != b.part
    {
        return Some((Rule::Stitch, a.part == Part::LeftLeg));
    }
    None
}
