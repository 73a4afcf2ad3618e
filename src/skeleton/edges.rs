//! The cast-on and bind-off edges of a fabric with open ends along v: no loop hangs free.
//!
//! Without them, the first course's feet (its sinker arcs) and the last course's heads are
//! live loops that nothing passes through: knitting that would run the moment it came off
//! the needles. A knitter starts on a cast-on and ends with a bind-off; we build both as
//! extra pieces of yarn, one per run of edge stitches:
//!
//! - **Cast-on**, under every stitch with no stitch below it: the top half of a course of
//!   loops (leg tops and heads, exactly where the course below would hold them, so every
//!   stitch of the first course is pulled through a loop by the interlock rule of
//!   [`super::crossings`]) standing on a strand that runs along the edge, 0.6 of a row below
//!   the first course. The strand passes the first course's sinkers on the interlock's
//!   side, a yarn diameter clear.
//! - **Bind-off**, over every stitch with no stitch above it, worked as the pattern's next
//!   row (knit over the stitches the next row knits, purl over the purls; a stitch that row
//!   would slip is worked like its nearest worked neighbour, as a knitter binds off linen
//!   stitch in one face, so the chain does not swap sides between two loops), so the last
//!   course's heads sit exactly as the tuned offsets put them. Each bind-off loop is pulled
//!   through the loop below it like any course, then lies over to the right, its head
//!   behind (for a knit) the left leg of the next bind-off loop: the next loop is pulled
//!   through it, as passing each stitch over the next makes a chain. The last loop of an
//!   open run is the fastened-off end.
//!
//! The lattice leaves a third of a row beyond the first and last courses
//! ([`crate::lattice::ROW_OVERHANG`]); the edges reach up to about twice that, so at the
//! border of a surface they hang a little past it, carried on along the surface's tangent
//! ([`beyond_border`]): the fabric itself is laid out exactly as with live loops.
//!
//! Units: (u, v) in the surface's domain; lambda in scene units (the offsets' own).

use glam::{Vec2, Vec3};

use super::stitch_shape::{landing, stitch_key_points, tile_at};
use super::{NormalOffsets, YarnPiece, KEY_POINTS};
use crate::lattice::{Lattice, Tile};
use crate::pattern::{Face, Form, Stitch, StitchPattern};
use crate::surface::{Surface, SurfacePoint};

/// Where a point of an edge at (u, v) lies: on the surface, or past an open v end of the
/// domain (the edges reach up to about three quarters of a row beyond it), carried on along the
/// surface's tangent there, `step` (in v) measured back from the border. At a pole, and for a
/// point off every UV island, the nearest point of the surface.
pub fn beyond_border(surface: &dyn Surface, uv: Vec2, step: f32) -> SurfacePoint {
    let domain = surface.domain();
    if !surface.cyclic_v() && (uv.y < domain.min.y || uv.y > domain.max.y) {
        let v = uv.y.clamp(domain.min.y, domain.max.y);
        let inward = if uv.y < domain.min.y { step } else { -step };
        let on = Vec2::new(uv.x, v);
        if let (Some(edge), Some(inside)) =
            (surface.eval(on), surface.eval(on + Vec2::new(0.0, inward)))
        {
            let along = (edge.position - inside.position) / step;
            // Not past a pole (a border that closes to a point round a cyclic u): there the
            // edge gathers its loops at the pole, as a knitter closes a crown.
            let opposite = Vec2::new(uv.x + 0.5 * domain.size().x, v);
            let pole = surface.cyclic_u()
                && surface.eval(opposite).is_some_and(|o| {
                    (o.position - edge.position).length() < 4.0 * step * along.length()
                });
            if !pole {
                return SurfacePoint {
                    position: edge.position + (uv.y - v).abs() * along,
                    normal: edge.normal,
                };
            }
        }
    }
    surface.eval(uv).unwrap_or_else(|| surface.eval_nearest(uv))
}

/// Which edge a piece of yarn finishes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Edge {
    /// Under the stitches of [`YarnPiece::course`] that have no stitch below.
    CastOn,
    /// Over the stitches of [`YarnPiece::course`] that have no stitch above.
    BindOff,
}

