//! Choosing the normal offsets by optimising clearance (docs/design.md section 3.3: "choose
//! lambdas by optimising the clearance metric, per stitch type and yarn thickness, not by
//! hand").
//!
//! The magnitudes of [`NormalOffsets`] and the [`LoopShape`] are tuned on a flat patch knitted
//! with the user's pattern, stitch size and yarn diameter by a deterministic compass search
//! inside `[0, 1.5 diameters]` ([`UPPER`]; one diameter where loops lean): maximising the minimum clearance (then the 1st
//! percentile) up to [`ENOUGH`], then the patch's optical cover. The inputs are
//! quantised first and the result cached per process, so the result is a pure function of
//! the quantised inputs: the same on every machine, whatever the cache held before.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use rayon::prelude::*;

use glam::{Vec2, Vec3};

use super::crossings::crossing_order;
use super::offsets::COEFFICIENTS;
use super::offsets::{Shape, DEFAULT_SHAPE, SHAPE_COEFFICIENTS};
use super::relief::ContactRelief;
use super::{
    contact, sample_piece, yarn_pieces, LoopShape, NormalOffsets, SplineSampling, KEY_POINTS,
};
use crate::lattice::Lattice;
use crate::metrics::{clearance, cover, YarnPolyline, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS};
use crate::pattern::{Form, StitchPattern};
use crate::surface::{PlaneSurface, Surface};

/// Samples per loop used while tuning (finer than the default output, so the tuned offsets
/// hold for any output sampling).
const TUNING_SAMPLES: usize = 24;
/// Minimum patch size in stitches in each direction.
const MIN_PATCH: usize = 6;
/// The clearance every stitch should keep, in diameters (the target): a relieved
/// optimum that reaches it ends the search.
const GOAL: f32 = 0.95;
/// Clearances beyond this many diameters do not matter to the search.
const CAP: f32 = 3.0;
/// The cap of the clearance the compass search scores by. Its score counts clearance only
/// up to [`ENOUGH`], so nearest distances need be resolved only a little past it: every
/// score is bit for bit the one [`CAP`] gives (a per-segment value below the cap is the
/// same nearest distance; one at the cap, however rounded, still counts as `ENOUGH`; and the
/// percentile is a nearest rank, which capping keeps). Nearest-neighbour queries then stop
/// after the shell of cells round a segment instead of searching three diameters out: the
/// search, most of a first knit's time, runs about twice as fast. Each start's optimum is
/// measured again at [`CAP`] for the clearance it reports.
const SEARCH_CAP: f32 = ENOUGH + 1.0 / 64.0;

/// Quantisation steps of the cache key (in units of the yarn diameter / tension).
const Q_RATIO: f32 = 1.0 / 64.0;
const Q_TENSION: f32 = 1.0 / 100.0;

#[derive(Debug, Clone, PartialEq, Eq, Hash)]
struct Key {
    /// The pattern tuned for: the user's, or its stand-in ([`stand_in`]).
    pattern: StitchPattern,
    /// Whether `pattern` knits exactly as the user's (false for a plain window, whose
    /// per-cell reliefs would not fit the user's cells, so none are made).
    exact: bool,
    width: i64,
    height: i64,
    tension: i64,
}

/// The result of tuning: offsets in diameters, and the clearance they reach on a flat patch.
#[derive(Debug, Clone, PartialEq)]
pub struct Tuned {
    /// Offset magnitudes as fractions of the yarn diameter.
    pub offsets: NormalOffsets,
    /// Minimum clearance on the flat patch, in diameters.
    pub clearance_min: f32,
    /// Height per column of lean of the rows where loops lean, in stitch widths
    /// ([`super::leaning_rows::ROOM_PER_LEAN`]): the one that cleared best.
    pub per_lean: f32,
    /// Whether every crossing the pattern decides is the right way round on the patch
    /// ([`super::crossings`]): a tuning that crosses right beats any that does not.
    pub crosses_right: bool,
}

/// One cell per key: a thread that asks for a key another thread is tuning waits (on the
/// cell's lock) for that result instead of tuning it again (the test suites knit the same
/// pattern on several threads at once). A tuning stopped on request ([`crate::cancel`]) is
/// not stored: the next call tunes afresh.
type Cell = Arc<Mutex<Option<Tuned>>>;

fn cache() -> &'static Mutex<HashMap<Key, Cell>> {
    static CACHE: OnceLock<Mutex<HashMap<Key, Cell>>> = OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// Stitch width and height in yarn diameters, quantised as the tuning is: the proportions
/// the offsets (and the rows of leaning loops, [`super::leaning_rows`]) are chosen for.
pub fn proportions(stitch_width: f32, stitch_height: f32, diameter: f32) -> (f32, f32) {
    let q = |x: f32| (x / diameter / Q_RATIO).round() as i64 as f32 * Q_RATIO;
    (q(stitch_width), q(stitch_height))
}

