//! Contact relief: per-stitch corrections to the key points' normal offsets that push yarns
//! apart where the stitch model brings them closer than a yarn diameter.
//!
//! The offsets of [`super::NormalOffsets`] come from one rule per kind of key point, and its
//! coefficients are tuned for the whole pattern at once ([`super::tuning`]). Leaning loops
//! (cables, decreases, twisted stitches) meet their neighbours in places no single coefficient
//! reaches: two loops leaning the same way run side by side, gathered loops share a landing
//! tile. Contact relief resolves those contacts locally, as touching yarns do: on a flat
//! patch of the pattern (one repeat and a margin of stitches round it, unit yarn diameter) every pair of yarn
//! segments nearer than [`TARGET`] diameters is pushed apart along the surface normal, each
//! by half the shortfall and in the order it already has (the one in front moves forwards),
//! so no crossing changes sides. Pushes on the centreline go to the key points whose spline
//! segment carries them, and the pushes on the middle repeat become the corrections of their
//! pattern cells; a few dozen rounds settle them. The result depends only on the pattern, the
//! stitch proportions and the tension, and is cached with the tuned offsets.
//!
//! A piece whose edge cuts a crossing or a decrease knits those wales straight
//! ([`super::StraightWales`]) with the relief of the pattern straightened; where they meet
//! the wales knitted as the pattern says, neither relief was made for what is on the other
//! side. [`relieve_edges`] pushes there the same way, on a flat strip of the piece itself
//! one repeat of rows tall, into corrections per pattern row and wale of the piece
//! ([`EdgeRelief`]), cached per piece width.
//!
//! Units: corrections are in yarn diameters, indexed by pattern cell (row, column) and key
//! point k0..k5 (by pattern row and wale of the piece for [`EdgeRelief`]).

use glam::Vec3;
use rayon::prelude::*;

use super::crossings::{decided_crossings, DecidedCrossing};
use super::relief::NO_CELL;
pub use super::relief::{ContactRelief, EdgeRelief};
use super::{sample_piece, yarn_pieces, NormalOffsets, SplineSampling, KEY_POINTS};
use crate::lattice::Lattice;
use crate::metrics::{
    clearance, ClosePairCache, YarnPolyline, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
};
use crate::pattern::StitchPattern;
use crate::surface::{PlaneSurface, Surface};

/// Clearance the relief aims for, in diameters: over one by enough that what the flat patch
/// does not model keeps the output at or above the goal of 0.95: the output's coarser
/// sampling, the surface's curvature and the irregularity of hand knitting (the add-on's
/// default kappa 0.005 took up to 0.04 diameters off feather and fan relieved to 1.02).
pub const TARGET: f32 = 1.05;
/// The depth, in diameters, by which the relief turns a crossing that is the wrong way
/// round (or holds one that is nearly so) onto its rule's side: enough that the output's
/// sampling, a curved surface and irregularity do not turn it back. Crossings clear of it are
/// pushed apart as any close pair is, in the order they have.
const CROSSING_MARGIN: f32 = 0.5;
/// Rounds of pushing.
const ROUNDS: usize = 96;
/// Fraction of the summed pushes applied per round: several contacts on one key point add
/// up, so a full step would overshoot.
const RATE: f32 = 0.5;
/// Largest correction, in diameters: the relief bends yarns aside, it does not restack the
/// fabric.
const LIMIT: f32 = 1.5;
/// Largest change of one correction in one round, in diameters: small enough that no strand
/// jumps through another between two rounds (which would turn a crossing round).
const STEP: f32 = 0.1;
/// Stitches round the measured repeat of the patch, at least: wider than the furthest a
/// loop leans ([`reach`]), and two rows above and below.
const MARGIN_WALES: usize = 4;
/// Wales either side of a wale knitted straight that [`relieve_edges`] corrects, at least:
/// as far as a loop leans.
const EDGE_WALES: usize = 3;

