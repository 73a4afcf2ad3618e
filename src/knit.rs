//! The whole pipeline: surface -> lattice -> skeleton -> yarn bundles -> flat buffers in the
//! dtypes Blender's `foreach_set` takes (float32 positions and colours, int32 indices).

use std::sync::Mutex;
use std::time::Instant;

use glam::Vec3;
use rayon::prelude::*;

use crate::budget::{self, OutputSize};
use crate::detail::{piece_spans, stitch_levels, DetailParams, Level, LevelSettings, Span};
use crate::error::{KnitError, Result};
use crate::geometry::{
    build_bundle, bundle_counts, piece_streams, stitch_seed, BundleCounts, BundleSettings,
    EndTangents, FullDensityDraws, MeshSubset, PieceBuffers, TopologyBuffers, VertexCorners,
};
use crate::lattice::{Lattice, ROW_OVERHANG};
use crate::metrics::{clearance, YarnPolyline, DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS};
use crate::output_buffer;
use crate::parallel::{run_in_pool, split_lengths};
use crate::pattern::{ColorPattern, StitchPattern};
use crate::skeleton::{
    built_stitches, sample_piece, sample_piece_uv, tuning, yarn_pieces, NormalOffsets,
    SplineSampling, YarnPiece,
};
use crate::surface::{Surface, UvRect};
use crate::visibility::seen_triangles;

/// Gauge used when neither counts nor a gauge are given: 20 stitches and 28 rows per 10 cm
/// (a worsted-weight yarn on 4.5 mm needles; [`crate::settings::GAUGE_STITCHES`]).
pub const DEFAULT_GAUGE: (f32, f32) = (
    crate::settings::GAUGE_STITCHES.default_f32(),
    crate::settings::GAUGE_ROWS.default_f32(),
);
/// Default yarn radius as a fraction of the stitch width: a diameter of a fifth of a stitch
/// (thinner yarn looks sparse; this is where the tuned offsets clear best).
pub const DEFAULT_RADIUS_PER_STITCH_WIDTH: f32 = 0.1;
/// Samples a loop at which [`PreparedKnit::crossing_order`] measures the skeleton's topology
/// (at least): the tuning's and the contact relief's.
pub const TOPOLOGY_SAMPLES: usize = 24;
/// Default yarn colour (linear RGB): a warm oatmeal wool.
pub const DEFAULT_YARN_COLOR: [f32; 3] = [0.55, 0.42, 0.30];
pub use crate::gauge::MAX_STITCHES_PER_DIRECTION;
/// Re-exported: a knit's `color_image` setting.
pub use crate::pattern::ColorImage;

/// Every setting of a knit. Lengths in scene units.
#[derive(Debug, Clone)]
pub struct KnitParams {
    /// Rows of stitches (along v). `None`: from the gauge.
    pub courses: Option<usize>,
    /// Columns of stitches (along u). `None`: from the gauge.
    pub wales: Option<usize>,
    /// Stitches and rows per 10 cm (0.1 scene units), measured on the surface. Used for the
    /// counts not given. Default: [`DEFAULT_GAUGE`].
    pub gauge: Option<(f32, f32)>,
    /// Yarn radius. Default: [`DEFAULT_RADIUS_PER_STITCH_WIDTH`] of the mean stitch width
    /// measured on the surface, or of `stitch_size`'s width where that is given (the gauge's
    /// width where a count in the round was rounded to whole pattern repeats).
    pub yarn_radius: Option<f32>,
    /// Stitch width and height (scene units) that the normal offsets (and the rows of leaning
    /// loops) are tuned for. Default: measured on the surface, the tighter stitches' size
    /// ([`crate::tight_stitches`]: the mean stitch where all are alike). An animated knit pins
    /// the values measured at its rest pose, so a stretched frame moves the yarn but never
    /// re-tunes it (which would change every loop's shape from one frame to the next).
    pub stitch_size: Option<(f32, f32)>,
    /// Apex push as a fraction of the radius, 0..=4. Default: 0.5.
    pub fluffiness: f32,
    /// Points per yarn ring, 3..=64. Default: 6.
    pub ring_segments: usize,
    /// Centreline samples per stitch, 6..=256. Default: 16.
    pub samples_per_loop: usize,
    /// Cardinal spline tension, 0..1 (0: Catmull-Rom). Default: 0.
    pub tension: f32,
    /// Irregularity of stitch positions: the recursive perturbation's kappa (seed 000,
    /// section 2.4), 0 (a regular lattice) to [`crate::lattice::KAPPA_MAX`]. Default: 0.
    pub kappa: f32,
    pub seed: u64,
    /// Colours per stitch from a palette chart. Default: one yarn colour.
    pub colors: Option<ColorPattern>,
    /// Colours per stitch from an image (wins over `colors`).
    pub color_image: Option<ColorImage>,
    /// Random brightness variation of vertex colours, 0..=1. Default: 0.15.
    pub color_variation: f32,
    /// Threads of the private pool. Default: all cores.
    pub threads: Option<usize>,
    /// Refuse outputs larger than this many bytes. Default: [`budget::DEFAULT_BUDGET_BYTES`].
    pub budget_bytes: u64,
    /// Also measure the clearance of the result (costs about as much as the knit itself).
    pub measure_clearance: bool,
    /// Camera-driven level of detail and culling ([`crate::detail`]). Default: `None`, every
    /// stitch at full quality.
    pub detail: Option<DetailParams>,
}

impl Default for KnitParams {
    /// The defaults of [`crate::settings`].
    fn default() -> Self {
        use crate::settings as s;
        Self {
            courses: None,
            wales: None,
            gauge: None,
            yarn_radius: None,
            stitch_size: None,
            fluffiness: s::FLUFFINESS.default_f32(),
            ring_segments: s::RING_SEGMENTS.default_usize(),
            samples_per_loop: s::SAMPLES_PER_LOOP.default_usize(),
            tension: s::TENSION.default_f32(),
            kappa: s::KAPPA.default_f32(),
            seed: 0,
            colors: None,
            color_image: None,
            color_variation: s::COLOR_VARIATION.default_f32(),
            threads: None,
            budget_bytes: budget::DEFAULT_BUDGET_BYTES,
            measure_clearance: false,
            detail: None,
        }
    }
}

