//! Accuracy measures (docs/design.md section 7). Clearance: how close the centrelines of yarn
//! segments that are not neighbours along the yarn come to each other, in yarn diameters.
//! Goal: at least 1.0 everywhere (no interpenetration), reported as the minimum and the 1st
//! percentile.
//!
//! The search is a uniform spatial hash over the segments, queried in growing shells of cells
//! around each segment until no unvisited cell can hold anything closer: O(n) for the n up to
//! a few million segments a garment has, parallel over segments with rayon. Every segment's
//! value is the exact minimum over a set of candidates fixed by the geometry alone, so the
//! result is bit for bit the same for any number of threads.

mod close_pair_cache;
mod cover;
mod holes;

pub use close_pair_cache::ClosePairCache;
pub use cover::{cover, cover_mask};
pub use holes::{holes, Holes};

use glam::Vec3;
use rayon::prelude::*;

/// Default for `clearance`'s `neighbour_arclength`, in yarn diameters.
///
/// Why 2: the tightest physical U-turn of a yarn of diameter `d` is round another yarn of the
/// same diameter; its centreline follows a half circle of radius `d` (the two radii), so its
/// legs are `2d` apart with `pi d` (about 3.1 d) of yarn between them. An exclusion of 2
/// diameters stays well below that, so the legs of the tightest real turn are still compared
/// with each other (a loop pinched tighter than its yarn is caught), while points within a
/// diameter or so along the yarn, where sampling noise of the polyline could fake a close
/// approach, are not. (The doubly critical rule of [`clearance`] already ignores pairs that
/// only get close by walking towards each other along the yarn.)
pub const DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS: f32 = 2.0;

/// One yarn centreline: a polyline of points in scene units; `closed` if it wraps (a course
/// round a tube), in which case a segment joins the last point back to the first.
pub struct YarnPolyline<'a> {
    pub points: &'a [Vec3],
    pub closed: bool,
}

/// Clearance in yarn diameters: the smallest centreline distance between segments that are
/// not neighbours along the yarn, divided by the diameter; `p01` the 1st percentile over
/// segments of each segment's nearest such distance (nearest rank: the `ceil(n / 100)`-th
/// smallest, an observed value). Distances beyond `cap` diameters are reported as `cap`.
/// `segments` is the number of segments measured. See [`clearance`] for which pairs count.
///
/// `min` and `p01` are NaN when the input cannot be measured: a NaN or infinite point, a
/// diameter or cap that is not positive and finite, or a NaN `neighbour_arclength`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clearance {
    pub min: f32,
    pub p01: f32,
    pub segments: usize,
}

/// Clearance of `yarns` (docs/design.md section 7): the summary of [`segment_clearances`].
///
/// - `diameter`: yarn diameter in scene units; distances are reported in diameters.
/// - `neighbour_arclength`: in diameters. Two segments of the same yarn are neighbours, and
///   not compared, when the arc length along the yarn between their nearest endpoints (the
///   shorter way round a closed yarn) is less than this; segments sharing an endpoint always
///   are. Segments of different yarns never are. See
///   [`DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS`]; infinity compares different yarns only.
/// - `cap`: in diameters; nearest distances beyond it are reported as `cap` (a segment with
///   nothing within `cap` diameters, or an empty input, gives `cap`). It also bounds the
///   search, so keep it small (a few diameters).
///
/// Which pairs count. Different yarns: the exact closest-point distance of every pair of
/// segments. One yarn against itself, beyond the exclusion: only *doubly critical* pairs,
/// where the line joining the two closest points is perpendicular to the yarn at both ends
/// (at a polyline vertex: where the distance does not shrink one way along the yarn while
/// growing the other). That is the self-distance of the thickness of a curve (Gonzalez and
/// Maddocks 1999; Litherland, Simon, Durumeric and Rawdon 1999), the measure of how thick a
/// tube round it can be before it touches itself. Without it, every yarn longer than the
/// exclusion would report a "clearance" of about the exclusion itself (two points of a
/// straight yarn `e` apart along it are `e` apart in space), hiding the real approaches: the
/// legs of a loop, a yarn folded back on itself. With it, a straight yarn reports the cap,
/// the legs of a U their distance, a circle its diameter.
///
/// Never panics.
pub fn clearance(
    yarns: &[YarnPolyline],
    diameter: f32,
    neighbour_arclength: f32,
    cap: f32,
) -> Clearance {
    let segments = yarns.iter().map(segment_count).sum();
    let Some(mut nearest) = segment_clearances(yarns, diameter, neighbour_arclength, cap) else {
        return Clearance {
            min: f32::NAN,
            p01: f32::NAN,
            segments,
        };
    };
    if nearest.is_empty() {
        return Clearance {
            min: cap,
            p01: cap,
            segments,
        };
    }
    let min = nearest.iter().copied().fold(cap, f32::min);
    // Nearest rank: the k-th smallest value is unique, whatever the selection algorithm.
    let rank = segments.div_ceil(100).max(1) - 1;
    let (_, p01, _) = nearest.select_nth_unstable_by(rank, f32::total_cmp);
    Clearance {
        min,
        p01: *p01,
        segments,
    }
}