/// The furthest a loop of `pattern` leans, in columns, and the margin of wales a patch
/// keeps round the loops it relieves (one more, and at least [`MARGIN_WALES`]). A 3/3
/// cable's loops lean three columns and fit the least margin; a 5/5 cable's crossed the
/// loops just past a margin of four, which stood on no patch, and were relieved onto their
/// depth (a 24-row repeat on a 24-stitch sheet: clearance 0.12, 1st percentile 0.29; with
/// the margin past its lean, 0.42 and 0.55).
fn reach(pattern: &StitchPattern) -> (usize, usize) {
    let lean = (0..pattern.height())
        .flat_map(|r| (0..pattern.width()).map(move |c| (r, c)))
        .map(|(r, c)| usize::from(pattern.stitch(r, c).land_offset.unsigned_abs()))
        .max()
        .unwrap_or(0);
    (lean, MARGIN_WALES.max(lean + 1))
}
const MARGIN_COURSES: usize = 2;
/// Samples per loop of the patch's centrelines.
const SAMPLES: usize = 24;
/// How far beyond [`TARGET`] the relief's rounds keep track of pairs of yarn segments, in
/// diameters ([`ClosePairCache`]): a segment that moves half this far is searched round
/// afresh.
const PAIR_MARGIN: f32 = 0.5;

/// A flat patch of the pattern with unit yarn diameter, stitches `width x height`.
struct Patch {
    plane: PlaneSurface,
    lattice: Lattice,
    pieces: Vec<super::YarnPiece>,
    /// The middle repeat: first course and first wale.
    middle: (usize, usize),
}

impl Patch {
    fn new(pattern: &StitchPattern, width: f32, height: f32, per_lean: f32) -> Self {
        // One repeat with a margin of stitches round it. Any `height` consecutive courses and
        // `width` consecutive wales hold every pattern cell once, so the repeat may start
        // anywhere.
        let (_, margin) = reach(pattern);
        let wales = pattern.width() + 2 * margin;
        let courses = pattern.height() + 2 * MARGIN_COURSES;
        let plane = PlaneSurface {
            width: wales as f32 * width,
            height: (courses as f32 + 2.0 * crate::lattice::ROW_OVERHANG) * height,
        };
        let lattice = super::leaning_rows::shaped(
            Lattice::regular(plane.domain(), courses, wales, false, false).window(),
            pattern,
            width,
            height,
            per_lean,
            super::leaning_rows::Ramp::Alike,
        );
        let pieces = yarn_pieces(&lattice, &vec![true; courses * wales]);
        Patch {
            plane,
            lattice,
            pieces,
            middle: (MARGIN_COURSES, margin),
        }
    }

    /// A flat strip of a piece of `wales` wales across u (open, not a window: its edges cut
    /// crossings as the piece's do), one repeat of rows and a margin of courses tall, with
    /// yarn only in the wales `built` says.
    fn strip(
        pattern: &StitchPattern,
        width: f32,
        height: f32,
        per_lean: f32,
        built_wales: &[bool],
    ) -> Self {
        let wales = built_wales.len();
        let courses = pattern.height() + 2 * MARGIN_COURSES;
        let plane = PlaneSurface {
            width: wales as f32 * width,
            height: (courses as f32 + 2.0 * crate::lattice::ROW_OVERHANG) * height,
        };
        let lattice = super::leaning_rows::shaped(
            Lattice::regular(plane.domain(), courses, wales, false, false),
            pattern,
            width,
            height,
            per_lean,
            super::leaning_rows::Ramp::Alike,
        );
        let built: Vec<bool> = (0..courses)
            .flat_map(|_| built_wales.iter().copied())
            .collect();
        let pieces = yarn_pieces(&lattice, &built);
        Patch {
            plane,
            lattice,
            pieces,
            middle: (MARGIN_COURSES, 0),
        }
    }