/// Figures about a knit.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct KnitStats {
    pub courses: usize,
    pub wales: usize,
    /// Stitches built.
    pub stitches: usize,
    /// Stitches not built because part of them had no surface (outside every UV island).
    pub stitches_skipped: usize,
    /// Built stitches whose normal offsets were clamped because the surface curves more
    /// tightly there than the offsets reach (a thin tube, a sharp crease; see
    /// [`crate::skeleton::curvature`]). Counted per build (the pose decides it), so 0 in
    /// [`PreparedKnit::stats`].
    pub stitches_clamped: usize,
    pub vertices: usize,
    pub triangles: usize,
    pub yarn_pieces: usize,
    /// Stitch width and height measured on the surface (scene units).
    pub stitch_width: f32,
    pub stitch_height: f32,
    /// Clearance of the tuned offsets on a flat patch, in yarn diameters.
    pub flat_clearance: f32,
    /// Clearance of this result (min, 1st percentile) in diameters, if measured.
    pub clearance: Option<(f32, f32)>,
    /// The interlock of this result, if measured (with the clearance): crossings between a
    /// course and the loops it is pulled through, and how many of them have the yarn the
    /// pattern says in front ([`crate::skeleton::crossings`]). Equal numbers: every course
    /// interlocks with the one below, stitch by stitch.
    pub interlock: Option<(usize, usize)>,
    /// Seconds spent in the core.
    pub seconds: f64,
    /// A key of the mesh topology (triangles, edges, their order): equal keys mean identical
    /// `triangles`, `edges` and `corner_edges` buffers, so a consumer holding a mesh with this
    /// key need only rewrite positions and colours. It depends on the yarn pieces' lengths,
    /// whether they are closed, and the ring segments; never on positions or random choices
    /// (each triangle owns its apex vertex, so the random apex picks move vertices only).
    pub topology_key: u64,
    /// Stitches at each [`Level`] (full, mid, far, texture, culled), of the `stitches` that
    /// have a surface. Without camera-driven detail all are full.
    pub levels: [usize; 5],
    /// Triangles the same knit has with every stitch at full quality (equal to `triangles`
    /// without camera-driven detail).
    pub triangles_full_detail: usize,
    /// Triangles culled as hidden behind other yarn from every view (`cull_hidden`; 0
    /// without). `triangles` are those left.
    pub triangles_hidden: usize,
}

/// A knit, in flat buffers.
#[derive(Debug, Clone, Default)]
pub struct KnitOutput {
    /// `(V, 3)` vertex positions, scene units, the surface's object space.
    pub positions: Vec<f32>,
    /// `(V, 4)` linear RGBA.
    pub colors: Vec<f32>,
    /// `(T, 3)` vertex indices.
    pub triangles: Vec<i32>,
    /// `(3T,)` edge from corner k to corner k+1 of each triangle.
    pub corner_edges: Vec<i32>,
    /// `(E, 2)` vertex indices.
    pub edges: Vec<i32>,
    /// `(P, 3)` yarn centreline samples.
    pub centerline: Vec<f32>,
    /// `(Y + 1,)`: yarn piece `i` is samples `offsets[i]..offsets[i + 1]`.
    pub yarn_offsets: Vec<i64>,
    /// `(Y,)` the course of each yarn piece.
    pub yarn_course: Vec<i32>,
    /// `(Y,)` whether each yarn piece is closed (a whole course round a cyclic-u surface).
    pub yarn_closed: Vec<bool>,
    /// `(V, 3)` unit vertex normals of the knit with its hidden yarn culled: the whole
    /// knit's smooth normals (Blender's: angle-weighted face normals), which the culled
    /// mesh's own triangles no longer give. Empty without `cull_hidden`.
    pub normals: Vec<f32>,
    pub yarn_radius: f32,
    pub stats: KnitStats,
}

fn validate(p: &KnitParams) -> Result<()> {
    use crate::settings as s;
    s::FLUFFINESS.check(p.fluffiness)?;
    s::RING_SEGMENTS.check_count(p.ring_segments)?;
    s::SAMPLES_PER_LOOP.check_count(p.samples_per_loop)?;
    s::TENSION.check(p.tension)?;
    s::COLOR_VARIATION.check(p.color_variation)?;
    s::KAPPA.check(p.kappa)?;
    if let Some(d) = &p.detail {
        d.validate()?;
    }
    for (setting, n) in [(s::COURSES, p.courses), (s::WALES, p.wales)] {
        if let Some(n) = n {
            setting.check_count(n)?;
        }
    }
    if let Some((stitches, rows)) = p.gauge {
        s::GAUGE_STITCHES.check(stitches)?;
        s::GAUGE_ROWS.check(rows)?;
    }
    if let Some((w, h)) = p.stitch_size {
        if !(w.is_finite() && h.is_finite() && w > 0.0 && h > 0.0) {
            return Err(KnitError::Parameter(format!(
                "stitch size must be a positive width and height, not ({w}, {h})"
            )));
        }
    }
    if let Some(r) = p.yarn_radius {
        if !(r.is_finite() && r > 0.0) {
            return Err(KnitError::Parameter(format!(
                "yarn_radius must be positive (or None: a tenth of the stitch width), not {r}"
            )));
        }
    }
    Ok(())
}

/// Stitch counts from explicit counts or the gauge and the surface's extent. Along a cyclic
/// direction a count from the gauge is rounded to whole repeats of the pattern (and of the
/// colour chart, where a whole number of both fits), as a knitter casts on in the round;
/// counts given explicitly are kept as given. Also returns how much wider a stitch is for the
/// rounding (the gauge's count over the rounded one), which the default yarn does not follow:
/// the gauge fixes the yarn, and rounding only stretches or gathers the stitches round.
fn stitch_counts(
    surface: &dyn Surface,
    pattern: &StitchPattern,
    p: &KnitParams,
) -> Result<(usize, usize, f32)> {
    let gauge = p.gauge.unwrap_or(DEFAULT_GAUGE);
    let (courses, wales) =
        crate::gauge::stitch_counts(surface.extent(), gauge, p.courses, p.wales)?;
    let colors = p.colors.as_ref().filter(|_| p.color_image.is_none());
    let repeat = |stitch: usize, color: Option<usize>, count: usize| {
        let both = color.map_or(stitch, |c| crate::pattern::lcm(stitch, c));
        if both <= count {
            both
        } else {
            stitch
        }
    };
    let gauge_wales = wales;
    let rounded = if surface.cyclic_u() && p.wales.is_none() {
        let r = repeat(pattern.width(), colors.map(ColorPattern::width), wales);
        crate::gauge::whole_repeats(wales, r)
    } else {
        wales
    };
    let courses = if surface.cyclic_v() && p.courses.is_none() {
        let r = repeat(pattern.height(), colors.map(ColorPattern::height), courses);
        crate::gauge::whole_repeats(courses, r)
    } else {
        courses
    };
    Ok((courses, rounded, gauge_wales as f32 / rounded.max(1) as f32))
}

