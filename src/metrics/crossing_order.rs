//! The interlock-topology metric (DESIGN.md section 7): at every crossing of two pieces of
//! yarn seen along the surface normal, is the one in front the one the stitch pattern says?
//!
//! Crossings are found in the (u, v) domain, where the normal offset lambda is the depth:
//! two centreline segments whose (u, v) projections intersect cross there, and the one with
//! the larger lambda at the intersection is in front. Each segment knows the stitch it belongs
//! to and which part of the loop it is (sinker, left leg, head, right leg), so the pattern
//! gives the expected order of the crossings it decides:
//!
//! - a leg and the head of the loop it is pulled through: the leg in front for a knit stitch,
//!   behind for a purl;
//! - two loops of one row that lean across each other (a cable) or are gathered by one
//!   decrease: the one with the higher layer in front;
//! - the crossed legs of a twisted stitch: the leg the yarn reaches first in front;
//! - a float past a slipped stitch and the loop it passes: the float in front when the yarn
//!   was held in front.
//!
//! Other crossings (a sinker passing the leg tops of the row below, whose side our offset
//! model leaves to the clearance tuning) are counted as undecided, not judged.

use glam::{Vec2, Vec3};

use crate::lattice::Lattice;
use crate::pattern::{Face, Form, StitchPattern};
use crate::skeleton::stitch_shape::landing;
use crate::skeleton::{YarnPiece, KEY_POINTS};

/// The result: crossings the pattern decides, how many of them agree, and the rest.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CrossingOrder {
    pub decided: usize,
    pub agree: usize,
    pub undecided: usize,
    /// The first disagreement found, described, for a test's message.
    pub first_disagreement: Option<String>,
}

impl CrossingOrder {
    /// The fraction of decided crossings that agree (1 when there are none).
    pub fn fraction(&self) -> f64 {
        if self.decided == 0 {
            1.0
        } else {
            self.agree as f64 / self.decided as f64
        }
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
            segs.push(Seg {
                a,
                b,
                piece: pi,
                index: j,
                course: pc.course,
                wale: (pc.first_wale + stitch.min(pc.stitches.saturating_sub(1))) % wales,
                part,
                float: pc.float_color.is_some(),
                knot: pc.bobble,
            });
        }
    }
    // A uniform grid over (u, v) with cells of one stitch.
    let cell = lattice.tile;
    let key = |p: Vec2| ((p.x / cell.x).floor() as i64, (p.y / cell.y).floor() as i64);
    let mut grid: std::collections::HashMap<(i64, i64), Vec<usize>> =
        std::collections::HashMap::new();
    for (i, s) in segs.iter().enumerate() {
        let (lo, hi) = (
            s.a.truncate().min(s.b.truncate()),
            s.a.truncate().max(s.b.truncate()),
        );
        let (k0, k1) = (key(lo), key(hi));
        for x in k0.0..=k1.0 {
            for y in k0.1..=k1.1 {
                grid.entry((x, y)).or_default().push(i);
            }
        }
    }
    let columns = (period / cell.x).round() as i64;
    let mut result = CrossingOrder::default();
    let mut seen = std::collections::HashSet::new();
    for (i, s) in segs.iter().enumerate() {
        let (lo, hi) = (
            s.a.truncate().min(s.b.truncate()),
            s.a.truncate().max(s.b.truncate()),
        );
        let (k0, k1) = (key(lo), key(hi));
        for x in k0.0..=k1.0 {
            for y in k0.1..=k1.1 {
                let shifts: &[i64] = if lattice.cyclic_u { &[0, -1, 1] } else { &[0] };
                for &wrap in shifts {
                    let Some(list) = grid.get(&(x + wrap * columns, y)) else {
                        continue;
                    };
                    for &k in list {
                        if k <= i || !seen.insert((i, k, wrap)) {
                            continue;
                        }
                        let o = &segs[k];
                        if o.piece == s.piece && o.index.abs_diff(s.index) < 2 {
                            continue;
                        }
                        let off = Vec3::new(wrap as f32 * period, 0.0, 0.0);
                        let Some((ls, lo_)) = intersect(s.a, s.b, o.a - off, o.b - off) else {
                            continue;
                        };
                        match expected(lattice, pattern, s, o) {
                            None => result.undecided += 1,
                            Some(s_front) => {
                                result.decided += 1;
                                if (ls > lo_) == s_front {
                                    result.agree += 1;
                                } else if result.first_disagreement.is_none() {
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
                            }
                        }
                    }
                }
            }
        }
    }
    result
}