/// How far below the bottom of its course the cast-on's strand runs, in rows (the first
/// course's sinkers dip at most 0.35).
pub const CAST_ON_DROP: f32 = 0.6;
/// Where the cast-on's leg bottoms stand below the bottom of its course, in rows.
pub const CAST_ON_LEG_DROP: f32 = 0.45;
/// How much nearer their column's edges than a course's leg bottoms they stand, in stitch
/// widths.
pub const CAST_ON_LEG_SLANT: f32 = 0.1;
/// How far the cast-on's strand stands off the first course's sinker, on the interlock's
/// side, in yarn diameters (they may cross there).
pub const STRAND_CLEARANCE: f32 = 1.1;
/// A bind-off loop's left leg top: how far into its column (stitch widths) and above the
/// last course's heads (rows). It stands high so that the loop's head, lying over to the
/// right, and its right leg, coming back low, pass a diameter apart.
pub const BIND_OFF_LEG_TOP: (f32, f32) = (0.30, 0.52);
/// Its head: past the left leg of the next bind-off loop (stitch widths from its own
/// column's left edge), and above the last course's heads (rows).
pub const BIND_OFF_HEAD: (f32, f32) = (1.45, 0.34);
/// Its right leg top, coming back under the head.
pub const BIND_OFF_RIGHT_LEG_TOP: (f32, f32) = (0.85, 0.26);
/// How far behind the next loop's legs (for a knit) a bind-off head lies, in diameters:
/// between them and the head of the last course that loop is pulled through.
pub const BIND_OFF_HEAD_DEPTH: f32 = 1.1;
/// The least depth of a bind-off loop's legs on its face side, in diameters.
pub const BIND_OFF_LEG_DEPTH: f32 = 0.75;

/// The edge pieces of a fabric whose stitches `fabric` (row-major) have a surface, over
/// the stitches `kept` (a subset of them: those built at this detail), in course order,
/// cast-ons before bind-offs. None along a cyclic v.
pub fn edge_pieces(lattice: &Lattice, fabric: &[bool], kept: &[bool]) -> Vec<YarnPiece> {
    if lattice.cyclic_v {
        return Vec::new();
    }
    let (courses, wales) = (lattice.courses, lattice.wales);
    let mut pieces = Vec::new();
    let mut row = vec![false; wales];
    for course in 0..courses {
        for edge in [Edge::CastOn, Edge::BindOff] {
            for (w, r) in row.iter_mut().enumerate() {
                let i = course * wales + w;
                let open = match edge {
                    Edge::CastOn => course == 0 || !fabric[i - wales],
                    Edge::BindOff => course + 1 == courses || !fabric[i + wales],
                };
                *r = kept[i] && fabric[i] && open;
            }
            for (first_wale, stitches, closed) in super::runs(&row, lattice.cyclic_u) {
                pieces.push(YarnPiece {
                    edge: Some(edge),
                    ..YarnPiece::course_run(course, first_wale, stitches, closed)
                });
            }
        }
    }
    pieces
}

/// Key points of an edge piece in (u, v, lambda), six per stitch, in yarn order.
pub fn edge_key_points(
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    piece: &YarnPiece,
    edge: Edge,
) -> Vec<Vec3> {
    let mut out = Vec::with_capacity(piece.stitches * KEY_POINTS);
    for j in 0..piece.stitches {
        let wale = piece.first_wale + j;
        let last = !piece.closed && j + 1 == piece.stitches;
        out.extend(match edge {
            Edge::CastOn => cast_on_stitch(lattice, pattern, offsets, piece.course, wale),
            Edge::BindOff => bind_off_stitch(lattice, pattern, offsets, piece.course, wale, last),
        });
    }
    out
}

/// The face a stitch of row `course` at wale `w` (in the domain) is worked with when the
/// row is worked plain (a cast-on's first row, a bind-off): its own, or for a slipped stitch,
/// which makes no loop of its own to show a face, that of the nearest stitch of the row that
/// is worked (left first), so that a bind-off over linen stitch's slips is one chain of one
/// face and does not swap sides between every pair of loops; knit where the whole row slips.
pub(super) fn worked_face(
    lattice: &Lattice,
    pattern: &StitchPattern,
    course: usize,
    w: usize,
) -> Face {
    let wales = lattice.wales;
    let worked = |x: usize| {
        let s = pattern.stitch(course, x);
        (!matches!(s.form, Form::Slip { .. })).then_some(s.face)
    };
    if let Some(face) = worked(w) {
        return face;
    }
    for step in 1..wales {
        let (left, right) = if lattice.cyclic_u {
            (Some((w + wales - step) % wales), Some((w + step) % wales))
        } else {
            (w.checked_sub(step), (w + step < wales).then_some(w + step))
        };
        if let Some(face) = left.and_then(worked).or_else(|| right.and_then(worked)) {
            return face;
        }
    }
    Face::Knit
}