/// Knits `pattern` over `surface`: [`PreparedKnit::new`] then [`PreparedKnit::build`].
pub fn knit(surface: &dyn Surface, pattern: &StitchPattern, p: &KnitParams) -> Result<KnitOutput> {
    let start = Instant::now();
    let prepared = PreparedKnit::new(surface, pattern, p)?;
    let mut out = prepared.build(surface)?;
    out.stats.seconds = start.elapsed().as_secs_f64();
    Ok(out)
}

/// A knit bound to a surface layout: everything that does not depend on where the surface
/// is in space, fixed once (stitch counts, yarn radius, stitch size and the tuned offsets,
/// lattice, which stitches are built, yarn pieces, buffer layout).
///
/// [`build`](Self::build) makes the whole output for a surface of that layout (the same
/// surface, or the same surface deformed: moved by an armature, a shape key, a modifier);
/// [`positions_into`](Self::positions_into) makes only the vertex positions, into a buffer
/// the caller keeps. Both run the same code, consume the same per-stitch random streams and
/// so give bit-identical positions, and the topology of every build is the same: this is
/// what lets a knit follow an animated surface without flicker, and lets a farm render frame
/// N alone and get what a whole sequence gets.
#[derive(Debug, Clone)]
pub struct PreparedKnit {
    params: KnitParams,
    pattern: StitchPattern,
    lattice: Lattice,
    pieces: Vec<YarnPiece>,
    offsets: NormalOffsets,
    sampling: SplineSampling,
    /// Centreline samples per piece (full density).
    samples: Vec<usize>,
    /// First sample of each piece in the concatenated centrelines.
    piece_start: Vec<usize>,
    /// The bundles built: one per piece without camera-driven detail, one per run of
    /// stitches of one level with it.
    spans: Vec<Span>,
    /// Bundle settings of the full, mid and far levels.
    level_bundle: [BundleSettings; 3],
    /// Element counts per span.
    counts: Vec<BundleCounts>,
    /// Level of every stitch (row-major), with camera-driven detail.
    levels: Option<Vec<Level>>,
    total: OutputSize,
    /// The (u,v) layout the knit was prepared for.
    domain: UvRect,
    cyclic: (bool, bool),
    /// Everything but the per-build figures.
    stats: KnitStats,
    radius: f32,
    /// With `cull_hidden`: the triangles kept, of the whole mesh the spans make.
    hidden: Option<HiddenCulled>,
    /// The whole build `cull_hidden` made from the views, kept for the first
    /// [`build`](Self::build) of the same surface.
    first_build: FirstBuild,
}

/// The seen triangles of a knit that culls its hidden yarn.
#[derive(Debug, Clone)]
struct HiddenCulled {
    subset: MeshSubset,
    /// The whole mesh's corners at each kept vertex, for its smooth normal.
    corners: VertexCorners,
    /// The whole mesh's triangles (its topology never changes).
    whole_triangles: Vec<i32>,
    /// One bit per triangle of the whole mesh (see [`DetailParams::pinned_seen`]).
    seen: Vec<u8>,
}

/// A whole build and the centrelines it was swept along (cloning a knit does not clone it).
#[derive(Default)]
struct FirstBuild(Mutex<Option<(Centrelines, KnitOutput)>>);

impl Clone for FirstBuild {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl std::fmt::Debug for FirstBuild {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("FirstBuild")
    }
}

impl FirstBuild {
    /// The kept build, if it was swept along exactly `c` (bit for bit: then it is what a new
    /// sweep would make).
    fn take_if_same(&self, c: &Centrelines) -> Option<KnitOutput> {
        let mut slot = self.0.lock().ok()?;
        let same = slot.as_ref().is_some_and(|(kept, _)| kept.same_as(c));
        if same {
            slot.take().map(|(_, out)| out)
        } else {
            None
        }
    }
}

/// Packs one flag per triangle into bits, triangle `i` at bit `i % 8` of byte `i / 8`.
fn pack_bits(flags: &[bool]) -> Vec<u8> {
    flags
        .chunks(8)
        .map(|c| {
            c.iter()
                .enumerate()
                .fold(0u8, |b, (i, &f)| b | (u8::from(f) << i))
        })
        .collect()
}

fn unpack_bits(bits: &[u8], n: usize) -> Result<Vec<bool>> {
    if bits.len() != n.div_ceil(8) {
        return Err(KnitError::Parameter(format!(
            "the pinned seen triangles are {} bytes; this knit has {n} triangles before \
             culling ({} bytes): they are from another knit",
            bits.len(),
            n.div_ceil(8)
        )));
    }
    Ok((0..n).map(|i| bits[i / 8] >> (i % 8) & 1 == 1).collect())
}