/// The clearance every knit reports, `(min, p01)` in yarn diameters (docs/design.md section 7):
/// [`clearance`] of the yarn pieces `pieces` (first point, end point, closed) of `points`
/// (scene units) with yarn of `radius`, at the default neighbour exclusion and a cap of 3
/// diameters. Ranges past the end are cut to it.
pub fn yarn_clearance(points: &[Vec3], pieces: &[(usize, usize, bool)], radius: f32) -> (f32, f32) {
    let n = points.len();
    let yarns: Vec<YarnPolyline> = pieces
        .iter()
        .map(|&(a, b, closed)| YarnPolyline {
            points: &points[a.min(n)..b.clamp(a.min(n), n)],
            closed,
        })
        .collect();
    let c = clearance(
        &yarns,
        2.0 * radius,
        DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
        3.0,
    );
    (c.min, c.p01)
}

/// Each segment's clearance in diameters, capped at `cap`, in order: yarn by yarn, segment
/// `k` of a yarn joining its points `k` and `k + 1` (the last of a closed yarn joining its
/// last point to the first; a closed yarn of two points has one segment). The per-segment
/// values [`clearance`] summarises, with the same arguments and rules; for colouring yarns by
/// clearance. `None` where `clearance` reports NaN.
pub fn segment_clearances(
    yarns: &[YarnPolyline],
    diameter: f32,
    neighbour_arclength: f32,
    cap: f32,
) -> Option<Vec<f32>> {
    let Measurable { segments, radius } = measurable(yarns, diameter, neighbour_arclength, cap)?;
    if segments == 0 {
        return Some(Vec::new());
    }
    let exclusion = f64::from(neighbour_arclength.max(0.0)) * f64::from(diameter);
    let index = SegmentIndex::new(yarns, diameter, radius, exclusion);
    // Collected in segment order, whatever the thread count.
    Some(
        (0..segments)
            .into_par_iter()
            .with_min_len(256)
            .map(|i| (index.nearest(i).min(radius) / diameter).min(cap))
            .collect(),
    )
}

/// Two segments nearer each other than asked (see [`close_pairs`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosePair {
    /// The segments, `a < b`, numbered as in [`segment_clearances`].
    pub a: usize,
    pub b: usize,
    /// Where the closest points sit along `a` and `b` (0 at the first point, 1 at the next).
    pub s: f32,
    pub t: f32,
    /// Their distance, in diameters.
    pub distance: f32,
}

/// Every pair of segments nearer than `within` diameters that [`clearance`] compares (other
/// yarns; the same yarn beyond the exclusion, doubly critical pairs only), each once, in
/// order of `a` then of the spatial index (the same for any thread count). `None` where
/// `clearance` reports NaN. For pushing yarns apart where they come too close.
pub fn close_pairs(
    yarns: &[YarnPolyline],
    diameter: f32,
    neighbour_arclength: f32,
    within: f32,
) -> Option<Vec<ClosePair>> {
    let Measurable { segments, radius } = measurable(yarns, diameter, neighbour_arclength, within)?;
    if segments == 0 {
        return Some(Vec::new());
    }
    let exclusion = f64::from(neighbour_arclength.max(0.0)) * f64::from(diameter);
    let index = SegmentIndex::new(yarns, diameter, radius, exclusion);
    Some(
        (0..segments)
            .into_par_iter()
            .with_min_len(256)
            .flat_map_iter(|a| {
                let mut found = Vec::new();
                index.within(a, |b, s, t, d| {
                    if b > a {
                        found.push(ClosePair {
                            a,
                            b,
                            s,
                            t,
                            distance: d / diameter,
                        });
                    }
                });
                found
            })
            .collect(),
    )
}

/// Segment count and search radius (scene units) of a measurable input.
struct Measurable {
    segments: usize,
    radius: f32,
}