/// The stitch of row `course` at `wale` (any wale: the pattern repeats), as a plain loop of
/// the face it is worked with ([`worked_face`]), and its left neighbour (itself at an open u
/// edge).
fn plain_and_left(
    lattice: &Lattice,
    pattern: &StitchPattern,
    course: usize,
    wale: usize,
) -> (Stitch, Stitch) {
    let wales = lattice.wales;
    let w = wale % wales;
    let plain = |x: usize| Stitch::plain(worked_face(lattice, pattern, course, x));
    let this = plain(w);
    let left = if w > 0 {
        plain(w - 1)
    } else if lattice.cyclic_u {
        plain(wales - 1)
    } else {
        this
    };
    (this, left)
}

/// The loops (course, wale) a bind-off over wale `w` of `course` is pulled through: those of
/// `course` that land in `w` (under a cable or a decrease, loops of other wales; at most
/// [`LANDING_REACH`] away), or under a slipped stitch the loop of the course below that it
/// carries up.
fn landing_here<'a>(
    lattice: &'a Lattice,
    pattern: &'a StitchPattern,
    course: usize,
    w: usize,
) -> impl Iterator<Item = (usize, usize)> + 'a {
    let wales = lattice.wales as isize;
    (-LANDING_REACH..=LANDING_REACH).filter_map(move |d| {
        let from = w as isize + d;
        let from = if lattice.cyclic_u {
            from.rem_euclid(wales)
        } else if (0..wales).contains(&from) {
            from
        } else {
            return None;
        };
        let lands = landing(lattice, pattern, course, from as usize);
        let lands = if lattice.cyclic_u {
            lands.rem_euclid(wales)
        } else {
            lands
        };
        if lands != w as isize {
            return None;
        }
        let slipped = matches!(
            pattern.stitch(course, from as usize).form,
            Form::Slip { .. }
        );
        match (slipped, course) {
            (false, _) => Some((course, from as usize)),
            (true, 0) => None,
            (true, _) => Some((course - 1, from as usize)),
        }
    })
}

/// How far a loop may lean, in wales, for [`landing_here`] (a 4/4 cable leans four).
const LANDING_REACH: isize = 6;

/// Lambdas `l` with a contact relief's corrections (in diameters of `diameter`) added.
fn relieved(
    mut l: [f32; KEY_POINTS],
    relief: Option<[f32; KEY_POINTS]>,
    diameter: f32,
) -> [f32; KEY_POINTS] {
    if let Some(r) = relief {
        for (l, r) in l.iter_mut().zip(r) {
            *l += r * diameter;
        }
    }
    l
}

/// The largest leg offset of a loop, in scene units: the edges' legs stand at least this far
/// out so that they clear the yarn they pass even where the tuned leg bottoms lie on the
/// surface (rib).
fn leg_depth(l: &[f32; KEY_POINTS]) -> f32 {
    l[1].abs().max(l[2].abs()).max(l[4].abs())
}