impl PreparedKnit {
    /// Validates the settings, fixes counts, radius and offsets from `surface`, lays out the
    /// lattice and checks the output against the budget (before anything large is allocated).
    pub fn new(surface: &dyn Surface, pattern: &StitchPattern, p: &KnitParams) -> Result<Self> {
        validate(p)?;
        let (len_u, len_v) = surface.extent();
        if !(len_u.is_finite() && len_v.is_finite() && len_u > 0.0 && len_v > 0.0) {
            return Err(KnitError::Surface(format!(
                "the surface has no extent to knit over (lengths {len_u} x {len_v} along u \
                 and v)"
            )));
        }
        let (courses, wales, widened) = stitch_counts(surface, pattern, p)?;
        let m = p.ring_segments;
        let s = p.samples_per_loop;
        let stitches = courses as u64 * wales as u64;
        budget::check(
            &OutputSize::upper_bound(stitches, (s * densest(pattern)) as u64, m as u64),
            p.budget_bytes,
            stitches,
        )?;

        let cyclic_v = surface.cyclic_v();
        let domain = surface.domain();
        let cyclic = (surface.cyclic_u(), cyclic_v);
        let base = Lattice::perturbed(domain, courses, wales, cyclic.0, cyclic.1, p.kappa, p.seed)?;
        // The mean stitch, which the default yarn follows.
        let mean = (
            len_u / wales as f32,
            if cyclic_v {
                len_v / courses as f32
            } else {
                len_v / (courses as f32 + 2.0 * ROW_OVERHANG)
            },
        );
        let (stitch_width, stitch_height) = match p.stitch_size {
            Some(size) => size,
            None => {
                let (rw, rh) = run_in_pool(p.threads, || {
                    crate::tight_stitches::tight_ratios(surface, &base)
                })?;
                (mean.0 * rw, mean.1 * rh)
            }
        };
        let yarn_width = p.stitch_size.map_or(mean.0, |s| s.0);
        let radius = p
            .yarn_radius
            .unwrap_or(DEFAULT_RADIUS_PER_STITCH_WIDTH * yarn_width / widened);
        let (check_w, check_h) = p.stitch_size.unwrap_or(mean);
        if 2.0 * radius > check_w.min(2.0 * check_h) {
            return Err(KnitError::Parameter(format!(
                "the yarn ({:.4} thick) is thicker than a stitch ({check_w:.4} x \
                 {check_h:.4}): use a thinner yarn or fewer stitches",
                2.0 * radius
            )));
        }
        let (offsets, flat_clearance, per_lean) = tuning::tuned_offsets(
            pattern,
            stitch_width,
            stitch_height,
            2.0 * radius,
            p.tension,
        );

        // Wales whose edge cuts a crossing or a decrease are knitted straight, with a relief
        // made for the pattern straightened.
        let straight_wales: Vec<bool> = if pattern.has_crossings() {
            (0..base.wales)
                .map(|w| !crate::skeleton::stitch_shape::wale_knits_whole(&base, pattern, w))
                .collect()
        } else {
            Vec::new()
        };
        let offsets = if !straight_wales.contains(&true) {
            offsets
        } else if base.cyclic_u {
            // Round a seam (explicit counts that are not whole repeats): no edge corrections,
            // which a flat strip cannot make across the seam.
            let straight = tuning::straight_offsets(
                pattern,
                stitch_width,
                stitch_height,
                2.0 * radius,
                p.tension,
            );
            offsets.with_straight(straight, straight_wales)
        } else {
            tuning::offsets_with_straight_wales(
                pattern,
                stitch_width,
                stitch_height,
                2.0 * radius,
                p.tension,
                straight_wales,
            )
        };
        let (width_d, height_d) = tuning::proportions(stitch_width, stitch_height, 2.0 * radius);
        let lattice =
            crate::skeleton::leaning_rows::shaped(base, pattern, width_d, height_d, per_lean);
        let sampling = SplineSampling {
            samples_per_loop: s,
            tension: p.tension,
        };
        let bundle = BundleSettings {
            radius,
            ring_segments: m,
            fluffiness: p.fluffiness,
            color_variation: p.color_variation,
            seed: p.seed,
        };
        // Full-detail pieces first: their triangles are the figure detail is measured against.
        let (full_pieces, built, built_count) = run_in_pool(p.threads, || {
            let built = built_stitches(surface, &lattice);
            let count = built.iter().filter(|b| **b).count();
            (
                with_extras(
                    course_pieces(&lattice, &built, pattern),
                    &lattice,
                    &built,
                    pattern,
                    p,
                ),
                built,
                count,
            )
        })?;
        let triangles_full_detail: usize = full_pieces
            .iter()
            .map(|pc| bundle_counts(pc.sample_count(s), m, pc.closed).triangles)
            .sum();
        let full = LevelSettings {
            samples_per_loop: s,
            ring_segments: m,
            fluffiness: p.fluffiness,
        };
        let (pieces, levels, spans) = match &p.detail {
            None => {
                let spans = full_pieces
                    .iter()
                    .enumerate()
                    .map(|(i, pc)| whole_piece_span(i, pc, s))
                    .collect();
                (full_pieces, None, spans)
            }
            Some(d) => run_in_pool(p.threads, || -> Result<_> {
                // The yarn stands off the surface by its offsets (at most about a diameter)
                // plus its radius and fluff.
                let reach = radius * (3.0 + p.fluffiness);
                let levels = stitch_levels(surface, &lattice, &built, d, reach)?;
                let kept: Vec<bool> = levels.iter().map(|l| l.is_built()).collect();
                let pieces = with_extras(
                    course_pieces(&lattice, &kept, pattern),
                    &lattice,
                    &kept,
                    pattern,
                    p,
                );
                let spl = |level: Level| d.level_settings(level, full).samples_per_loop;
                let spans: Vec<Span> = pieces
                    .par_iter()
                    .enumerate()
                    .map(|(i, pc)| {
                        let runs = level_runs(
                            surface, &lattice, pattern, &offsets, &sampling, pc, &levels, s,
                        );
                        piece_spans(i, pc.sample_count(s), pc.closed, &runs, s, spl)
                    })
                    .flatten()
                    .collect();
                Ok((pieces, Some(levels), spans))
            })??,
        };
        let samples: Vec<usize> = pieces.iter().map(|pc| pc.sample_count(s)).collect();
        let piece_start: Vec<usize> = samples
            .iter()
            .scan(0usize, |acc, &n| {
                *acc += n;
                Some(*acc - n)
            })
            .collect();
        let level_bundle = [Level::Full, Level::Mid, Level::Far].map(|level| {
            let q = p
                .detail
                .as_ref()
                .map_or(full, |d| d.level_settings(level, full));
            BundleSettings {
                ring_segments: q.ring_segments,
                fluffiness: q.fluffiness,
                ..bundle
            }
        });
        let counts: Vec<BundleCounts> = spans
            .iter()
            .map(|sp| {
                bundle_counts(
                    sp.rings,
                    level_bundle[sp.level as usize].ring_segments,
                    sp.closed,
                )
            })
            .collect();
        let total = OutputSize {
            vertices: counts.iter().map(|c| c.vertices as u64).sum(),
            triangles: counts.iter().map(|c| c.triangles as u64).sum(),
            edges: counts.iter().map(|c| c.edges as u64).sum(),
            samples: samples.iter().map(|&n| n as u64).sum(),
        };
        let built_yarn: u64 = pieces.iter().map(|pc| pc.stitches as u64).sum();
        budget::check(&total, p.budget_bytes, built_yarn)?;

        let mut level_counts = [0usize; 5];
        match &levels {
            None => level_counts[0] = built_count,
            Some(levels) => {
                for (l, b) in levels.iter().zip(&built) {
                    level_counts[*l as usize] += usize::from(*b);
                }
            }
        }
        let topology_key = match &levels {
            None => topology_key(m, &pieces, &samples),
            Some(_) => detail_topology_key(&spans, &level_bundle),
        };
        let stats = KnitStats {
            courses,
            wales,
            stitches: built_count,
            stitches_skipped: courses * wales - built_count,
            vertices: total.vertices as usize,
            triangles: total.triangles as usize,
            yarn_pieces: pieces.len(),
            stitch_width,
            stitch_height,
            flat_clearance,
            topology_key,
            levels: level_counts,
            triangles_full_detail,
            ..Default::default()
        };
        let mut prepared = Self {
            params: p.clone(),
            pattern: pattern.clone(),
            lattice,
            pieces,
            offsets,
            sampling,
            samples,
            piece_start,
            spans,
            level_bundle,
            counts,
            levels,
            total,
            domain,
            cyclic,
            stats,
            radius,
            hidden: None,
            first_build: FirstBuild::default(),
        };
        if let Some(d) = p.detail.as_ref().filter(|d| d.cull_hidden) {
            prepared.cull_hidden(surface, d)?;
        }
        Ok(prepared)
    }