    /// Centrelines of every piece (points, and each sample's spline parameter).
    fn centrelines(
        &self,
        pattern: &StitchPattern,
        offsets: &NormalOffsets,
        sampling: &SplineSampling,
    ) -> Vec<Vec<Vec3>> {
        self.pieces
            .par_iter()
            .map(|piece| {
                let n = piece.sample_count(SAMPLES);
                let mut pts = vec![Vec3::ZERO; n];
                let mut nrm = vec![Vec3::ZERO; n];
                let mut own = vec![0u32; n];
                sample_piece(
                    &self.plane,
                    &self.lattice,
                    pattern,
                    offsets,
                    sampling,
                    piece,
                    &mut pts,
                    &mut nrm,
                    &mut own,
                );
                pts
            })
            .collect()
    }
}

impl Patch {
    /// Every crossing of `lines` (this patch's centrelines, unit yarn diameter) that the
    /// pattern decides ([`decided_crossings`]).
    fn crossings(&self, pattern: &StitchPattern, lines: &[Vec<Vec3>]) -> Vec<DecidedCrossing> {
        let uv: Vec<Vec<Vec3>> = lines
            .iter()
            .map(|l| {
                l.iter()
                    .map(|p| Vec3::new(p.x / self.plane.width, p.y / self.plane.height, p.z))
                    .collect()
            })
            .collect();
        decided_crossings(&self.lattice, pattern, &self.pieces, &uv, SAMPLES)
    }
}

/// How far in front of the other the yarn a crossing's rule puts in front is, in diameters
/// (negative: the crossing is the wrong way round).
fn separation(c: &DecidedCrossing) -> f32 {
    if c.a_front {
        c.depths.0 - c.depths.1
    } else {
        c.depths.1 - c.depths.0
    }
}

/// Whether every crossing in `crossings` is the way round its rule says.
fn all_right(crossings: &[DecidedCrossing]) -> bool {
    crossings
        .iter()
        .all(|c| (c.depths.0 > c.depths.1) == c.a_front)
}

/// What a relief reached: the corrections (`None` where none improved on the start), the
/// patch's minimum clearance in diameters and whether every crossing the pattern decides is
/// the right way round, with them (without them, if `None`).
#[derive(Debug, Clone, PartialEq)]
pub struct Relieved<R> {
    pub relief: Option<R>,
    pub clearance: f32,
    pub crosses_right: bool,
}

fn polylines(lines: &[Vec<Vec3>]) -> Vec<YarnPolyline<'_>> {
    lines
        .iter()
        .map(|p| YarnPolyline {
            points: p,
            closed: false,
        })
        .collect()
}

/// Finds the relief of `pattern` knitted with stitches `width x height` yarn diameters and
/// spline `tension`, rows of leaning loops `per_lean` ([`super::leaning_rows`]), on top of
/// `offsets` (in diameters, without relief). No relief where the patch already clears
/// [`TARGET`] with every crossing the right way round.
pub fn relieve(
    pattern: &StitchPattern,
    width: f32,
    height: f32,
    tension: f32,
    per_lean: f32,
    offsets: &NormalOffsets,
) -> Relieved<ContactRelief> {
    let patch = Patch::new(pattern, width, height, per_lean);
    let sampling = SplineSampling {
        samples_per_loop: SAMPLES,
        tension,
        aspect: height / width,
    };
    let (h, w) = (pattern.height(), pattern.width());
    let start = {
        let lines = patch.centrelines(pattern, offsets, &sampling);
        (
            min_clearance(&lines),
            all_right(&patch.crossings(pattern, &lines)),
        )
    };
    if start.0 >= TARGET && start.1 {
        return Relieved {
            relief: None,
            clearance: start.0,
            crosses_right: true,
        };
    }
    let (r0, c0) = patch.middle;
    let relief = |lambdas: &[[f32; KEY_POINTS]]| ContactRelief {
        height: h,
        width: w,
        lambdas: lambdas.to_vec(),
    };
    let reached = relax(
        &patch,
        pattern,
        &sampling,
        vec![[0.0; KEY_POINTS]; h * w],
        start,
        |course, wale| {
            ((r0..r0 + h).contains(&course) && (c0..c0 + w).contains(&wale))
                .then(|| (course % h) * w + wale % w)
        },
        |lambdas| offsets.clone().with_relief(relief(lambdas)),
    );
    Relieved {
        relief: reached.relief.map(|b| relief(&b)),
        clearance: reached.clearance,
        crosses_right: reached.crosses_right,
    }
}