/// Tunes the normal offsets for `pattern` knitted with stitches `stitch_width x stitch_height`
/// (scene units, measured on the surface) and yarn of `diameter`. Returns offsets in scene
/// units, the flat-patch clearance in diameters and the rows of leaning loops' height per
/// column of lean ([`super::leaning_rows`]).
pub fn tuned_offsets(
    pattern: &StitchPattern,
    stitch_width: f32,
    stitch_height: f32,
    diameter: f32,
    tension: f32,
) -> (NormalOffsets, f32, f32) {
    let (key, shift) = key(pattern, stitch_width, stitch_height, diameter, tension);
    let tuned = tuned(key);
    (
        in_users_phase(tuned.offsets, shift).scaled(diameter),
        tuned.clearance_min,
        tuned.per_lean,
    )
}

/// The offsets of the wales a piece knits straight because its edge cuts a crossing or a
/// decrease there ([`super::StraightWales`]), in scene units: the pattern's tuned
/// coefficients and shapes ([`tuned_offsets`], so they meet the wales beside them as the
/// same yarn model), with the relief of the pattern straightened
/// ([`StitchPattern::straightened`]) made on top of them, where the pattern's relief is made
/// for loops that lean there. Cached like the tuning.
pub fn straight_offsets(
    pattern: &StitchPattern,
    stitch_width: f32,
    stitch_height: f32,
    diameter: f32,
    tension: f32,
) -> NormalOffsets {
    let (key, shift) = key(pattern, stitch_width, stitch_height, diameter, tension);
    in_users_phase(straight(key), shift).scaled(diameter)
}

/// [`straight_offsets`] for `key`, in diameters.
fn straight(key: Key) -> NormalOffsets {
    static CACHE: OnceLock<Mutex<HashMap<Key, NormalOffsets>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(o) = cache.lock().ok().and_then(|c| c.get(&key).cloned()) {
        return o;
    }
    let tuned = tuned(key.clone());
    let base = NormalOffsets {
        relief: None,
        ..tuned.offsets
    };
    if !key.exact {
        return base;
    }
    let relief = contact::relieve(
        &key.pattern.straightened(),
        key.width as f32 * Q_RATIO,
        key.height as f32 * Q_RATIO,
        key.tension as f32 * Q_TENSION,
        tuned.per_lean,
        &base,
    )
    .relief;
    let o = match relief {
        Some(r) => base.with_relief(r),
        None => base,
    };
    if let (false, Ok(mut c)) = (crate::cancel::requested(), cache.lock()) {
        c.insert(key, o.clone());
    }
    o
}

/// The offsets of a piece of `wales` wales across an open u whose edges cut crossings or
/// decreases (`straight_wales[w]`: wale `w` is knitted straight), in scene units: the
/// tuned offsets ([`tuned_offsets`]), the straightened pattern's relief in the wales knitted
/// straight ([`straight_offsets`]) and corrections made for this piece where the two meet
/// ([`contact::relieve_edges`]). Cached per pattern, quantised proportions and wale count.
pub fn offsets_with_straight_wales(
    pattern: &StitchPattern,
    stitch_width: f32,
    stitch_height: f32,
    diameter: f32,
    tension: f32,
    straight_wales: Vec<bool>,
) -> NormalOffsets {
    // The wales are the piece's, so the phase the pattern starts at is part of the key.
    type EdgeKey = (Key, usize, Vec<bool>);
    static CACHE: OnceLock<Mutex<HashMap<EdgeKey, NormalOffsets>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    let (key, shift) = key(pattern, stitch_width, stitch_height, diameter, tension);
    let edge_key = (key.clone(), shift, straight_wales);
    if let Some(o) = cache.lock().ok().and_then(|c| c.get(&edge_key).cloned()) {
        return o.scaled(diameter);
    }
    let tuned = tuned(key.clone());
    let offsets = in_users_phase(tuned.offsets.clone(), shift).with_straight(
        in_users_phase(straight(key.clone()), shift),
        edge_key.2.clone(),
    );
    // The stand-in, not `pattern`: the same cells when it is exact, and bounded work; in the
    // user's phase, as the piece's wales are.
    let w = key.pattern.width();
    let users = key.pattern.columns_rotated((w - shift % w) % w);
    let edge = key.exact.then(|| {
        contact::relieve_edges(
            &users,
            &offsets,
            (key.width as f32 * Q_RATIO, key.height as f32 * Q_RATIO),
            key.tension as f32 * Q_TENSION,
            tuned.per_lean,
        )
    });
    let offsets = match edge.flatten() {
        Some(e) => offsets.with_edge_relief(e),
        None => offsets,
    };
    if let (false, Ok(mut c)) = (crate::cancel::requested(), cache.lock()) {
        c.insert(edge_key, offsets.clone());
    }
    offsets.scaled(diameter)
}