    /// Finds the triangles `d`'s views see on `surface` (or takes its pinned ones), so every
    /// build keeps only those. The whole build made to look is kept for the first
    /// [`build`](Self::build) of the same surface.
    fn cull_hidden(&mut self, surface: &dyn Surface, d: &DetailParams) -> Result<()> {
        let whole = self.total.triangles as usize;
        let pinned = d
            .pinned_seen
            .as_ref()
            .map(|bits| unpack_bits(bits, whole))
            .transpose()?;
        let (c, out, seen) = run_in_pool(self.params.threads, || {
            let c = self.centrelines(surface);
            let out = self.bundles(&c);
            let seen = pinned.unwrap_or_else(|| {
                seen_triangles(
                    &out.positions,
                    &out.triangles,
                    &d.views,
                    d.resolution,
                    d.hidden_supersampling,
                    d.frustum_margin,
                )
            });
            (c, out, seen)
        })?;
        let subset = MeshSubset::new(
            &seen,
            &out.triangles,
            &out.corner_edges,
            self.total.vertices as usize,
            self.total.edges as usize,
        );
        let bits = pack_bits(&seen);
        self.stats.vertices = subset.vertex_count();
        self.stats.triangles = subset.triangle_count();
        self.stats.triangles_hidden = whole - subset.triangle_count();
        self.stats.topology_key = bits.chunks(8).fold(self.stats.topology_key, |h, c| {
            let mut word = [0u8; 8];
            word[..c.len()].copy_from_slice(c);
            crate::geometry::stitch_seed(h, u64::from_le_bytes(word) as usize, 0x5345_454e)
        });
        let corners =
            VertexCorners::new(&out.triangles, subset.vertex_count(), subset.vertex_index());
        self.hidden = Some(HiddenCulled {
            subset,
            corners,
            whole_triangles: out.triangles.clone(),
            seen: bits,
        });
        if d.pinned_seen.is_none() {
            if let Ok(mut slot) = self.first_build.0.lock() {
                *slot = Some((c, out));
            }
        }
        Ok(())
    }

    /// With `cull_hidden`: the triangles seen, one bit per triangle of the knit before
    /// culling (see [`DetailParams::pinned_seen`]); give them back as `pinned_seen` to
    /// rebuild the same mesh in another pose or session.
    pub fn seen_triangles(&self) -> Option<&[u8]> {
        self.hidden.as_ref().map(|h| h.seen.as_slice())
    }

    /// Figures known before building (counts, sizes, topology key); `seconds` and
    /// `clearance` are left empty.
    pub fn stats(&self) -> &KnitStats {
        &self.stats
    }

    /// The yarn radius, scene units.
    pub fn yarn_radius(&self) -> f32 {
        self.radius
    }

    /// Vertices of every build: the length of [`positions_into`](Self::positions_into)'s
    /// buffer is three times this.
    pub fn vertex_count(&self) -> usize {
        self.hidden
            .as_ref()
            .map_or(self.total.vertices as usize, |h| h.subset.vertex_count())
    }

    fn check_layout(&self, surface: &dyn Surface) -> Result<()> {
        let cyclic = (surface.cyclic_u(), surface.cyclic_v());
        if surface.domain() != self.domain || cyclic != self.cyclic {
            return Err(KnitError::Surface(format!(
                "the surface's (u,v) layout changed since it was knitted (domain {:?} -> \
                 {:?}, cyclic {:?} -> {:?}): knit it again",
                self.domain,
                surface.domain(),
                self.cyclic,
                cyclic
            )));
        }
        Ok(())
    }

    /// The whole output for `surface` (the prepared one, or it deformed).
    pub fn build(&self, surface: &dyn Surface) -> Result<KnitOutput> {
        let start = Instant::now();
        self.check_layout(surface)?;
        let mut out = run_in_pool(self.params.threads, || self.build_in_pool(surface))??;
        out.yarn_radius = self.radius;
        out.stats = KnitStats {
            seconds: start.elapsed().as_secs_f64(),
            stitches_clamped: out.stats.stitches_clamped,
            ..self.stats.clone()
        };
        if self.params.measure_clearance {
            out.stats.clearance = Some(measure(&out));
            let order = self.crossing_order(surface)?;
            out.stats.interlock = Some((order.interlock_decided, order.interlock_agree));
        }
        Ok(out)
    }

    /// Only the vertex positions for `surface` (the prepared one, or it deformed), into
    /// `positions` (`3 * vertex_count()` floats): the same values [`build`](Self::build)
    /// writes, without allocating the rest. The per-frame path of an animated knit.
    pub fn positions_into(&self, surface: &dyn Surface, positions: &mut [f32]) -> Result<()> {
        self.positions_and_normals_into(surface, positions, None)
    }

    /// [`positions_into`](Self::positions_into), and with `normals` (`3 * vertex_count()`
    /// floats) the vertex normals [`build`](Self::build) gives a knit with its hidden yarn
    /// culled (an error for any other knit: it gives none).
    pub fn positions_and_normals_into(
        &self,
        surface: &dyn Surface,
        positions: &mut [f32],
        normals: Option<&mut [f32]>,
    ) -> Result<()> {
        self.check_layout(surface)?;
        if let Some(n) = &normals {
            if self.hidden.is_none() {
                return Err(KnitError::Parameter(
                    "only a knit that culls its hidden yarn has normals of its own".into(),
                ));
            }
            if n.len() != 3 * self.vertex_count() {
                return Err(KnitError::Parameter(format!(
                    "the normals buffer holds {} floats; this knit needs {}",
                    n.len(),
                    3 * self.vertex_count()
                )));
            }
        }
        let nv = self.vertex_count();
        if positions.len() != 3 * nv {
            return Err(KnitError::Parameter(format!(
                "the positions buffer holds {} floats; this knit needs {} ({nv} vertices x 3)",
                positions.len(),
                3 * nv
            )));
        }
        run_in_pool(self.params.threads, || {
            let centrelines = self.centrelines(surface);
            match &self.hidden {
                None => self.whole_positions(&centrelines, positions),
                Some(h) => {
                    let mut whole = output_buffer::zeroed(3 * self.total.vertices as usize);
                    self.whole_positions(&centrelines, &mut whole);
                    h.subset.gather_positions(&whole, positions);
                    if let Some(normals) = normals {
                        h.corners.normals(&whole, &h.whole_triangles, normals);
                    }
                }
            }
        })
    }