/// The cast-on loop under stitch (`course`, `wale`): the top of the loop the stitch is
/// pulled through, on a strand along the edge.
fn cast_on_stitch(
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    course: usize,
    wale: usize,
) -> [Vec3; KEY_POINTS] {
    let w = wale % lattice.wales;
    // As the course below would be (the pattern's row before, with its contact relief):
    // its leg tops on the puller's face side, its head on the other. Under a row whose
    // loops below lean (a cable row) the cast-on's loops stand straight, without the
    // corrections made for leaning loops.
    let row_below = course + pattern.height() - 1;
    let straight = pattern.stitch(row_below, w).land_offset == 0;
    let (offsets, relief) = offsets.for_stitch(row_below, w, straight);
    let s = offsets.loop_shape;
    let t = tile_at(lattice, course, wale as isize);
    let (across, up) = (t.n2 - t.n3, t.n0 - t.n3);
    let rise = cast_on_rise(lattice, pattern, course, w);
    let (puller, left) = plain_and_left(lattice, pattern, course + rise, wale);
    let l = relieved(
        offsets.lambdas(puller, puller, left),
        relief,
        offsets.diameter,
    );
    let side = puller.side();
    // The legs pass in front of (for a knit puller) the first course's yarn where it climbs
    // from its sinkers to its leg bottoms, a diameter out.
    let here = stitch_key_points(lattice, pattern, offsets, course, w);
    let next = stitch_key_points(lattice, pattern, offsets, course, wale + 1);
    let arms = (side * 0.5 * (here[0].z + here[1].z)).max(side * 0.5 * (here[5].z + next[0].z));
    let leg = side * leg_depth(&l).max(arms + STRAND_CLEARANCE * offsets.diameter);
    // The strand passes the sinker of the stitch above on the side the interlock gives it,
    // at least as far out as the legs: the first course's yarn climbs from that sinker to
    // its leg bottoms right over the strand.
    let above = stitch_key_points(lattice, pattern, offsets, course + rise, w);
    let sinker = here[0].z;
    // The head lies a diameter behind the legs pulled through it (on the puller's face
    // side) where they cross it, a quarter of the way up from their feet, whatever the tuned
    // row below would give it.
    let legs = [
        0.75 * above[1].z + 0.25 * above[2].z,
        0.75 * above[5].z + 0.25 * above[4].z,
    ]
    .map(|z| side * z)
    .into_iter()
    .fold(f32::MAX, f32::min);
    let head = side * (side * l[3]).min(legs - offsets.diameter);
    let strand = side * (side * sinker + STRAND_CLEARANCE * offsets.diameter).max(leg.abs());
    // The legs rise steeply by the strand's corners, where the first course's yarn dips
    // furthest the other way to its sinkers, not under its leg bottoms (where it is already
    // back out on the face side).
    let (drop, leg_drop) = (-CAST_ON_DROP * up, -CAST_ON_LEG_DROP * up);
    let leg_at = s.leg_bottom - CAST_ON_LEG_SLANT;
    // The loop's top: at the foot of the stitch above, or a row higher under each slipped
    // stitch, which carries it up to the next course.
    let (top, top_across, top_up) = if rise > 0 {
        let t = tile_at(lattice, course + rise - 1, wale as isize);
        (t.n0, t.n1 - t.n0, t.n4 - t.n0)
    } else {
        (t.n3, across, up)
    };
    if matches!(
        pattern.stitch(course, w).form,
        Form::YarnOver | Form::MakeOne
    ) {
        // Nothing is pulled through the cast-on there (a yarn-over is made over the
        // needle): the strand runs straight on under it.
        return std::array::from_fn(|i| {
            let p = t.n3 + (i as f32 / KEY_POINTS as f32) * across + drop;
            Vec3::new(p.x, p.y, strand)
        });
    }
    let points: [(Vec2, f32); KEY_POINTS] = [
        (t.n3 + drop, strand),
        (t.n3 + leg_at * across + leg_drop, leg),
        (top + s.leg_top * top_across, l[2]),
        (top + 0.5 * top_across + s.head_reach * top_up, head),
        (top + (1.0 - s.leg_top) * top_across, l[4]),
        (t.n3 + (1.0 - leg_at) * across + leg_drop, leg),
    ];
    finish(points)
}

/// How many courses the cast-on loop under stitch (`course`, `wale`) is carried up by
/// stitches slipped over it, as [`super::stitch_shape::carried_rise`] for a loop of the
/// fabric: 0 where that stitch is worked, 1 under one slipped stitch, 2 where the next row
/// slips it again; capped at the last course.
pub(super) fn cast_on_rise(
    lattice: &Lattice,
    pattern: &StitchPattern,
    course: usize,
    wale: usize,
) -> usize {
    let last = lattice.courses.saturating_sub(1);
    let mut rise = 0;
    while course + rise < last
        && rise < pattern.height()
        && matches!(pattern.stitch(course + rise, wale).form, Form::Slip { .. })
    {
        rise += 1;
    }
    rise
}