/// Checks the inputs of [`segment_clearances`] and [`close_pairs`]: `None` where they are
/// not measurable (a diameter or reach that is not positive and finite, a NaN exclusion, a
/// point that is not finite, more segments than u32 ids).
fn measurable(
    yarns: &[YarnPolyline],
    diameter: f32,
    neighbour_arclength: f32,
    reach: f32,
) -> Option<Measurable> {
    let segments: usize = yarns.iter().map(segment_count).sum();
    let positive = |x: f32| x.is_finite() && x > 0.0;
    if !positive(diameter) || !positive(reach) || neighbour_arclength.is_nan() {
        return None;
    }
    if yarns
        .iter()
        .any(|y| y.points.iter().any(|p| !p.is_finite()))
    {
        return None;
    }
    let radius = reach * diameter;
    // Segment and cell ids are u32; four billion segments would not fit in memory anyway.
    if !radius.is_finite() || u32::try_from(segments).is_err() {
        return None;
    }
    Some(Measurable { segments, radius })
}

fn segment_count(y: &YarnPolyline) -> usize {
    match (y.points.len(), y.closed) {
        (0 | 1, _) => 0,
        (n, false) => n - 1,
        // Two points closed: the same segment twice; measure it once.
        (2, true) => 1,
        (n, true) => n,
    }
}

/// Squared distance between segments `[p1, q1]` and `[p2, q2]` (exact closest points, see
/// [`closest_parameters`]).
#[inline]
pub fn segment_distance_squared(p1: Vec3, q1: Vec3, p2: Vec3, q2: Vec3) -> f32 {
    let (s, t) = closest_parameters(p1, q1, p2, q2);
    ((p1 - p2) + (q1 - p1) * s - (q2 - p2) * t).length_squared()
}