/// Finds corrections for one piece near the wales it knits straight (`offsets.straight`,
/// whose mask has one entry per wale of the piece; [`EdgeRelief`]), knitted with stitches
/// `width x height` yarn diameters, spline `tension` and rows of leaning loops `per_lean`, on
/// top of `offsets` (in diameters, with both reliefs). On a flat strip of the piece one
/// repeat of rows tall,
/// the wales within [`EDGE_WALES`] of a wale knitted straight are relieved as a pattern's
/// middle repeat is ([`relieve`]), starting from the corrections they have, with
/// [`MARGIN_WALES`] more round them standing still. `None` where the piece knits no wale
/// straight, or where the strip clears [`TARGET`] with every crossing the right way round
/// already, or nothing improved on it.
pub fn relieve_edges(
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    (width, height): (f32, f32),
    tension: f32,
    per_lean: f32,
) -> Option<EdgeRelief> {
    let straight = offsets.straight.as_ref()?;
    let wales = straight.wales.len();
    if !straight.wales.contains(&true) {
        return None;
    }
    let near = |reach: usize| -> Vec<bool> {
        (0..wales)
            .map(|x| {
                (x.saturating_sub(reach)..=(x + reach).min(wales - 1)).any(|y| straight.wales[y])
            })
            .collect()
    };
    let (lean, margin) = reach(pattern);
    let free = near(EDGE_WALES.max(lean));
    // Every loop a relieved loop crosses or is gathered with stands on the strip too, with
    // the margin round it: relieved against half a cable, a loop next to the wales knitted
    // straight was moved onto the depth of a loop of the other half it crosses on the fabric
    // (a 4/4 cable on a sheet of 24 stitches: 0.05 diameters apart, 0.30 without the edge
    // relief).
    let mut grouped = free.clone();
    for x in (0..wales).filter(|&x| free[x]) {
        for r in 0..pattern.height() {
            let (lo, hi) = pattern.landing_group(r, x);
            let (from, to) = (x as isize + lo, x as isize + hi);
            for y in from.max(0)..=to.min(wales as isize - 1) {
                grouped[y as usize] = true;
            }
        }
    }
    let built: Vec<bool> = (0..wales)
        .map(|x| (x.saturating_sub(margin)..=(x + margin).min(wales - 1)).any(|y| grouped[y]))
        .collect();
    let patch = Patch::strip(pattern, width, height, per_lean, &built);
    let sampling = SplineSampling {
        samples_per_loop: SAMPLES,
        tension,
        aspect: height / width,
    };
    let rows = pattern.height();
    let mut first_cell = vec![NO_CELL; wales];
    let mut start = Vec::new();
    for (x, _) in free.iter().enumerate().filter(|(_, f)| **f) {
        first_cell[x] = start.len() as u32;
        for r in 0..rows {
            let whole = super::stitch_shape::group_on_fabric(&patch.lattice, pattern, r, x);
            let (_, relief) = offsets.for_stitch(r, x, whole);
            start.push(relief.unwrap_or([0.0; KEY_POINTS]));
        }
    }
    let edge = |lambdas: &[[f32; KEY_POINTS]]| EdgeRelief {
        rows,
        first_cell: first_cell.clone(),
        lambdas: lambdas.to_vec(),
    };
    let before = {
        let lines = patch.centrelines(
            pattern,
            &offsets.clone().with_edge_relief(edge(&start)),
            &sampling,
        );
        (
            min_clearance(&lines),
            all_right(&patch.crossings(pattern, &lines)),
        )
    };
    if before.0 >= TARGET && before.1 {
        return None;
    }
    let r0 = patch.middle.0;
    let reached = relax(
        &patch,
        pattern,
        &sampling,
        start,
        before,
        |course, wale| {
            let first = *first_cell.get(wale)?;
            ((r0..r0 + rows).contains(&course) && first != NO_CELL)
                .then(|| first as usize + course % rows)
        },
        |lambdas| offsets.clone().with_edge_relief(edge(lambdas)),
    );
    reached.relief.map(|b| edge(&b))
}

