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
//! Units: corrections are in yarn diameters, indexed by pattern cell (row, column) and key
//! point k0..k5.

use glam::Vec3;
use rayon::prelude::*;

use super::{sample_piece, yarn_pieces, NormalOffsets, SplineSampling, KEY_POINTS};
use crate::lattice::Lattice;
use crate::metrics::{
    clearance, close_pairs, crossing_order, YarnPolyline, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
};
use crate::pattern::StitchPattern;
use crate::surface::{PlaneSurface, Surface};

/// Clearance the relief aims for, in diameters: a little over one, so that the spacing of
/// the output's coarser sampling and gentle curvature keep it at or above the goal.
pub const TARGET: f32 = 1.02;
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
/// Stitches round the measured repeat of the patch: wider than the furthest a loop leans
/// (three columns, a 3/3 cable), and two rows above and below.
const MARGIN_WALES: usize = 4;
const MARGIN_COURSES: usize = 2;
/// Samples per loop of the patch's centrelines.
const SAMPLES: usize = 24;

/// Normal-offset corrections per pattern cell and key point, in yarn diameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactRelief {
    height: usize,
    width: usize,
    /// Row-major, `height * width` cells.
    lambdas: Vec<[f32; KEY_POINTS]>,
}

impl ContactRelief {
    /// The corrections of stitch (`course`, `wale`) of a fabric knitted with the pattern.
    pub fn at(&self, course: usize, wale: usize) -> [f32; KEY_POINTS] {
        self.lambdas[(course % self.height) * self.width + wale % self.width]
    }

    /// The largest correction, in diameters.
    pub fn largest(&self) -> f32 {
        self.lambdas
            .iter()
            .flatten()
            .fold(0.0f32, |m, x| m.max(x.abs()))
    }
}

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
        let wales = pattern.width() + 2 * MARGIN_WALES;
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
        );
        let pieces = yarn_pieces(&lattice, &vec![true; courses * wales]);
        Patch {
            plane,
            lattice,
            pieces,
            middle: (MARGIN_COURSES, MARGIN_WALES),
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
    /// Whether every crossing the pattern decides is the right way round on `lines`.
    fn crosses_right(&self, pattern: &StitchPattern, lines: &[Vec<Vec3>]) -> bool {
        let uv: Vec<Vec<Vec3>> = lines
            .iter()
            .map(|l| {
                l.iter()
                    .map(|p| Vec3::new(p.x / self.plane.width, p.y / self.plane.height, p.z))
                    .collect()
            })
            .collect();
        let order = crossing_order(&self.lattice, pattern, &self.pieces, &uv, SAMPLES);
        order.agree == order.decided
    }
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
/// `offsets` (in diameters, without relief). Returns `None` where
/// the patch already clears [`TARGET`], and the patch's minimum clearance with the relief
/// (without it, if `None`).
pub fn relieve(
    pattern: &StitchPattern,
    width: f32,
    height: f32,
    tension: f32,
    per_lean: f32,
    offsets: &NormalOffsets,
) -> (Option<ContactRelief>, f32) {
    let patch = Patch::new(pattern, width, height, per_lean);
    let sampling = SplineSampling {
        samples_per_loop: SAMPLES,
        tension,
    };
    let (h, w) = (pattern.height(), pattern.width());
    let mut relief = ContactRelief {
        height: h,
        width: w,
        lambdas: vec![[0.0; KEY_POINTS]; h * w],
    };
    let measure = |o: &NormalOffsets| {
        let lines = patch.centrelines(pattern, o, &sampling);
        clearance(
            &polylines(&lines),
            1.0,
            DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
            3.0,
        )
        .min
    };
    let start = measure(offsets);
    if start >= TARGET {
        return (None, start);
    }
    let mut best: (f32, Option<ContactRelief>) = (start, None);
    for _ in 0..ROUNDS {
        let current = offsets.clone().with_relief(relief.clone());
        let lines = patch.centrelines(pattern, &current, &sampling);
        let yarns = polylines(&lines);
        let Some(pairs) = close_pairs(&yarns, 1.0, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS, TARGET)
        else {
            break;
        };
        // The clearance, where it is under the target (`clearance` would find the same).
        let found = pairs.iter().map(|p| p.distance).fold(TARGET, f32::min);
        // A relief that turns a crossing the wrong way round is never kept.
        if found > best.0 && patch.crosses_right(pattern, &lines) {
            best = (found, Some(relief.clone()));
        }
        if pairs.is_empty() || found >= TARGET {
            break;
        }
        // Segment number -> (piece, first point).
        let mut first = Vec::with_capacity(lines.len() + 1);
        first.push(0usize);
        for l in &lines {
            first.push(first.last().copied().unwrap_or(0) + l.len().saturating_sub(1));
        }
        let locate = |seg: usize| {
            let piece = first.partition_point(|&f| f <= seg) - 1;
            (piece, seg - first[piece])
        };
        let mut push = vec![[0.0f32; KEY_POINTS]; h * w];
        let mut add = |piece: usize, sample: usize, amount: f32| {
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
                let (r0, c0) = patch.middle;
                if !(r0..r0 + h).contains(&course) || !(c0..c0 + w).contains(&wale) {
                    continue;
                }
                push[(course % h) * w + wale % w][kp % KEY_POINTS] += weight * amount;
            }
        };
        for p in &pairs {
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
                add(piece, k, (1.0 - s) * sign * need);
                add(piece, k + 1, s * sign * need);
            }
        }
        for (cell, p) in relief.lambdas.iter_mut().zip(&push) {
            for (x, d) in cell.iter_mut().zip(p) {
                *x = (*x + (RATE * d).clamp(-STEP, STEP)).clamp(-LIMIT, LIMIT);
            }
        }
    }
    let lines = patch.centrelines(
        pattern,
        &offsets.clone().with_relief(relief.clone()),
        &sampling,
    );
    let last = clearance(
        &polylines(&lines),
        1.0,
        DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
        3.0,
    )
    .min;
    if last > best.0 && patch.crosses_right(pattern, &lines) {
        best = (last, Some(relief));
    }
    (best.1, best.0)
}