/// Most cells of a repeat tuned as it is. Tuning and relief cost grows with the repeat (a 16
/// x 16 chart takes about 13 s on 2 cores, a 64 x 64 one minutes), and every preset is at
/// most 128 cells.
pub const MAX_TUNED_CELLS: usize = 256;

/// The pattern the offsets are tuned on, and whether it knits exactly as `pattern`: the
/// pattern itself up to [`MAX_TUNED_CELLS`] cells; beyond, its smallest repeat if that is
/// small enough or if any of its stitches is more than a plain knit or purl loop; else a
/// plain window of at most [`MAX_TUNED_CELLS`] cells ([`StitchPattern::plain_window`]),
/// which tunes the knit and purl offsets for the chart's mix of faces in bounded time.
///
/// Why a large repeat of cables, lace, slips or twisted stitches is tuned whole, however
/// long its first knit takes: the plain window lets every loop land straight, so its
/// offsets know nothing of a leaning loop, and a cable tuned that way knits with loops
/// pulled through the wrong side of the heads they hang from (a 4/4 cable in a 12 x 24
/// repeat: 8 of 2,815 interlock crossings the wrong way round and 0.006 diameters of
/// clearance; tuned whole, in 35 s on 2 cores, all of them right and 0.30).
fn stand_in(pattern: &StitchPattern) -> (StitchPattern, bool) {
    let cells = |p: &StitchPattern| p.width() * p.height();
    if cells(pattern) <= MAX_TUNED_CELLS {
        return (pattern.clone(), true);
    }
    let repeat = pattern.minimal_repeat();
    if cells(&repeat) <= MAX_TUNED_CELLS || !repeat.is_plain_loops() {
        return (repeat, true);
    }
    let cols = repeat.width().min(16);
    let rows = repeat.height().min(MAX_TUNED_CELLS / cols);
    (repeat.plain_window(rows, cols), false)
}

/// The column the tuning starts an exact stand-in's chart at (issue 17, bug 1): where it
/// cuts the fewest stitches reaching across to their loops, its own first column if that is
/// one of them (every preset's chart is: none is cut there), else the first that is. A chart
/// started in the middle of a cable tuned its patch with the cable cut at both sides, and
/// knitted at a third of the clearance of the same fabric charted from another column.
///
/// Not every phase of a chart is tuned alike: two phases that both cut nothing put
/// different stitches at the patch's sides, and tune a little differently (0.385 and 0.400
/// for the twisted cable rib's). A canonical phase (the least chart in cell order) would
/// tune all of them alike, but at worse clearance than the presets' own phases for most
/// cables (0.41 -> 0.24 for the C4), so a chart's own phase is kept where it cuts nothing.
fn canonical_shift(p: &StitchPattern) -> usize {
    let w = p.width();
    let cuts: Vec<usize> = (0..w).map(|s| p.cuts_at_column(s)).collect();
    let least = cuts.iter().copied().min().unwrap_or(0);
    (0..w).find(|&s| cuts[s] == least).unwrap_or(0)
}

/// Offsets tuned on the chart started `shift` columns on ([`canonical_shift`]), for the
/// chart as the user's pattern starts it: the relief's columns moved back.
fn in_users_phase(offsets: NormalOffsets, shift: usize) -> NormalOffsets {
    let relief = offsets.relief.as_ref().map(|r| {
        let w = r.width;
        Arc::new(r.columns_rotated((w - shift % w) % w))
    });
    NormalOffsets { relief, ..offsets }
}

/// The cache key (the stand-in in the phase it is tuned in, [`canonical_shift`], and the
/// stitch proportions in diameters and tension quantised), and the columns that phase is
/// shifted by from the user's.
fn key(
    pattern: &StitchPattern,
    stitch_width: f32,
    stitch_height: f32,
    diameter: f32,
    tension: f32,
) -> (Key, usize) {
    let (pattern, exact) = stand_in(pattern);
    let shift = if exact { canonical_shift(&pattern) } else { 0 };
    let pattern = pattern.columns_rotated(shift);
    let key = Key {
        pattern,
        exact,
        width: (stitch_width / diameter / Q_RATIO).round() as i64,
        height: (stitch_height / diameter / Q_RATIO).round() as i64,
        tension: (tension / Q_TENSION).round() as i64,
    };
    debug_assert_eq!(
        proportions(stitch_width, stitch_height, diameter),
        (key.width as f32 * Q_RATIO, key.height as f32 * Q_RATIO)
    );
    (key, shift)
}