    /// Every span's vertex positions, before any culling of hidden yarn.
    fn whole_positions(&self, centrelines: &Centrelines, positions: &mut [f32]) {
        let pos = split_lengths(
            positions,
            &self
                .counts
                .iter()
                .map(|c| 3 * c.vertices)
                .collect::<Vec<_>>(),
        );
        pos.into_par_iter().enumerate().for_each(|(k, positions)| {
            let mut bufs = PieceBuffers::positions_only(positions);
            self.bundle_span(k, centrelines, &mut bufs);
        });
    }

    /// Samples every piece's centreline (points, surface normals, owning stitch), in parallel.
    fn centrelines(&self, surface: &dyn Surface) -> Centrelines {
        let n = self.total.samples as usize;
        let mut c = Centrelines {
            points: vec![Vec3::ZERO; n],
            normals: vec![Vec3::ZERO; n],
            owner: vec![0u32; n],
            clamped: 0,
        };
        {
            let pts = split_lengths(&mut c.points, &self.samples);
            let nrm = split_lengths(&mut c.normals, &self.samples);
            let own = split_lengths(&mut c.owner, &self.samples);
            c.clamped = self
                .pieces
                .par_iter()
                .zip(pts)
                .zip(nrm)
                .zip(own)
                .map(|(((pc, a), b), o)| {
                    sample_piece(
                        surface,
                        &self.lattice,
                        &self.pattern,
                        &self.offsets,
                        &self.sampling,
                        pc,
                        a,
                        b,
                        o,
                    )
                })
                .sum();
        }
        c
    }

    /// Sweeps span `k`'s bundle into `bufs` (whatever parts of the output they hold).
    fn bundle_span(&self, k: usize, cl: &Centrelines, bufs: &mut PieceBuffers) {
        let sp = self.spans[k];
        let pc = self.pieces[sp.piece];
        let n = self.samples[sp.piece];
        let base = self.piece_start[sp.piece];
        let points = &cl.points[base..base + n];
        let normals = &cl.normals[base..base + n];
        let owner = &cl.owner[base..base + n];
        let wales = self.lattice.wales;
        // A float of stranded colourwork is its own colour, not the stitches' it passes.
        let float = pc.float_color.and_then(|i| {
            let palette = self.params.colors.as_ref()?.palette();
            palette.get(usize::from(i)).copied()
        });
        let color_of =
            |course: usize, wale: usize| float.unwrap_or_else(|| self.stitch_color(course, wale));
        let settings = &self.level_bundle[sp.level as usize];
        let whole = sp.first == 0 && sp.rings == n && (sp.closed || sp.last + 1 == n);
        if whole {
            // Every sample: the piece's own slices, exactly as without detail.
            let owner_of = |i: usize| (pc.course, (pc.first_wale + owner[i] as usize) % wales);
            build_bundle(
                points,
                normals,
                &owner_of,
                &color_of,
                sp.closed,
                EndTangents::default(),
                settings,
                None,
                bufs,
            );
            return;
        }
        let idx: Vec<usize> = (0..sp.rings).map(|i| sp.sample(i, n)).collect();
        let pts: Vec<Vec3> = idx.iter().map(|&i| points[i]).collect();
        let nrm: Vec<Vec3> = idx.iter().map(|&i| normals[i]).collect();
        let own: Vec<u32> = idx.iter().map(|&i| owner[i]).collect();
        let owner_of = |i: usize| (pc.course, (pc.first_wale + own[i] as usize) % wales);
        // Where the span meets another one, its end ring takes the full-density tangent so
        // both spans put the shared ring in the same plane.
        let tangent_at = |i: usize| -> Option<Vec3> {
            let inner = i > 0 && i + 1 < n;
            if pc.closed || inner {
                Some(points[(i + 1) % n] - points[(i + n - 1) % n])
            } else {
                None
            }
        };
        let ends = if sp.closed {
            EndTangents::default()
        } else {
            EndTangents {
                first: tangent_at(idx[0]),
                last: tangent_at(idx[sp.rings - 1]),
            }
        };
        // The draws of the whole piece at full detail, so this span keeps a subset of its
        // fibres (see `geometry::bundle`).
        let seed = self.level_bundle[Level::Full as usize].seed;
        let streams = piece_streams(n, |i| {
            stitch_seed(seed, pc.course, (pc.first_wale + owner[i] as usize) % wales)
        });
        let draws = FullDensityDraws {
            samples: &idx,
            streams: &streams,
            ring_segments: self.level_bundle[Level::Full as usize].ring_segments,
        };
        build_bundle(
            &pts,
            &nrm,
            &owner_of,
            &color_of,
            sp.closed,
            ends,
            settings,
            Some(&draws),
            bufs,
        );
    }

    /// The linear RGB colour of stitch (course, wale) before the random brightness
    /// variation: from the colour image, else the colour pattern, else the default yarn.
    pub fn stitch_color(&self, course: usize, wale: usize) -> [f32; 3] {
        match (&self.params.color_image, &self.params.colors) {
            (Some(img), _) => img.sample(self.lattice.tile_center(course, wale)),
            (None, Some(c)) => c.color(course, wale),
            (None, None) => DEFAULT_YARN_COLOR,
        }
    }

    /// The level of every stitch (row-major, course by wale: `courses * wales`) with
    /// camera-driven detail; `None` without (every stitch full). Stitches with no surface
    /// under them are [`Level::Culled`].
    pub fn stitch_levels(&self) -> Option<&[Level]> {
        self.levels.as_deref()
    }

    /// The bundles built, in output order: which piece, which samples, which level.
    pub fn spans(&self) -> &[Span] {
        &self.spans
    }

    /// Ring segments of a built level.
    pub fn ring_segments(&self, level: Level) -> usize {
        self.level_bundle[(level as usize).min(2)].ring_segments
    }

    /// The settings this knit was prepared with.
    pub fn params(&self) -> &KnitParams {
        &self.params
    }

    /// The stitch lattice (perturbed by `kappa`), in the surface's (u,v) domain.
    pub fn lattice(&self) -> &Lattice {
        &self.lattice
    }

    /// The (u,v) domain the knit was prepared for.
    pub fn domain(&self) -> UvRect {
        self.domain
    }