/// The bind-off loop over stitch (`course`, `wale`), worked as the pattern's next row there;
/// `last`: the fastened-off end of an open run (its head does not lie over).
fn bind_off_stitch(
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    course: usize,
    wale: usize,
    last: bool,
) -> [Vec3; KEY_POINTS] {
    let (offsets, l, leg) = bind_off_legs(lattice, pattern, offsets, course, wale);
    let s = offsets.loop_shape;
    let t = tile_at(lattice, course, wale as isize);
    // The left leg stands as tall as the loop before it needs to lie its head across it;
    // the right leg top only as tall as this loop's own foot needs (see [`bind_off_up`]).
    let (across, up, own_up) = (
        t.n1 - t.n0,
        bind_off_up(lattice, course, wale as isize),
        own_bind_off_up(&t),
    );
    let at =
        |(across_at, up_at): (f32, f32)| t.n0 + across_at * across + (s.head_reach + up_at) * up;
    let at_own = |(across_at, up_at): (f32, f32)| {
        t.n0 + across_at * across + (s.head_reach + up_at) * own_up
    };
    let (head, head_lambda, right_top, right_lambda) = if last {
        // Fastened off: a small upright loop.
        let (x, y) = BIND_OFF_LEG_TOP;
        (at((0.5, y + 0.08)), leg, at_own((1.0 - x, y)), leg)
    } else {
        // The head passes the next loop's left leg where it crosses, two thirds of the way
        // up from its foot, a diameter and more on the chain's side.
        let (_, next_l, next_leg) = bind_off_legs(lattice, pattern, offsets, course, wale + 1);
        // The chain's side is the next loop's face: its legs need only keep a diameter from
        // the head below, so their depth may have either sign.
        let side = plain_and_left(lattice, pattern, course + 1, wale + 1)
            .0
            .side();
        let crossing = 0.4 * next_l[1] + 0.6 * next_leg;
        let head = crossing - side * BIND_OFF_HEAD_DEPTH * offsets.diameter;
        // Placed in the next column's tile: rows of leaning loops are shaped column by
        // column, so the next tile's top need not continue this one's.
        let n = tile_at(lattice, course, wale as isize + 1);
        let (x, y) = BIND_OFF_HEAD;
        let head_at = n.n0
            + (x - 1.0) * (n.n1 - n.n0)
            + (s.head_reach + y) * bind_off_up(lattice, course, wale as isize + 1);
        // The yarn comes back from the head across the next loop's leg a second time, on
        // the same side: the right leg top stays no further towards that leg than the head
        // and half a diameter.
        let right = side * (side * 0.5 * leg).min(side * head + 0.5 * offsets.diameter);
        (head_at, head, at_own(BIND_OFF_RIGHT_LEG_TOP), right)
    };
    let points: [(Vec2, f32); KEY_POINTS] = [
        (
            // The sinker dips into the last course at the tile's left corner: by its left side.
            t.n0 - s.sinker_dip * (t.n0 - t.n3),
            bind_off_sinker(lattice, pattern, offsets, course, wale, l[0]),
        ),
        (t.n0 + s.leg_bottom * across, l[1]),
        (at(BIND_OFF_LEG_TOP), leg),
        (head, head_lambda),
        (right_top, right_lambda),
        (t.n0 + (1.0 - s.leg_bottom) * across, l[5]),
    ];
    finish(points)
}

/// A row's height over the last course's tile `t`, for the bind-off loop worked on it: the
/// tile's left side, stretched to the length of the taller of its two sides. Under a cable
/// row the tuned row heights make the last course short at some node columns and tall at
/// others ([`crate::lattice::RowHeights`]); the bind-off row is worked plain, and a loop
/// measured by its left side only stood half as tall as its neighbour, whose head, lying
/// over to it, then passed above the short loop's leg instead of across it, and nothing held
/// it (a 3/3 cable bound off on the row under its crossing row). The mean of the sides held
/// it but lowered other loops onto the heads below (a 2/2 cable's clearance fell from 0.58
/// to 0.23). On a regular tile both sides are equal and the left one is taken unchanged.
/// The loop's foot needs this much: its right leg top stands at it.
fn own_bind_off_up(t: &Tile) -> Vec2 {
    stretched_side(t, (t.n1 - t.n2).length())
}

/// The height the bind-off loop over (`course`, `wale`) stands at where the loop before it
/// lies its head across its left leg: [`own_bind_off_up`], stretched further to the left
/// side of the tile before. The loop before stands as tall as its own tile's sides, and
/// where that is taller than this one's (a 4/4 cable's crossing row is three rows tall over
/// its node columns, a regular one beside it), its head, placed at this loop's height, came
/// down steeply from its tall legs and passed above this loop's leg top: the loop before
/// was held by nothing (a 4/4 cable in 16 rows bound off on its tall row, 2 of 719 loops).
fn bind_off_up(lattice: &Lattice, course: usize, wale: isize) -> Vec2 {
    let t = tile_at(lattice, course, wale);
    let mut tallest = (t.n1 - t.n2).length();
    if wale > 0 || lattice.cyclic_u {
        let before = tile_at(lattice, course, wale - 1);
        tallest = tallest.max((before.n0 - before.n3).length());
    }
    stretched_side(&t, tallest)
}