/// The tuning for `key`, from the cache or tuned now (in diameters).
fn tuned(key: Key) -> Tuned {
    let run = || {
        let mut t = tune(
            &key.pattern,
            key.width as f32 * Q_RATIO,
            key.height as f32 * Q_RATIO,
            key.tension as f32 * Q_TENSION,
        );
        if !key.exact {
            t.offsets.relief = None;
        }
        t
    };
    // The map's lock is held only to find the key's cell, never while tuning.
    let cell = match cache().lock() {
        Ok(mut c) => c.entry(key.clone()).or_default().clone(),
        // A poisoned map (a panic elsewhere while it was held): tune without caching.
        Err(_) => return run(),
    };
    let Ok(mut slot) = cell.lock() else {
        return run();
    };
    if let Some(t) = slot.as_ref() {
        return t.clone();
    }
    // Another process of this build may have tuned it ([`super::tuning_store`]).
    let text = format!("{key:?}");
    if let Some(t) = super::tuning_store::load(&text).and_then(|w| Tuned::from_words(&w)) {
        *slot = Some(t.clone());
        return t;
    }
    let t = run();
    if !crate::cancel::requested() {
        *slot = Some(t.clone());
        if let Some(words) = t.to_words() {
            super::tuning_store::save(&text, &words);
        }
    }
    t
}

impl Tuned {
    /// The tuning as words for the store ([`super::tuning_store`]): every `f32` as its bits.
    /// `None` for offsets holding a piece's own wales ([`NormalOffsets::straight`]), which a
    /// tuning never holds.
    fn to_words(&self) -> Option<Vec<u32>> {
        let o = &self.offsets;
        if o.straight.is_some() {
            return None;
        }
        let mut words: Vec<u32> = Vec::new();
        words.extend(o.x.iter().map(|v| v.to_bits()));
        words.push(o.diameter.to_bits());
        words.extend(o.shape.iter().map(|v| v.to_bits()));
        words.extend(o.loop_shape.to_array().iter().map(|v| v.to_bits()));
        words.push(self.clearance_min.to_bits());
        words.push(self.per_lean.to_bits());
        words.push(u32::from(self.crosses_right));
        match &o.relief {
            None => words.push(0),
            Some(r) => {
                words.push(1);
                words.push(u32::try_from(r.height).ok()?);
                words.push(u32::try_from(r.width).ok()?);
                words.extend(r.lambdas.iter().flatten().map(|v| v.to_bits()));
            }
        }
        Some(words)
    }

    /// The tuning [`to_words`](Self::to_words) wrote, or `None` if `words` are not one.
    fn from_words(words: &[u32]) -> Option<Tuned> {
        let mut at = words.iter().copied();
        let (x, diameter, shape, loop_shape, clearance_min, per_lean) = {
            let mut float = || at.next().map(f32::from_bits);
            let x: [f32; COEFFICIENTS] = floats(&mut float)?;
            let diameter = float()?;
            let shape: [f32; SHAPE_COEFFICIENTS] = floats(&mut float)?;
            let loop_shape = LoopShape::from_array(floats(&mut float)?);
            (x, diameter, shape, loop_shape, float()?, float()?)
        };
        let crosses_right = match at.next()? {
            0 => false,
            1 => true,
            _ => return None,
        };
        let relief = match at.next()? {
            0 => None,
            1 => {
                let height = usize::try_from(at.next()?).ok()?;
                let width = usize::try_from(at.next()?).ok()?;
                let rest: Vec<f32> = at.by_ref().map(f32::from_bits).collect();
                if height * width == 0 || rest.len() != height.checked_mul(width)? * KEY_POINTS {
                    return None;
                }
                let lambdas = rest
                    .chunks_exact(KEY_POINTS)
                    .map(|c| std::array::from_fn(|i| c[i]))
                    .collect();
                Some(Arc::new(ContactRelief {
                    height,
                    width,
                    lambdas,
                }))
            }
            _ => return None,
        };
        if at.next().is_some() {
            return None;
        }
        Some(Tuned {
            offsets: NormalOffsets {
                x,
                diameter,
                shape,
                relief,
                straight: None,
                loop_shape,
            },
            clearance_min,
            per_lean,
            crosses_right,
        })
    }
}

/// The next `N` values of `next`, or `None` if it runs out.
fn floats<const N: usize>(next: &mut impl FnMut() -> Option<f32>) -> Option<[f32; N]> {
    let mut out = [0.0f32; N];
    for v in &mut out {
        *v = next()?;
    }
    Some(out)
}

/// Clearance (min, p01) in diameters of `pattern` on a flat patch with unit yarn diameter.
pub fn patch_clearance(
    pattern: &StitchPattern,
    width: f32,
    height: f32,
    tension: f32,
    per_lean: f32,
    offsets: &NormalOffsets,
) -> (f32, f32) {
    let m = patch_measure(
        pattern, width, height, tension, per_lean, offsets, false, CAP,
    );
    (m.min, m.p01)
}