    /// Every yarn piece's centreline in (u, v, lambda) (lambda: normal offset, scene units),
    /// sampled exactly where [`build`](Self::build) samples it, before it is mapped onto the
    /// surface. Runs in the caller's rayon pool.
    pub fn uv_centrelines(&self, surface: &dyn Surface) -> Result<Vec<UvYarn>> {
        self.check_layout(surface)?;
        let wales = self.lattice.wales;
        Ok(self
            .pieces
            .par_iter()
            .zip(&self.samples)
            .map(|(pc, &n)| {
                let mut points = vec![Vec3::ZERO; n];
                let mut owner = vec![0u32; n];
                sample_piece_uv(
                    surface,
                    &self.lattice,
                    &self.pattern,
                    &self.offsets,
                    &self.sampling,
                    pc,
                    &mut points,
                    &mut owner,
                );
                let stitches = owner
                    .iter()
                    .map(|&o| (pc.course, (pc.first_wale + o as usize) % wales))
                    .collect();
                UvYarn {
                    points,
                    stitches,
                    closed: pc.closed,
                    period_u: self.lattice.tile.x * wales as f32,
                }
            })
            .collect())
    }

    /// The interlock-topology metric of this knit on `surface` (see
    /// [`crate::skeleton::crossings::crossing_order`]), measured on the skeleton's spline at
    /// [`TOPOLOGY_SAMPLES`] samples a loop at least (as the tuning and the contact relief
    /// see it), not on the output's possibly coarser polyline: where a head and a sinker run
    /// side by side, a coarse chord grazes across the other yarn's projection and back, and
    /// which of two such grazing "crossings" exist depends on the sampling, not the knit.
    pub fn crossing_order(
        &self,
        surface: &dyn Surface,
    ) -> Result<crate::skeleton::crossings::CrossingOrder> {
        self.check_layout(surface)?;
        let sampling = SplineSampling {
            samples_per_loop: self.sampling.samples_per_loop.max(TOPOLOGY_SAMPLES),
            ..self.sampling
        };
        let lines: Vec<Vec<Vec3>> = self
            .pieces
            .par_iter()
            .map(|pc| {
                let n = pc.sample_count(sampling.samples_per_loop);
                let mut points = vec![Vec3::ZERO; n];
                let mut owner = vec![0u32; n];
                sample_piece_uv(
                    surface,
                    &self.lattice,
                    &self.pattern,
                    &self.offsets,
                    &sampling,
                    pc,
                    &mut points,
                    &mut owner,
                );
                points
            })
            .collect();
        Ok(crate::skeleton::crossings::crossing_order(
            &self.lattice,
            &self.pattern,
            &self.pieces,
            &lines,
            sampling.samples_per_loop,
        ))
    }

    fn build_in_pool(&self, surface: &dyn Surface) -> Result<KnitOutput> {
        let centrelines = self.centrelines(surface);
        let mut out = match self.first_build.take_if_same(&centrelines) {
            Some(out) => out,
            None => self.bundles(&centrelines),
        };
        if let Some(h) = &self.hidden {
            let mut normals = output_buffer::zeroed(3 * h.subset.vertex_count());
            h.corners
                .normals(&out.positions, &out.triangles, &mut normals);
            out.normals = normals;
            let b = h.subset.apply(
                &out.positions,
                &out.colors,
                &out.triangles,
                &out.corner_edges,
                &out.edges,
            );
            out.positions = b.positions;
            out.colors = b.colors;
            out.triangles = b.triangles;
            out.corner_edges = b.corner_edges;
            out.edges = b.edges;
        }
        out.stats.stitches_clamped = centrelines.clamped;
        Ok(out)
    }

    /// The whole output swept along `centrelines`, before any culling of hidden yarn.
    fn bundles(&self, centrelines: &Centrelines) -> KnitOutput {
        let nv = self.total.vertices as usize;
        let nt = self.total.triangles as usize;
        let ne = self.total.edges as usize;
        let mut out = KnitOutput {
            positions: output_buffer::zeroed(3 * nv),
            colors: output_buffer::zeroed(4 * nv),
            triangles: output_buffer::zeroed(3 * nt),
            corner_edges: output_buffer::zeroed(3 * nt),
            edges: output_buffer::zeroed(2 * ne),
            ..Default::default()
        };
        let (mut vbase, mut ebase) = (
            Vec::with_capacity(self.pieces.len()),
            Vec::with_capacity(self.pieces.len()),
        );
        let (mut v, mut e) = (0usize, 0usize);
        for c in &self.counts {
            vbase.push(v);
            ebase.push(e);
            v += c.vertices;
            e += c.edges;
        }
        let lengths = |f: &dyn Fn(&BundleCounts) -> usize| -> Vec<usize> {
            self.counts.iter().map(f).collect()
        };
        let pos = split_lengths(&mut out.positions, &lengths(&|c| 3 * c.vertices));
        let col = split_lengths(&mut out.colors, &lengths(&|c| 4 * c.vertices));
        let tri = split_lengths(&mut out.triangles, &lengths(&|c| 3 * c.triangles));
        let ced = split_lengths(&mut out.corner_edges, &lengths(&|c| 3 * c.triangles));
        let edg = split_lengths(&mut out.edges, &lengths(&|c| 2 * c.edges));
        pos.into_par_iter()
            .zip(col)
            .zip(tri)
            .zip(ced)
            .zip(edg)
            .enumerate()
            .for_each(
                |(i, ((((positions, colors), corner_verts), corner_edges), edge_verts))| {
                    let mut bufs = PieceBuffers {
                        vertex_base: vbase[i],
                        edge_base: ebase[i],
                        positions,
                        colors: Some(colors),
                        topology: Some(TopologyBuffers {
                            corner_verts,
                            corner_edges,
                            edge_verts,
                        }),
                    };
                    self.bundle_span(i, centrelines, &mut bufs);
                },
            );

        out.centerline = centrelines
            .points
            .iter()
            .flat_map(|q| q.to_array())
            .collect();
        out.yarn_offsets = std::iter::once(0i64)
            .chain(self.samples.iter().scan(0i64, |acc, &n| {
                *acc += n as i64;
                Some(*acc)
            }))
            .collect();
        out.yarn_course = self.pieces.iter().map(|pc| pc.course as i32).collect();
        out.yarn_closed = self.pieces.iter().map(|pc| pc.closed).collect();
        out
    }
}

/// One yarn piece's centreline in (u, v, lambda): see [`PreparedKnit::uv_centrelines`].
#[derive(Debug, Clone)]
pub struct UvYarn {
    /// Samples in (u, v, lambda); u may run past the domain on a cyclic-u surface.
    pub points: Vec<Vec3>,
    /// (course, wale) of the stitch each sample belongs to.
    pub stitches: Vec<(usize, usize)>,
    /// A whole course round a cyclic-u surface: the last sample joins the first moved by
    /// `period_u` along u.
    pub closed: bool,
    /// The domain's width in u (the period of a cyclic u).
    pub period_u: f32,
}

/// Sampled centrelines of all pieces, concatenated.
struct Centrelines {
    points: Vec<Vec3>,
    normals: Vec<Vec3>,
    owner: Vec<u32>,
    /// Stitches whose offsets were clamped for curvature.
    clamped: usize,
}