/// The left side of `t` stretched to `length` where that is longer: the left side's
/// direction keeps a length that tips from one side to the other moving the loop
/// continuously (taking the right side's vector outright jumped it sideways where two
/// nearly equal sides swapped under round-off, as a sheared parent's transform does).
fn stretched_side(t: &Tile, length: f32) -> Vec2 {
    let left = t.n0 - t.n3;
    let left_len = left.length();
    if length > left_len && left_len > 0.0 {
        left * (length / left_len)
    } else {
        left
    }
}

/// The depth of the sinker at the left corner of the bind-off loop over (`course`, `wale`):
/// `tuned`, or further to the side the interlock gives it, a diameter past the leg tops of
/// the loops it passes there (which the relief of a row with slipped stitches may have moved
/// towards it) where the loops on both sides of the corner agree on that side.
fn bind_off_sinker(
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    course: usize,
    wale: usize,
    tuned: f32,
) -> f32 {
    let w = wale % lattice.wales;
    let side_of = |x: usize| -plain_and_left(lattice, pattern, course + 1, x).0.side();
    let here = side_of(w);
    let mut reach = here * tuned;
    for (c, from) in landing_here(lattice, pattern, course, w) {
        reach = reach.max(
            here * stitch_key_points(lattice, pattern, offsets, c, from)[2].z + offsets.diameter,
        );
    }
    if w > 0 || lattice.cyclic_u {
        let left = (w + lattice.wales - 1) % lattice.wales;
        if side_of(left) == here {
            for (c, from) in landing_here(lattice, pattern, course, left) {
                reach = reach.max(
                    here * stitch_key_points(lattice, pattern, offsets, c, from)[4].z
                        + offsets.diameter,
                );
            }
        }
    }
    here * reach
}

/// The offsets a bind-off loop over stitch (`course`, `wale`) is made with, its foot's
/// lambdas as the next course's would be (with the contact relief of the pattern's row),
/// and its legs' offset (signed: the face side of the pattern's next row there). Its leg
/// bottoms (lambdas 1 and 5) and legs pass the head of the loop below a diameter out on
/// their side, wherever the tuned feet of a course there would stand.
fn bind_off_legs<'a>(
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &'a NormalOffsets,
    course: usize,
    wale: usize,
) -> (&'a NormalOffsets, [f32; KEY_POINTS], f32) {
    let w = wale % lattice.wales;
    let (offsets_here, relief) = offsets.for_stitch(course + 1, w, true);
    let (this, left) = plain_and_left(lattice, pattern, course + 1, wale);
    let mut l = relieved(
        offsets_here.lambdas(this, this, left),
        relief,
        offsets.diameter,
    );
    let side = this.side();
    // The loops of the last course that land in this column (under a cable or a decrease,
    // loops of other columns), and where the legs cross their heads' arches: near the head,
    // a quarter of the way to either leg top.
    let below: Vec<[Vec3; KEY_POINTS]> = landing_here(lattice, pattern, course, w)
        .map(|(c, from)| stitch_key_points(lattice, pattern, offsets, c, from))
        .collect();
    let clear = |top: usize| {
        below
            .iter()
            .map(|k| side * (0.75 * k[3].z + 0.25 * k[top].z))
            .fold(f32::MIN, f32::max)
            + offsets.diameter
    };
    let offsets = offsets_here;
    // Both feet move out together, keeping the tuned difference that parts the loop's two
    // leg bottoms (a sixth of a stitch apart) in depth.
    let out = (clear(2) - side * l[1])
        .max(clear(4) - side * l[5])
        .max(0.0);
    l[1] += side * out;
    l[5] += side * out;
    // At least BIND_OFF_LEG_DEPTH out on the face side: the previous loop's head passes
    // behind the legs (for a knit) on its way down, and a leg near the surface, which the
    // head below would allow where it lies far back, leaves the head no room to get past.
    let leg = side
        * leg_depth(&l)
            .max(clear(2))
            .max(clear(4))
            .max(BIND_OFF_LEG_DEPTH * offsets.diameter);
    (offsets, l, leg)
}

/// The points in (u, v, lambda). They are not kept to the lattice's rows
/// ([`Lattice::keep_on_fabric`]): the surface reaches [`EDGE_ROOM`] further.
fn finish(points: [(Vec2, f32); KEY_POINTS]) -> [Vec3; KEY_POINTS] {
    points.map(|(p, l)| Vec3::new(p.x, p.y, l))
}