/// What the search measures on its patch.
#[derive(Debug, Clone, Copy)]
struct PatchMeasure {
    /// Clearance (min, p01) in diameters.
    min: f32,
    p01: f32,
    /// The fraction of the crossings the pattern decides that are the wrong way round
    /// ([`crate::skeleton::crossings::crossing_order`]; 0 unless measured).
    wrong: f64,
    /// The optical cover of the patch's inner stitches ([`crate::metrics::cover`]): measured
    /// where the crossings are and the clearance reaches [`ENOUGH`], 0 elsewhere.
    cover: f32,
}

impl PatchMeasure {
    /// The search's score: clearance up to [`ENOUGH`], then cover; never a crossing the
    /// wrong way round (a loop whose leg top sits on the surface leaves its interlock to
    /// the spline's overshoot). Past the clearance the yarn needs, more clearance only
    /// spreads the loops apart; cover is what a viewer sees of it.
    fn score(&self) -> f32 {
        self.min.min(ENOUGH) + 0.1 * self.p01.min(ENOUGH) + COVER_WEIGHT * self.cover
            - 100.0 * self.wrong as f32
    }
}

/// Score per unit of cover, once the patch clears [`ENOUGH`]: any cover gained is worth
/// more than the 1st percentile's clearance lost beyond it.
const COVER_WEIGHT: f32 = 3.0;

/// Pixels across the patch's inner window for its cover: about a twelfth of a diameter
/// each at the default proportions.
const COVER_RESOLUTION: usize = 192;

/// Clearance (min, p01, each at most `cap` diameters) and, if `order`, the fraction of the
/// crossings the pattern decides that are the wrong way round and the cover
/// ([`PatchMeasure`]).
#[allow(clippy::too_many_arguments)]
fn patch_measure(
    pattern: &StitchPattern,
    width: f32,
    height: f32,
    tension: f32,
    per_lean: f32,
    offsets: &NormalOffsets,
    order: bool,
    cap: f32,
) -> PatchMeasure {
    let wales = pattern.width() * MIN_PATCH.div_ceil(pattern.width());
    let courses = pattern.height() * MIN_PATCH.div_ceil(pattern.height());
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
    let built = vec![true; courses * wales];
    let pieces = yarn_pieces(&lattice, &built);
    let sampling = SplineSampling {
        samples_per_loop: TUNING_SAMPLES,
        tension,
        aspect: height / width,
    };
    let lines: Vec<Vec<Vec3>> = pieces
        .iter()
        .map(|piece| {
            let n = piece.sample_count(TUNING_SAMPLES);
            let mut pts = vec![Vec3::ZERO; n];
            let mut nrm = vec![Vec3::ZERO; n];
            let mut own = vec![0u32; n];
            sample_piece(
                &plane, &lattice, pattern, offsets, &sampling, piece, &mut pts, &mut nrm, &mut own,
            );
            pts
        })
        .collect();
    let yarns: Vec<YarnPolyline> = lines
        .iter()
        .map(|p| YarnPolyline {
            points: p,
            closed: false,
        })
        .collect();
    let c = clearance(&yarns, 1.0, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS, cap);
    let wrong = if order {
        // The plane maps (u, v) to (u * width, v * height) with normal +z.
        let uv: Vec<Vec<Vec3>> = lines
            .iter()
            .map(|l| {
                l.iter()
                    .map(|p| Vec3::new(p.x / plane.width, p.y / plane.height, p.z))
                    .collect()
            })
            .collect();
        1.0 - crossing_order(&lattice, pattern, &pieces, &uv, TUNING_SAMPLES).fraction()
    } else {
        0.0
    };
    let cover = if order && c.min >= ENOUGH {
        // The stitches a stitch or more inside the patch's edges, seen square-on.
        let y0 = crate::lattice::ROW_OVERHANG * height;
        let min = Vec2::new(width, y0 + height);
        let max = Vec2::new(
            (wales - 1) as f32 * width,
            y0 + (courses - 1) as f32 * height,
        );
        let tubes: Vec<(&[Vec3], bool)> = lines.iter().map(|l| (l.as_slice(), false)).collect();
        cover(&tubes, 0.5, min, max, COVER_RESOLUTION) as f32
    } else {
        0.0
    };
    PatchMeasure {
        min: c.min,
        p01: c.p01,
        wrong,
        cover,
    }
}

/// Clearance on a relieved patch good enough to stop trying other row heights: the goal
/// and a margin for the output's coarser sampling, curved surfaces and irregularity (at
/// 0.96 the honeycomb cable stopped at a patch of 0.967 and kept 0.943 on the sphere band
/// with the add-on's default irregularity; trying on, 0.991).
const ENOUGH: f32 = 0.97;