impl Centrelines {
    /// Bit for bit the same samples (so the same sweep).
    fn same_as(&self, other: &Centrelines) -> bool {
        let same = |a: &[Vec3], b: &[Vec3]| {
            a.len() == b.len()
                && a.iter()
                    .zip(b)
                    .all(|(p, q)| p.to_array().map(f32::to_bits) == q.to_array().map(f32::to_bits))
        };
        self.owner == other.owner
            && same(&self.points, &other.points)
            && same(&self.normals, &other.normals)
    }
}

/// Clearance (min, p01) of a finished knit, in yarn diameters.
pub fn measure(out: &KnitOutput) -> (f32, f32) {
    let pts: &[Vec3] = vec3_slice(&out.centerline);
    let yarns: Vec<YarnPolyline> = out
        .yarn_offsets
        .windows(2)
        .zip(&out.yarn_closed)
        .map(|(w, &closed)| YarnPolyline {
            points: &pts[w[0] as usize..w[1] as usize],
            closed,
        })
        .collect();
    let c = clearance(
        &yarns,
        2.0 * out.yarn_radius,
        DEFAULT_NEIGHBOUR_ARCLENGTH_DIAMETERS,
        3.0,
    );
    (c.min, c.p01)
}

/// The most samples-per-loop multiple any piece of `pattern` can get.
fn densest(pattern: &StitchPattern) -> usize {
    let lean = (0..pattern.height())
        .flat_map(|r| (0..pattern.width()).map(move |w| (r, w)))
        .map(|(r, w)| pattern.stitch(r, w).land_offset.unsigned_abs() as usize)
        .max()
        .unwrap_or(0);
    crate::skeleton::sampling_density::density(lean)
}

/// The pieces of yarn of every course over the stitches `built`, each sampled as densely as
/// its loops need ([`crate::skeleton::sampling_density`]).
fn course_pieces(lattice: &Lattice, built: &[bool], pattern: &StitchPattern) -> Vec<YarnPiece> {
    let mut pieces = yarn_pieces(lattice, built);
    crate::skeleton::sampling_density(&mut pieces, lattice, pattern);
    pieces
}

/// `pieces` and the extra pieces of yarn the pattern asks for: the balls of its bobbles
/// ([`crate::skeleton::bobbles`]) and, for a palette colour chart (not an image), the floats
/// of stranded colourwork ([`crate::skeleton::floats`]).
fn with_extras(
    mut pieces: Vec<YarnPiece>,
    lattice: &Lattice,
    built: &[bool],
    pattern: &StitchPattern,
    p: &KnitParams,
) -> Vec<YarnPiece> {
    pieces.extend(crate::skeleton::bobbles::bobble_pieces(
        lattice, built, pattern,
    ));
    if let (Some(colors), None) = (&p.colors, &p.color_image) {
        pieces.extend(crate::skeleton::floats::float_pieces(
            lattice, built, colors,
        ));
    }
    pieces
}

/// See [`KnitStats::topology_key`]: a SplitMix64 chain over the structure that fixes the
/// buffers' layout.
fn topology_key(ring_segments: usize, pieces: &[YarnPiece], samples: &[usize]) -> u64 {
    let mix = |h: u64, x: u64| crate::geometry::stitch_seed(h, x as usize, 0x4b4e_4954);
    let mut h = mix(0x6b6e_6974_7765_6172, ring_segments as u64);
    h = mix(h, pieces.len() as u64);
    for (pc, &n) in pieces.iter().zip(samples) {
        h = mix(h, ((n as u64) << 1) | pc.closed as u64);
    }
    h
}

/// The topology key with camera-driven detail: the spans' ring counts, closure and ring
/// segments (see [`KnitStats::topology_key`]).
fn detail_topology_key(spans: &[Span], level_bundle: &[BundleSettings; 3]) -> u64 {
    let mix = |h: u64, x: u64| crate::geometry::stitch_seed(h, x as usize, 0x4c4f_4421);
    let mut h = mix(0x6b6e_6974_6465_7461, spans.len() as u64);
    for sp in spans {
        let m = level_bundle[sp.level as usize].ring_segments as u64;
        h = mix(h, ((sp.rings as u64) << 8) | (m << 1) | sp.closed as u64);
    }
    h
}

/// A whole piece as one full-quality span.
fn whole_piece_span(i: usize, pc: &YarnPiece, samples_per_loop: usize) -> Span {
    let n = pc.sample_count(samples_per_loop);
    Span {
        piece: i,
        first: 0,
        last: if pc.closed { n } else { n.saturating_sub(1) },
        rings: n,
        closed: pc.closed,
        level: Level::Full,
    }
}

/// The runs of one level along a piece: `(first sample, level)` in yarn order, a new run
/// where the owning stitch's level changes (at the first sample of that stitch, where the
/// two spans will share a ring). A closed piece of one level gives one run at sample 0.
#[allow(clippy::too_many_arguments)]
fn level_runs(
    surface: &dyn Surface,
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    sampling: &SplineSampling,
    pc: &YarnPiece,
    levels: &[Level],
    samples_per_loop: usize,
) -> Vec<(usize, Level)> {
    let wales = lattice.wales;
    let level_of = |j: usize| levels[pc.course * wales + (pc.first_wale + j) % wales];
    let first = level_of(0);
    if (1..pc.stitches).all(|j| level_of(j) == first) {
        return vec![(0, first)];
    }
    // Which stitch each sample belongs to, as the build samples it.
    let n = pc.sample_count(samples_per_loop);
    let mut uvl = vec![Vec3::ZERO; n];
    let mut owner = vec![0u32; n];
    sample_piece_uv(
        surface, lattice, pattern, offsets, sampling, pc, &mut uvl, &mut owner,
    );
    let level_at = |k: usize| level_of(owner[k] as usize);
    let mut runs = Vec::new();
    for k in 0..n {
        let here = level_at(k);
        let starts = if k == 0 {
            !pc.closed || level_at(n - 1) != here
        } else {
            level_at(k - 1) != here
        };
        if starts {
            runs.push((k, here));
        }
    }
    runs
}

fn vec3_slice(v: &[f32]) -> &[Vec3] {
    // Vec3 is three packed f32 (glam's non-SIMD Vec3), so a flat f32 buffer of 3N values is
    // N Vec3s.
    let n = v.len() / 3;
    // SAFETY: Vec3 is #[repr(C)] { x, y, z: f32 }, size 12, align 4, like [f32; 3].
    unsafe { std::slice::from_raw_parts(v.as_ptr().cast::<Vec3>(), n) }
}