/// Where the (u, v) projections of segments `a0 a1` and `b0 b1` cross (not at an end), the
/// depths (lambda) of each there.
fn intersect(a0: Vec3, a1: Vec3, b0: Vec3, b1: Vec3) -> Option<(f32, f32)> {
    let (p, r) = (a0.truncate(), (a1 - a0).truncate());
    let (q, s) = (b0.truncate(), (b1 - b0).truncate());
    let denom = r.perp_dot(s);
    if denom.abs() < 1e-12 {
        return None;
    }
    let t = (q - p).perp_dot(s) / denom;
    let u = (q - p).perp_dot(r) / denom;
    let inside = |x: f32| (1e-4..=1.0 - 1e-4).contains(&x);
    (inside(t) && inside(u)).then_some((a0.z + t * (a1.z - a0.z), b0.z + u * (b1.z - b0.z)))
}

/// Whether `a` should be in front of `b` where they cross, if the pattern decides it.
fn expected(lattice: &Lattice, pattern: &StitchPattern, a: &Seg, b: &Seg) -> Option<bool> {
    // A float of stranded colourwork runs behind the fabric, a bobble's ball in front of it.
    if a.float || b.float {
        return (a.float != b.float).then_some(b.float);
    }
    if a.knot || b.knot {
        return (a.knot != b.knot).then_some(a.knot);
    }
    let wales = lattice.wales;
    let cell = |s: &Seg| pattern.stitch(s.course, s.wale);
    let dest =
        |s: &Seg| landing(lattice, pattern, s.course, s.wale).rem_euclid(wales as isize) as usize;
    let is_leg = |s: &Seg| matches!(s.part, Part::LeftLeg | Part::RightLeg);
    let (ca, cb) = (cell(a), cell(b));
    let float = |c: crate::pattern::Stitch| match c.form {
        Form::Slip { yarn_front } => Some(yarn_front),
        _ => None,
    };
    // A float and the loop it passes (not where the yarn goes in and out of the float, whose
    // side the yarn is changing).
    if a.course != b.course && a.part != Part::Sinker && b.part != Part::Sinker {
        if let Some(front) = float(ca) {
            return Some(front);
        }
        if let Some(front) = float(cb) {
            return Some(!front);
        }
    }
    // A leg and the head of the loop it is pulled through.
    let pulled_through = |leg: &Seg, head: &Seg| {
        let rise = usize::from(cell(head).rise > 0 && head.course + 1 < lattice.courses);
        is_leg(leg)
            && head.part == Part::Head
            && head.course + 1 + rise == leg.course
            && dest(head) == leg.wale
            && float(cell(leg)).is_none()
    };
    if pulled_through(a, b) {
        return Some(ca.face == Face::Knit);
    }
    if pulled_through(b, a) {
        return Some(cb.face != Face::Knit);
    }
    // Loops of one row crossing or stacked: the higher layer in front.
    if a.course == b.course
        && a.wale != b.wale
        && a.part != Part::Sinker
        && b.part != Part::Sinker
        && ca.land_layer != cb.land_layer
        && ca.land_layer != 0
        && cb.land_layer != 0
    {
        return Some(ca.land_layer > cb.land_layer);
    }
    // The crossed legs of a twisted stitch.
    if a.piece == b.piece
        && a.course == b.course
        && a.wale == b.wale
        && ca.form == Form::Twisted
        && is_leg(a)
        && is_leg(b)
        && a.part != b.part
    {
        return Some(a.part == Part::LeftLeg);
    }
    None
}