/// Tunes at each height of leaning rows ([`super::leaning_rows::ROOM_PER_LEAN`], in order)
/// until one clears [`ENOUGH`], and keeps the best. Patterns without leaning loops are tuned
/// once.
fn tune(pattern: &StitchPattern, width: f32, height: f32, tension: f32) -> Tuned {
    let candidates = if super::leaning_rows::leans(pattern) {
        super::leaning_rows::ROOM_PER_LEAN
    } else {
        &super::leaning_rows::ROOM_PER_LEAN[..1]
    };
    // Every height is tuned at once (each is a pure function of its inputs), then chosen in
    // order as a sequential search would: the same result on any thread count.
    let tunings: Vec<Tuned> = candidates
        .par_iter()
        .map(|&per_lean| tune_at(pattern, width, height, tension, per_lean))
        .collect();
    let mut best: Option<Tuned> = None;
    for t in tunings {
        if keep_best(&mut best, t, ENOUGH) {
            break;
        }
    }
    best.unwrap_or_else(|| untuned(super::leaning_rows::ROOM_PER_LEAN[0]))
}

/// Keeps `t` in `best` if it crosses right where `best` does not, or clears more; whether
/// `best` now crosses right and clears `enough`.
fn keep_best(best: &mut Option<Tuned>, t: Tuned, enough: f32) -> bool {
    if best
        .as_ref()
        .is_none_or(|b| (t.crosses_right, t.clearance_min) > (b.crosses_right, b.clearance_min))
    {
        *best = Some(t);
    }
    best.as_ref()
        .is_some_and(|b| b.crosses_right && b.clearance_min >= enough)
}

/// Offsets of half a diameter everywhere: what a search that found nothing returns.
fn untuned(per_lean: f32) -> Tuned {
    Tuned {
        offsets: NormalOffsets {
            x: [0.5; COEFFICIENTS],
            diameter: 1.0,
            shape: DEFAULT_SHAPE,
            relief: None,
            straight: None,
            loop_shape: LoopShape::PAPER,
        },
        clearance_min: 0.0,
        per_lean,
        crosses_right: false,
    }
}

/// The search's variables: the normal-offset coefficients (diameters), then the loop shape
/// (fractions of a tile, [`LoopShape::to_array`]).
const VARIABLES: usize = COEFFICIENTS + LoopShape::FIELDS;

/// Offsets in diameters from the search's variables.
fn offsets_of(v: &[f32; VARIABLES]) -> NormalOffsets {
    NormalOffsets {
        x: std::array::from_fn(|i| v[i]),
        diameter: 1.0,
        shape: DEFAULT_SHAPE,
        relief: None,
        straight: None,
        loop_shape: LoopShape::from_array(std::array::from_fn(|i| v[COEFFICIENTS + i])),
    }
}

/// Bounds and step scale of variable `i`: the coefficients move by the step in diameters,
/// the loop shape by a fifth of it in tiles.
fn variable_bounds(i: usize, upper: f32) -> (f32, f32, f32) {
    if i < COEFFICIENTS {
        (LOWER[i], upper, 1.0)
    } else {
        let (lo, hi) = LoopShape::BOUNDS[i - COEFFICIENTS];
        (lo, hi, 0.2)
    }
}