/// The minimum clearance of `lines`, in diameters (unit yarn diameter).
fn min_clearance(lines: &[Vec<Vec3>]) -> f32 {
    clearance(
        &polylines(lines),
        1.0,
        DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
        3.0,
    )
    .min
}

/// Pushes yarns on `patch` apart (see the module documentation): the corrections in
/// `start` (one per cell, in diameters), with which the patch has clearance `start.0` and
/// crosses right (`start.1`), move by the pushes on the key points that
/// `cell_of(course, wale)` maps to a cell; `offsets_with(cells)` gives offsets holding a set
/// of corrections.
///
/// Every crossing the pattern decides that is the wrong way round, or nearly, is pushed
/// towards the side its rule gives until the yarns there stand [`CROSSING_MARGIN`] apart.
/// Other close pairs are pushed apart in the order they have. The best
/// corrections found win: crossing right first, then clearance. Returns them (`None` where
/// nothing improved on the start), with the clearance they reach and whether they cross
/// right.
fn relax(
    patch: &Patch,
    pattern: &StitchPattern,
    sampling: &SplineSampling,
    start: Vec<[f32; KEY_POINTS]>,
    start_state: (f32, bool),
    cell_of: impl Fn(usize, usize) -> Option<usize>,
    offsets_with: impl Fn(&[[f32; KEY_POINTS]]) -> NormalOffsets,
) -> Relieved<Vec<[f32; KEY_POINTS]>> {
    let mut cells = start;
    // (crosses right, clearance): crossing right first.
    let better = |a: (f32, bool), b: (f32, bool)| (a.1, a.0) > (b.1, b.0);
    let mut best: ((f32, bool), Option<Vec<[f32; KEY_POINTS]>>) = (start_state, None);
    // The rounds move the yarns a little each: their close pairs are tracked, not searched
    // for afresh (the same pairs, bit for bit).
    let mut near = ClosePairCache::new(PAIR_MARGIN);
    for _ in 0..ROUNDS {
        if crate::cancel::requested() {
            break;
        }
        let current = offsets_with(&cells);
        let lines = patch.centrelines(pattern, &current, sampling);
        let yarns = polylines(&lines);
        let Some(pairs) =
            near.close_pairs(&yarns, 1.0, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS, TARGET)
        else {
            break;
        };
        let crossings = patch.crossings(pattern, &lines);
        let right = all_right(&crossings);
        // The clearance, where it is under the target (`clearance` would find the same).
        let found = pairs.iter().map(|p| p.distance).fold(TARGET, f32::min);
        if better((found, right), best.0) {
            best = ((found, right), Some(cells.clone()));
        }
        let held = crossings.iter().all(|c| separation(c) >= CROSSING_MARGIN);
        if right && held && (pairs.is_empty() || found >= TARGET) {
            break;
        }
        // Segment number -> (piece, first point), and back.
        let mut first = Vec::with_capacity(lines.len() + 1);
        first.push(0usize);
        for l in &lines {
            first.push(first.last().copied().unwrap_or(0) + l.len().saturating_sub(1));
        }
        let locate = |seg: usize| {
            let piece = first.partition_point(|&f| f <= seg) - 1;
            (piece, seg - first[piece])
        };
        let mut push = vec![[0.0f32; KEY_POINTS]; cells.len()];
        // Pushes that turn (or hold) a crossing: where a key point has one, it moves by that
        // alone, whatever the close pairs round it ask (they would hold it where it is).
        let mut turn = vec![[0.0f32; KEY_POINTS]; cells.len()];
        let add = |into: &mut Vec<[f32; KEY_POINTS]>, piece: usize, sample: usize, amount: f32| {
            let pc = &patch.pieces[piece];
            let t = pc.sample_t(sample, SAMPLES);
            let k = t.floor();
            let f = t - k;
            let kp_count = pc.stitches * KEY_POINTS;
            for (kp, weight) in [(k as usize, 1.0 - f), (k as usize + 1, f)] {
                if kp >= kp_count || weight <= 0.0 {
                    continue;
                }
                let (course, wale) = (pc.course, pc.first_wale + kp / KEY_POINTS);
                if let Some(cell) = cell_of(course, wale) {
                    into[cell][kp % KEY_POINTS] += weight * amount;
                }
            }
        };
        // The segments of each decided crossing and their neighbours: a close pair there is
        // pushed by the crossing's rule, not by the order it happens to have.
        let mut decided = std::collections::HashSet::new();
        for c in &crossings {
            let need = CROSSING_MARGIN - separation(c);
            if need <= 0.0 {
                continue;
            }
            let (sa, sb) = (first[c.a.0] + c.a.1, first[c.b.0] + c.b.1);
            for da in 0..3 {
                for db in 0..3 {
                    let (x, y) = ((sa + da).saturating_sub(1), (sb + db).saturating_sub(1));
                    decided.insert((x.min(y), x.max(y)));
                }
            }
            let side = if c.a_front { 0.5 } else { -0.5 };
            for ((piece, k, s), sign) in [(c.a, side), (c.b, -side)] {
                add(&mut turn, piece, k, (1.0 - s) * sign * need);
                add(&mut turn, piece, k + 1, s * sign * need);
            }
        }
        for p in &pairs {
            if decided.contains(&(p.a.min(p.b), p.a.max(p.b))) {
                continue;
            }
            let (pa, ka) = locate(p.a);
            let (pb, kb) = locate(p.b);
            let (la, lb) = (&lines[pa], &lines[pb]);
            let a = la[ka].lerp(la[ka + 1], p.s);
            let b = lb[kb].lerp(lb[kb + 1], p.t);
            // Flat patch: the normal is +z.
            let v = a - b;
            let along = v.x * v.x + v.y * v.y;
            let need = (TARGET * TARGET - along).max(0.0).sqrt() - v.z.abs();
            if need <= 0.0 {
                continue;
            }
            let side = if v.z >= 0.0 { 0.5 } else { -0.5 };
            for (piece, k, s, sign) in [(pa, ka, p.s, side), (pb, kb, p.t, -side)] {
                add(&mut push, piece, k, (1.0 - s) * sign * need);
                add(&mut push, piece, k + 1, s * sign * need);
            }
        }
        for ((cell, p), t) in cells.iter_mut().zip(&push).zip(&turn) {
            for ((x, d), e) in cell.iter_mut().zip(p).zip(t) {
                let d = if *e != 0.0 { *e } else { *d };
                *x = (*x + (RATE * d).clamp(-STEP, STEP)).clamp(-LIMIT, LIMIT);
            }
        }
    }
    let lines = patch.centrelines(pattern, &offsets_with(&cells), sampling);
    let last = (
        min_clearance(&lines),
        all_right(&patch.crossings(pattern, &lines)),
    );
    if better(last, best.0) {
        best = (last, Some(cells));
    }
    Relieved {
        relief: best.1,
        clearance: best.0 .0,
        crosses_right: best.0 .1,
    }
}