/// Closest points of segments `[p1, q1]` and `[p2, q2]`: parameters `(s, t)` in `[0, 1]` of
/// the points `p1 + s (q1 - p1)` and `p2 + t (q2 - p2)` (Ericson, *Real-Time Collision
/// Detection*, section 5.1.9), robust for parallel and zero-length segments. Callers form the
/// difference of the points as `(p1 - p2) + d1 s - d2 t` from the small vectors rather than as
/// a difference of two large positions, to keep f32 precision far from the origin.
#[inline]
pub fn closest_parameters(p1: Vec3, q1: Vec3, p2: Vec3, q2: Vec3) -> (f32, f32) {
    let d1 = q1 - p1;
    let d2 = q2 - p2;
    let r = p1 - p2;
    let a = d1.length_squared();
    let e = d2.length_squared();
    let f = d2.dot(r);
    if a <= TINY && e <= TINY {
        return (0.0, 0.0);
    }
    if a <= TINY {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(r);
    if e <= TINY {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(d2);
    let denom = a * e - b * b;
    // Parallel (denom at rounding level): any s works; take 0 and let the clamps below find
    // the closest pair.
    let s = if denom > 1e-7 * a * e {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let t = (b * s + f) / e;
    if t < 0.0 {
        ((-c / a).clamp(0.0, 1.0), 0.0)
    } else if t > 1.0 {
        (((b - c) / a).clamp(0.0, 1.0), 1.0)
    } else {
        (s, t)
    }
}

/// Below this squared length (scene units squared) a segment is a point: no direction.
const TINY: f32 = 1e-30;

/// Below this cosine between the line joining two points and the yarn's direction, stepping
/// along the yarn counts as neither nearer nor further (the distance is flat there): absorbs
/// rounding where two parallel pieces of yarn face each other, and the nearly parallel pairs
/// that `closest_parameters` resolves at an endpoint.
const FLAT_COSINE: f32 = 1e-3;

/// Whether a point of a yarn is a critical point of its distance to a fixed point `q` of the
/// same yarn, `w = c - q`, as the point walks along the yarn: the point sits at parameter
/// `s` of a segment with direction `d`, whose neighbours along the yarn have directions
/// `prev` and `next` (zero past an open yarn's ends).
///
/// Critical: the distance is flat there, or grows both ways (a local minimum), or shrinks
/// both ways (a local maximum, as for opposite points of a circle). Not critical: it shrinks
/// one way and grows the other, so the pair only gets closer by walking towards each other,
/// into the neighbour exclusion; and an open yarn's end from which the distance shrinks.
#[inline]
fn critical(w: Vec3, s: f32, d: Vec3, [prev, next]: [Vec3; 2]) -> bool {
    #[derive(PartialEq)]
    enum Slope {
        Up,
        Down,
        Flat,
        End,
    }
    let w_len = w.length();
    if w_len == 0.0 {
        return true; // touching: critical in every sense
    }
    let slope = |m: Vec3| {
        let m_len = m.length();
        if m_len * m_len <= TINY {
            return Slope::End;
        }
        let cos = w.dot(m) / (w_len * m_len);
        if cos > FLAT_COSINE {
            Slope::Up
        } else if cos < -FLAT_COSINE {
            Slope::Down
        } else {
            Slope::Flat
        }
    };
    let along = d.length_squared() > TINY;
    let forward = slope(if along && s < 1.0 { d } else { next });
    let backward = slope(if along && s > 0.0 { -d } else { -prev });
    // Flat either way, a minimum (an open end counts as rising), or a maximum.
    matches!(
        (forward, backward),
        (Slope::Flat, _)
            | (_, Slope::Flat)
            | (Slope::Up | Slope::End, Slope::Up | Slope::End)
            | (Slope::Down, Slope::Down)
    )
}

/// Where a segment sits along its yarn.
#[derive(Debug, Clone, Copy)]
struct SegmentInfo {
    yarn: u32,
    /// Position in the yarn: segment `k` joins points `k` and `k + 1` (mod n when closed).
    index: u32,
    /// Arc length (scene units) along the yarn from its first point to the segment's start
    /// and end; f64 so long yarns keep sub-diameter resolution.
    start: f64,
    end: f64,
}

#[derive(Debug, Clone, Copy)]
struct YarnInfo {
    closed: bool,
    segments: u32,
    length: f64,
}

/// Marks an empty hash slot (cell keys use 63 bits).
const EMPTY: u64 = u64::MAX;
/// Bits per axis of a cell key. Coordinates wrap modulo 2^21 cells: two far-apart cells may
/// then share a key, which only adds candidates (distances are exact), never loses one.
const KEY_BITS: u32 = 21;

/// Segments, their place along the yarns, and a spatial hash: cell -> ids of the segments
/// whose box (split into pieces no longer than a cell) overlaps it.
struct SegmentIndex {
    ends: Vec<[Vec3; 2]>,
    /// Directions of the nearest segments with length before and after each segment along
    /// its yarn (wrapping round a closed yarn; zero past an open yarn's ends).
    turns: Vec<[Vec3; 2]>,
    info: Vec<SegmentInfo>,
    yarns: Vec<YarnInfo>,
    exclusion: f64,
    /// Largest distance worth finding (cap in scene units).
    radius: f32,
    origin: Vec3,
    cell: f32,
    inv_cell: f32,
    /// Highest cell coordinate holding anything, per axis (lowest is 0): searches are
    /// clipped to it, so a thin scene (one yarn, a sheet) does not probe empty space.
    top: [i64; 3],
    /// Cell -> its range of `entries`.
    cells: CellTable,
    /// Segment ids, cell by cell, ascending within a cell.
    entries: Vec<u32>,
}

/// Where each cell's segments lie in [`SegmentIndex::entries`]. A scene of few cells for its
/// segments (a tuning patch, a swatch) gets a dense grid, indexed directly; a sparse one
/// (a large or thin scene of small cells) a hash table of the cells that hold anything. Both
/// list the same segments per cell (the hash's wrapped keys only add far-away candidates,
/// which the exact distances drop), so every query answers the same.
enum CellTable {
    /// Cells `[0, top]` per axis in x-major order: cell `c`'s entries are
    /// `starts[c]..starts[c + 1]`.
    Dense { dims: [usize; 3], starts: Vec<u32> },
    /// Open addressing over cell keys ([`key`]): `slots[h]` a key (or [`EMPTY`]),
    /// `ranges[h]` its entries.
    Hashed {
        slots: Vec<u64>,
        ranges: Vec<[u32; 2]>,
    },
}

impl CellTable {
    /// The table of `pairs` (cell in `[0, top]`, segment), listed in segment order, and the
    /// segments cell by cell (each once per cell, ascending).
    fn new(top: [i64; 3], pairs: Vec<([i64; 3], u32)>) -> (Self, Vec<u32>) {
        let dims = top.map(|t| t.max(0) as usize + 1);
        let count = dims[0].saturating_mul(dims[1]).saturating_mul(dims[2]);
        // Dense while its cells cost no more than a few words per listed segment.
        if count <= (4 * pairs.len()).max(1 << 12) {
            // A piece's cell is clamped into the grid: a lerp may round an ulp past the
            // scene's box, and listing a segment in one more cell only adds a candidate.
            let index = |c: [i64; 3]| {
                let at = |ax: usize| c[ax].clamp(0, top[ax].max(0)) as usize;
                (at(0) * dims[1] + at(1)) * dims[2] + at(2)
            };
            // A counting sort, stable: segments stay ascending within a cell, and the pieces
            // of one segment that share a cell are adjacent there.
            let mut starts = vec![0u32; count + 1];
            for &(c, _) in &pairs {
                starts[index(c) + 1] += 1;
            }
            for k in 0..count {
                starts[k + 1] += starts[k];
            }
            let mut fill = starts.clone();
            let mut placed = vec![0u32; pairs.len()];
            for &(c, s) in &pairs {
                let at = &mut fill[index(c)];
                placed[*at as usize] = s;
                *at += 1;
            }
            // Drop a segment listed twice in one cell (two of its pieces there).
            let mut entries = Vec::with_capacity(placed.len());
            let mut from = 0usize;
            for k in 0..count {
                let end = starts[k + 1] as usize;
                starts[k] = entries.len() as u32;
                for (n, &s) in placed[from..end].iter().enumerate() {
                    if n == 0 || placed[from + n - 1] != s {
                        entries.push(s);
                    }
                }
                from = end;
            }
            starts[count] = entries.len() as u32;
            return (CellTable::Dense { dims, starts }, entries);
        }
        let mut pairs: Vec<(u64, u32)> = pairs.into_iter().map(|(c, s)| (key(c), s)).collect();
        pairs.par_sort_unstable();
        pairs.dedup();
        let distinct = pairs.windows(2).filter(|w| w[0].0 != w[1].0).count() + 1;
        let capacity = (2 * distinct).next_power_of_two().max(16);
        let mut slots = vec![EMPTY; capacity];
        let mut ranges = vec![[0u32; 2]; capacity];
        let entries: Vec<u32> = pairs.iter().map(|&(_, s)| s).collect();
        let mut start = 0;
        while start < pairs.len() {
            let k = pairs[start].0;
            let mut end = start + 1;
            while end < pairs.len() && pairs[end].0 == k {
                end += 1;
            }
            let mut h = hash(k) & (capacity - 1);
            while slots[h] != EMPTY {
                h = (h + 1) & (capacity - 1);
            }
            slots[h] = k;
            ranges[h] = [start as u32, end as u32];
            start = end;
        }
        (CellTable::Hashed { slots, ranges }, entries)
    }

    /// The range of entries of cell `c` (inside `[0, top]`).
    #[inline]
    fn range(&self, c: [i64; 3]) -> [u32; 2] {
        match self {
            CellTable::Dense { dims, starts } => {
                let k = (c[0] as usize * dims[1] + c[1] as usize) * dims[2] + c[2] as usize;
                [starts[k], starts[k + 1]]
            }
            CellTable::Hashed { slots, ranges } => {
                let k = key(c);
                let mask = slots.len() - 1;
                let mut h = hash(k) & mask;
                loop {
                    match slots[h] {
                        EMPTY => return [0, 0],
                        s if s == k => return ranges[h],
                        _ => h = (h + 1) & mask,
                    }
                }
            }
        }
    }
}

impl SegmentIndex {
    fn new(yarns: &[YarnPolyline], diameter: f32, radius: f32, exclusion: f64) -> Self {
        let mut ends = Vec::new();
        let mut turns = Vec::new();
        let mut info = Vec::new();
        let mut yarn_info = Vec::with_capacity(yarns.len());
        for (y, yarn) in yarns.iter().enumerate() {
            let n = segment_count(yarn);
            let pts = yarn.points;
            let mut s = 0.0f64;
            for k in 0..n {
                let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
                let len = f64::from(a.distance(b));
                ends.push([a, b]);
                info.push(SegmentInfo {
                    yarn: y as u32,
                    index: k as u32,
                    start: s,
                    end: s + len,
                });
                s += len;
            }
            let closed = yarn.closed && n > 1;
            yarn_info.push(YarnInfo {
                closed,
                segments: n as u32,
                length: s,
            });
            turns.extend(turn_directions(&ends[ends.len() - n..], closed));
        }
        let n = ends.len();
        let (lo, hi) = ends
            .iter()
            .fold((Vec3::MAX, Vec3::MIN), |(lo, hi), [a, b]| {
                (lo.min(*a).min(*b), hi.max(*a).max(*b))
            });
        let total_length: f64 = yarn_info.iter().map(|y| y.length).sum();

        // Cell size: one diameter, where nearest distances in a knit live (touching yarns),
        // so a query usually stops after one shell of small cells. Never below a quarter of
        // the mean segment length, so splitting segments into cell-sized pieces stays O(n),
        // nor below radius / 16, so a query probes at most ~33 cells across.
        let mean_length = (total_length / n as f64) as f32;
        let mut cell = diameter.max(0.25 * mean_length).max(radius / 16.0);
        // The whole scene must fit in a sane number of cells per axis even for a tiny
        // diameter (keys wrap, but the clipping box should stay small).
        let span = (hi - lo).max_element();
        cell = cell.max(span / (1u32 << 20) as f32);
        if !(cell > 0.0 && cell.is_finite()) {
            // All points coincide (or the scene is enormous): one cell holds everything.
            cell = if span > 0.0 && span.is_finite() {
                span
            } else {
                1.0
            };
        }
        let inv_cell = 1.0 / cell;
        let cell_of = |p: Vec3| -> [i64; 3] {
            let g = ((p - lo) * inv_cell).floor();
            // NaN cannot occur (points were checked); casts saturate.
            [g.x as i64, g.y as i64, g.z as i64]
        };
        let hi_cell = cell_of(hi);

        // (cell, segment) pairs: each segment split into pieces no longer than a cell, each
        // piece's box overlapping at most 2 x 2 x 2 cells; in segment order.
        // Plain loops over chunks of segments rather than nested iterator adapters: this
        // runs for every measurement of a first knit's tuning, and the adapters cost about a
        // tenth of that search. Chunks are joined in order, so the pairs are the same list.
        const CHUNK: usize = 1024;
        let chunks: Vec<Vec<([i64; 3], u32)>> = ends
            .par_chunks(CHUNK)
            .enumerate()
            .map(|(k, chunk)| {
                let mut out = Vec::with_capacity(2 * chunk.len());
                for (n, &[a, b]) in chunk.iter().enumerate() {
                    let i = (k * CHUNK + n) as u32;
                    let pieces = ((a.distance(b) * inv_cell).ceil() as usize).clamp(1, 1 << 20);
                    for p in 0..pieces {
                        let t0 = p as f32 / pieces as f32;
                        let t1 = (p + 1) as f32 / pieces as f32;
                        // The last piece ends exactly at b (lerp may round beside it).
                        let (u, v) = (
                            a.lerp(b, t0),
                            if p + 1 == pieces { b } else { a.lerp(b, t1) },
                        );
                        let (c0, c1) = (cell_of(u.min(v)), cell_of(u.max(v)));
                        for x in c0[0]..=c1[0] {
                            for y in c0[1]..=c1[1] {
                                for z in c0[2]..=c1[2] {
                                    out.push(([x, y, z], i));
                                }
                            }
                        }
                    }
                }
                out
            })
            .collect();
        let pairs = chunks.concat();
        let (cells, entries) = CellTable::new(hi_cell, pairs);

        SegmentIndex {
            ends,
            turns,
            info,
            yarns: yarn_info,
            exclusion,
            radius,
            origin: lo,
            cell,
            inv_cell,
            top: hi_cell,
            cells,
            entries,
        }
    }

    #[inline]
    fn cell_of(&self, p: Vec3) -> [i64; 3] {
        let g = ((p - self.origin) * self.inv_cell).floor();
        [g.x as i64, g.y as i64, g.z as i64]
    }

    #[inline]
    fn lookup(&self, c: [i64; 3]) -> &[u32] {
        let [a, b] = self.cells.range(c);
        &self.entries[a as usize..b as usize]
    }

    /// How segments `i` and `j` relate along the yarns (see [`clearance`]).
    #[inline]
    fn relation(&self, i: usize, j: usize) -> Relation {
        let (a, b) = (&self.info[i], &self.info[j]);
        if a.yarn != b.yarn {
            return Relation::OtherYarn;
        }
        if self.adjacent(i, j) {
            return Relation::Neighbour; // the same segment, or sharing an endpoint
        }
        let (a, b) = if a.index <= b.index { (a, b) } else { (b, a) };
        let yarn = &self.yarns[a.yarn as usize];
        let mut gap = b.start - a.end;
        if yarn.closed {
            gap = gap.min(yarn.length - b.end + a.start);
        }
        if gap < self.exclusion {
            Relation::Neighbour
        } else {
            Relation::SameYarn
        }
    }

    /// Calls `found(j, s, t, distance)` for every segment `j` nearer segment `i` than
    /// `radius` that [`clearance`] compares with it (each once, in ascending `j`).
    fn within(&self, i: usize, mut found: impl FnMut(usize, f32, f32, f32)) {
        self.near(i, |j| {
            if let Some((s, t, d)) = self.compare(i, j) {
                found(j, s, t, d);
            }
        });
    }

    /// Calls `found(j)` for every segment `j` other than `i` and its two neighbours along the
    /// yarn whose box comes nearer segment `i`'s than `radius`, each once, in ascending `j`:
    /// every segment that could be nearer it than `radius`, whatever the yarns' arclengths.
    fn near(&self, i: usize, mut found: impl FnMut(usize)) {
        let [a, b] = self.ends[i];
        let r = Vec3::splat(self.radius);
        let (lo, hi) = (a.min(b), a.max(b));
        let (c0, c1) = (self.cell_of(lo - r), self.cell_of(hi + r));
        let r2 = self.radius * self.radius;
        let mut seen = Vec::new();
        for x in c0[0].max(0)..=c1[0].min(self.top[0]) {
            for y in c0[1].max(0)..=c1[1].min(self.top[1]) {
                for z in c0[2].max(0)..=c1[2].min(self.top[2]) {
                    seen.extend_from_slice(self.lookup([x, y, z]));
                }
            }
        }
        // A segment split over several cells is listed in each: visit it once.
        seen.sort_unstable();
        seen.dedup();
        for j in seen {
            let j = j as usize;
            let [p, q] = self.ends[j];
            let gap = (p.min(q) - hi).max(lo - p.max(q)).max(Vec3::ZERO);
            if gap.length_squared() >= r2 || self.adjacent(i, j) {
                continue;
            }
            found(j);
        }
    }

    /// Whether `i` and `j` are one segment or share an end point along a yarn: neighbours
    /// whatever the yarn's shape.
    #[inline]
    fn adjacent(&self, i: usize, j: usize) -> bool {
        let (a, b) = (&self.info[i], &self.info[j]);
        if a.yarn != b.yarn {
            return false;
        }
        let (a, b) = if a.index <= b.index { (a, b) } else { (b, a) };
        let yarn = &self.yarns[a.yarn as usize];
        b.index - a.index <= 1 || (yarn.closed && a.index == 0 && b.index == yarn.segments - 1)
    }

    /// `(s, t, distance)` of segments `i` and `j` where [`clearance`] compares them and they
    /// are nearer than `radius`: other yarns, or the same yarn beyond the exclusion and
    /// doubly critical. The one test every search here applies, so they all agree bit for bit.
    #[inline]
    fn compare(&self, i: usize, j: usize) -> Option<(f32, f32, f32)> {
        let same_yarn = match self.relation(i, j) {
            Relation::Neighbour => return None,
            Relation::OtherYarn => false,
            Relation::SameYarn => true,
        };
        let [a, b] = self.ends[i];
        let [p, q] = self.ends[j];
        let (s, t) = closest_parameters(a, b, p, q);
        let w = (a - p) + (b - a) * s - (q - p) * t;
        let d2 = w.length_squared();
        if d2 >= self.radius * self.radius {
            return None;
        }
        if same_yarn
            && !(critical(w, s, b - a, self.turns[i]) && critical(-w, t, q - p, self.turns[j]))
        {
            return None;
        }
        Some((s, t, d2.sqrt()))
    }

    /// Distance from segment `i` to the nearest segment that is not its neighbour, or
    /// `radius` if there is none that close. Visits the cells of the segment's box, then
    /// shells one cell thicker each time, until the distance from the box to the unvisited
    /// space exceeds the best distance found (or `radius`).
    fn nearest(&self, i: usize) -> f32 {
        let [a, b] = self.ends[i];
        let (lo, hi) = (a.min(b), a.max(b));
        let (c0, c1) = (self.cell_of(lo), self.cell_of(hi));
        let mut best2 = self.radius * self.radius;
        let mut previous: Option<([i64; 3], [i64; 3])> = None;
        for k in 0.. {
            let mut b0 = [0i64; 3];
            let mut b1 = [0i64; 3];
            for ax in 0..3 {
                b0[ax] = (c0[ax] - k).max(0);
                b1[ax] = (c1[ax] + k).min(self.top[ax]);
            }
            for x in b0[0]..=b1[0] {
                for y in b0[1]..=b1[1] {
                    // Cells of the previous box were visited: in its (x, y) column, only the
                    // new z layers remain.
                    let inner = previous.filter(|(p0, p1)| {
                        (p0[0]..=p1[0]).contains(&x) && (p0[1]..=p1[1]).contains(&y)
                    });
                    let mut visit = |z0: i64, z1: i64| {
                        for z in z0..=z1 {
                            for &j in self.lookup([x, y, z]) {
                                let j = j as usize;
                                let [p, q] = self.ends[j];
                                // Box-to-box distance first: cheap, and rejects most.
                                let gap = (p.min(q) - hi).max(lo - p.max(q)).max(Vec3::ZERO);
                                if gap.length_squared() >= best2 {
                                    continue;
                                }
                                let same_yarn = match self.relation(i, j) {
                                    Relation::Neighbour => continue,
                                    Relation::OtherYarn => false,
                                    Relation::SameYarn => true,
                                };
                                let (s, t) = closest_parameters(a, b, p, q);
                                let w = (a - p) + (b - a) * s - (q - p) * t;
                                let d2 = w.length_squared();
                                if d2 >= best2 {
                                    continue;
                                }
                                // One yarn against itself: only doubly critical pairs (see
                                // `clearance`).
                                if same_yarn
                                    && !(critical(w, s, b - a, self.turns[i])
                                        && critical(-w, t, q - p, self.turns[j]))
                                {
                                    continue;
                                }
                                best2 = d2;
                            }
                        }
                    };
                    match inner {
                        None => visit(b0[2], b1[2]),
                        Some((p0, p1)) => {
                            visit(b0[2], p0[2] - 1);
                            visit(p1[2] + 1, b1[2]);
                        }
                    }
                }
            }
            // Distance from the segment's box to the nearest unvisited cell (sides of the
            // box at the scene's edge have nothing beyond them).
            let mut bound = f32::INFINITY;
            for ax in 0..3 {
                if b0[ax] > 0 {
                    let wall = self.origin[ax] + b0[ax] as f32 * self.cell;
                    bound = bound.min(lo[ax] - wall);
                }
                if b1[ax] < self.top[ax] {
                    let wall = self.origin[ax] + (b1[ax] + 1) as f32 * self.cell;
                    bound = bound.min(wall - hi[ax]);
                }
            }
            // A hair of slack for the rounding of cell walls.
            let bound = bound - 1e-5 * self.cell;
            if bound == f32::INFINITY || (bound > 0.0 && best2 <= bound * bound) {
                break;
            }
            previous = Some((b0, b1));
        }
        best2.sqrt()
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Relation {
    OtherYarn,
    /// Same yarn, closer along it than the exclusion (or sharing an endpoint): not compared.
    Neighbour,
    /// Same yarn, far enough along it to be compared.
    SameYarn,
}

/// For each segment of one yarn, the directions of the nearest segments with length before
/// and after it (wrapping when `closed`, zero past the ends of an open yarn): where a closest
/// point sits on a vertex, these say which ways the yarn can move on from it.
fn turn_directions(ends: &[[Vec3; 2]], closed: bool) -> Vec<[Vec3; 2]> {
    let dirs: Vec<Vec3> = ends.iter().map(|[a, b]| *b - *a).collect();
    let real = |d: &&Vec3| d.length_squared() > TINY;
    let mut turns = vec![[Vec3::ZERO; 2]; dirs.len()];
    let mut last = if closed {
        dirs.iter().rev().find(real).copied().unwrap_or(Vec3::ZERO)
    } else {
        Vec3::ZERO
    };
    for (k, d) in dirs.iter().enumerate() {
        turns[k][0] = last;
        if real(&d) {
            last = *d;
        }
    }
    let mut last = if closed {
        dirs.iter().find(real).copied().unwrap_or(Vec3::ZERO)
    } else {
        Vec3::ZERO
    };
    for (k, d) in dirs.iter().enumerate().rev() {
        turns[k][1] = last;
        if real(&d) {
            last = *d;
        }
    }
    turns
}

/// Packs a cell's coordinates (modulo 2^21 each) into a key below `EMPTY`.
#[inline]
fn key(c: [i64; 3]) -> u64 {
    let m = (1u64 << KEY_BITS) - 1;
    (c[0] as u64 & m) | ((c[1] as u64 & m) << KEY_BITS) | ((c[2] as u64 & m) << (2 * KEY_BITS))
}

/// SplitMix64 finaliser: spreads neighbouring cells over the table.
#[inline]
fn hash(k: u64) -> usize {
    crate::rng::splitmix64(k) as usize
}