/// Deterministic compass search over the signed coefficients in `[LOWER, upper_bound]` diameters and
/// the loop shape within [`LoopShape::BOUNDS`], started from each of a few fixed points; the
/// best result wins.
fn tune_at(pattern: &StitchPattern, width: f32, height: f32, tension: f32, per_lean: f32) -> Tuned {
    let upper = upper_bound(pattern);
    let measure = |v: &[f32; VARIABLES], cap: f32| {
        patch_measure(
            pattern,
            width,
            height,
            tension,
            per_lean,
            &offsets_of(v),
            true,
            cap,
        )
    };
    let score = |v: &[f32; VARIABLES]| measure(v, SEARCH_CAP).score();
    // Every start's optimum (searched in parallel, kept in the order of START_POINTS), best
    // first.
    let search = |start: &[f32; COEFFICIENTS]| {
        let paper = LoopShape::PAPER.to_array();
        let mut x: [f32; VARIABLES] = std::array::from_fn(|i| {
            if i < COEFFICIENTS {
                start[i]
            } else {
                paper[i - COEFFICIENTS]
            }
        });
        let mut best = score(&x);
        // Scores already measured on this search's path: a point is often tried again (the
        // step back from where the last sweep moved to is where it came from), and a score
        // is a pure function of the point, so it is looked up, not measured again (about an
        // eighth of the measurements of feather and fan's first knit).
        let mut scored: HashMap<[u32; VARIABLES], f32> = HashMap::new();
        scored.insert(x.map(f32::to_bits), best);
        let mut step = 0.25f32;
        while step >= 1.0 / 32.0 && !crate::cancel::requested() {
            let mut improved = false;
            for i in 0..VARIABLES {
                let (lo, hi, scale) = variable_bounds(i, upper);
                for dir in [1.0f32, -1.0] {
                    let mut y = x;
                    y[i] = (y[i] + dir * step * scale).clamp(lo, hi);
                    if y[i] == x[i] {
                        continue;
                    }
                    let s = *scored
                        .entry(y.map(f32::to_bits))
                        .or_insert_with(|| score(&y));
                    if s > best + 1e-6 {
                        x = y;
                        best = s;
                        improved = true;
                    }
                }
            }
            if !improved {
                step *= 0.5;
            }
        }
        // The clearance the optimum reports, to the full cap.
        let m = measure(&x, CAP);
        (best, (m.min, m.wrong == 0.0), x)
    };
    let mut found: Vec<(f32, (f32, bool), [f32; VARIABLES])> =
        START_POINTS.par_iter().map(search).collect();
    // Stable: equal scores keep the order of START_POINTS.
    found.sort_by(|a, b| b.0.total_cmp(&a.0));
    // Starts that converge to one optimum relieve alike.
    found.dedup_by(|a, b| a.2 == b.2);
    let free = shape_coefficients_used(pattern);
    // Each optimum, and its relief where it does not clear already, worked out in parallel;
    // then chosen in order as a sequential search would.
    let optima: Vec<(Tuned, Option<contact::Relieved<_>>)> = found
        .into_par_iter()
        .map(|(_, (clearance_min, crosses_right), x)| {
            let offsets = offsets_of(&x);
            let tuned = if free.is_empty() || !TUNE_SHAPE {
                Tuned {
                    offsets,
                    clearance_min,
                    per_lean,
                    crosses_right,
                }
            } else {
                tune_shape(pattern, width, height, tension, per_lean, offsets, &free)
            };
            let relieved =
                (!(tuned.crosses_right && tuned.clearance_min >= contact::TARGET)).then(|| {
                    contact::relieve(pattern, width, height, tension, per_lean, &tuned.offsets)
                });
            (tuned, relieved)
        })
        .collect();
    let mut result: Option<Tuned> = None;
    for (tuned, relieved) in optima {
        let Some(rr) = relieved else {
            // Clear already: no relief, and no other start can do better where it matters.
            if result
                .as_ref()
                .is_none_or(|r| !r.crosses_right || r.clearance_min < contact::TARGET)
            {
                result = Some(tuned);
            }
            break;
        };
        // Where one coefficient per kind of key point cannot keep the yarns apart, or turn
        // every crossing the way its stitch says, local corrections do. The best optimum
        // unrelieved is not always the one that relieves best: the next is tried while the
        // relief falls short of the goal.
        let outcome = match rr.relief {
            Some(relief) => Tuned {
                offsets: tuned.offsets.with_relief(relief),
                clearance_min: rr.clearance,
                per_lean,
                crosses_right: rr.crosses_right,
            },
            None => tuned,
        };
        if keep_best(&mut result, outcome, GOAL) {
            break;
        }
    }
    result.unwrap_or_else(|| untuned(per_lean))
}

/// The [`Shape`] coefficients that change the fabric of `pattern`.
fn shape_coefficients_used(pattern: &StitchPattern) -> Vec<usize> {
    let mut used = [false; SHAPE_COEFFICIENTS];
    for c in 0..pattern.height() {
        for w in 0..pattern.width() {
            let s = pattern.stitch(c, w);
            if s.land_layer != 0 || s.land_offset != 0 {
                for k in [
                    Shape::PushBottom,
                    Shape::PushTop,
                    Shape::PushHead,
                    Shape::SplitBottom,
                    Shape::SplitTop,
                ] {
                    used[k as usize] = true;
                }
            }
            match s.form {
                Form::Twisted => used[Shape::Twist as usize] = true,
                Form::Slip { .. } => used[Shape::Float as usize] = true,
                _ => {}
            }
        }
    }
    (0..SHAPE_COEFFICIENTS).filter(|&i| used[i]).collect()
}

/// Whether to tune the shape coefficients too. Measured on the presets: the search gained
/// under 0.02 diameters of clearance for several seconds per pattern, so the defaults stand.
const TUNE_SHAPE: bool = false;

/// Bounds of the shape coefficients, in diameters.
const SHAPE_BOUNDS: [(f32, f32); SHAPE_COEFFICIENTS] = [
    (0.0, 2.0),
    (0.0, 2.0),
    (0.0, 2.0),
    (-1.0, 1.0),
    (-1.0, 1.0),
    (-1.0, 1.0),
    (0.5, 2.5),
];

/// Compass search over the shape coefficients `free`, the knit/purl offsets held.
fn tune_shape(
    pattern: &StitchPattern,
    width: f32,
    height: f32,
    tension: f32,
    per_lean: f32,
    mut offsets: NormalOffsets,
    free: &[usize],
) -> Tuned {
    let score = |o: &NormalOffsets| {
        let m = patch_measure(pattern, width, height, tension, per_lean, o, true, CAP);
        (m.score(), (m.min, m.wrong == 0.0))
    };
    let (mut best, mut best_min) = score(&offsets);
    let mut step = 0.25f32;
    while step >= 1.0 / 16.0 && !crate::cancel::requested() {
        let mut improved = false;
        for &i in free {
            for dir in [1.0f32, -1.0] {
                let mut y = offsets.clone();
                let (lo, hi) = SHAPE_BOUNDS[i];
                y.shape[i] = (y.shape[i] + dir * step).clamp(lo, hi);
                if y.shape[i] == offsets.shape[i] {
                    continue;
                }
                let (s, m) = score(&y);
                if s > best + 1e-6 {
                    offsets = y;
                    best = s;
                    best_min = m;
                    improved = true;
                }
            }
        }
        if !improved {
            step *= 0.5;
        }
    }
    Tuned {
        offsets,
        clearance_min: best_min.0,
        per_lean,
        crosses_right: best_min.1,
    }
}

/// Lower bounds of the coefficients: every key point on the side the interlock puts it
/// (docs/design.md section 3), so the search shapes the loops but never flips one to the other
/// side of the fabric (which stacks the courses like roof shingles: the clearance it wins is
/// not the knit's). The leg bottoms (k1, k5) and the leg tops (k2, k4) pass the head below
/// and the sinker above on their stitch's side; the head (k3) and the sinker (k0) pass the
/// legs above and below on the other side. Only the extra offset of a sinker on a knit/purl
/// boundary, where the yarn goes from one side to the other, may take either sign.
const LOWER: [f32; COEFFICIENTS] = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0];

/// Upper bound of every coefficient, in diameters: the centrelines stay within one and a
/// half diameters of the surface, so the fabric is at most four diameters thick. Measured on
/// stockinette with the default yarn (a quarter of a stitch wide): with one diameter (three
/// thick) the best loops cleared 0.89 diameters and hid 84% of the fabric; with one and a
/// half they clear 1.0 and hide 89%, as the taller, rounder loops of a real knit need the
/// depth to pass each other.
const UPPER: f32 = 1.5;

/// The same for patterns whose loops lean (cables, twists, decreases): their crossing loops
/// stand half a diameter out and in ([`Shape::PushBottom`]), and with plain legs out to one
/// and a half diameters the irregularity of hand knitting turned neighbouring crossed legs
/// of twisted cable rib the wrong way round (36 of 1,425 crossings on a 24-wale patch at
/// kappa 0.005; none within one diameter).
const UPPER_LEANING: f32 = 1.0;

/// The upper bound of the coefficients for `pattern`.
fn upper_bound(pattern: &StitchPattern) -> f32 {
    if super::leaning_rows::leans(pattern) {
        UPPER_LEANING
    } else {
        UPPER
    }
}

/// Starting points of the search (coefficients in diameters, see [`NormalOffsets`]): half a
/// diameter each side, the legs further out than the head and sinker, and the reverse.
const START_POINTS: &[[f32; COEFFICIENTS]] = &[
    [0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.0],
    [0.25, 0.75, 0.75, 0.25, 0.75, 0.75, 0.0],
    [0.75, 0.25, 0.25, 0.75, 0.25, 0.25, 0.0],
];

#[cfg(test)]
mod store_tests {
    use super::*;

    fn sample(relief: bool) -> Tuned {
        Tuned {
            offsets: NormalOffsets {
                x: std::array::from_fn(|i| 0.1 * i as f32 - 0.3),
                diameter: 1.0,
                shape: std::array::from_fn(|i| 1.0 / (i as f32 + 3.0)),
                relief: relief.then(|| {
                    Arc::new(ContactRelief {
                        height: 2,
                        width: 3,
                        lambdas: (0..6)
                            .map(|c| std::array::from_fn(|k| (c * 7 + k) as f32 * 1e-3))
                            .collect(),
                    })
                }),
                straight: None,
                loop_shape: LoopShape::PAPER,
            },
            clearance_min: 0.987_654_3,
            per_lean: 0.5,
            crosses_right: true,
        }
    }

    #[test]
    fn a_tuning_reads_back_from_its_words_and_from_nothing_else() {
        for relief in [false, true] {
            let t = sample(relief);
            let words = t.to_words().unwrap();
            assert_eq!(Tuned::from_words(&words).as_ref(), Some(&t));
            for cut in 1..words.len() {
                assert_eq!(
                    Tuned::from_words(&words[..words.len() - cut]),
                    None,
                    "{cut}"
                );
            }
            let mut longer = words.clone();
            longer.push(0);
            assert_eq!(Tuned::from_words(&longer), None);
        }
    }
}
