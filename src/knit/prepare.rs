//! Binding a knit to its surface's (u,v) layout once: counts, yarn radius, stitch size,
//! offsets, lattice, detail levels and the budget check ([`PreparedKnit::new`]).

use glam::Vec3;
use rayon::prelude::*;

use super::*;
use crate::budget::{self, OutputSize};
use crate::detail::{piece_spans, stitch_levels, Level, LevelSettings, Span};
use crate::error::{KnitError, Result};
use crate::geometry::{bundle_counts, BundleCounts, BundleSettings};
use crate::lattice::{Lattice, ROW_OVERHANG};
use crate::parallel::run_in_pool;
use crate::pattern::{ColorPattern, StitchPattern};
use crate::skeleton::{SplineSampling, YarnPiece, YarnSkeleton};
use crate::surface::{Surface, UvRect};

/// Stitch counts from explicit counts or the gauge and the surface's extent. Along a cyclic
/// direction a count from the gauge is rounded to whole repeats of the pattern (and of the
/// colour chart, where a whole number of both fits), as a knitter casts on in the round;
/// counts given explicitly are kept as given. Also returns how much wider a stitch is for the
/// rounding (the gauge's count over the rounded one), which the default yarn does not follow:
/// the gauge fixes the yarn, and rounding only stretches or gathers the stitches round.
pub(super) fn stitch_counts(
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

/// See [`KnitStats::topology_key`]: a SplitMix64 chain over the structure that fixes the
/// buffers' layout.
pub(super) fn topology_key(ring_segments: usize, pieces: &[YarnPiece], samples: &[usize]) -> u64 {
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
pub(super) fn detail_topology_key(spans: &[Span], level_bundle: &[BundleSettings; 3]) -> u64 {
    let mix = |h: u64, x: u64| crate::geometry::stitch_seed(h, x as usize, 0x4c4f_4421);
    let mut h = mix(0x6b6e_6974_6465_7461, spans.len() as u64);
    for sp in spans {
        let m = level_bundle[sp.level as usize].ring_segments as u64;
        h = mix(h, ((sp.rings as u64) << 8) | (m << 1) | sp.closed as u64);
    }
    h
}

/// A whole piece as one full-quality span.
pub(super) fn whole_piece_span(i: usize, pc: &YarnPiece, samples_per_loop: usize) -> Span {
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
pub(super) fn level_runs(
    surface: &dyn Surface,
    skeleton: &YarnSkeleton,
    pattern: &StitchPattern,
    pc: &YarnPiece,
    levels: &[Level],
    samples_per_loop: usize,
) -> Vec<(usize, Level)> {
    let wales = skeleton.lattice().wales;
    let level_of = |j: usize| levels[pc.course * wales + (pc.first_wale + j) % wales];
    let first = level_of(0);
    if (1..pc.stitches).all(|j| level_of(j) == first) {
        return vec![(0, first)];
    }
    // Which stitch each sample belongs to, as the build samples it.
    let n = pc.sample_count(samples_per_loop);
    let mut uvl = vec![Vec3::ZERO; n];
    let mut owner = vec![0u32; n];
    skeleton.sample_uv(surface, pattern, pc, samples_per_loop, &mut uvl, &mut owner);
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

/// The first check [`PreparedKnit::new`] makes: whether `courses x wales` stitches of
/// `pattern` at `p`'s sampling (`samples_per_loop`, `ring_segments`) fit `p.budget_bytes` and a
/// Blender mesh, at full detail. Returns the output's upper bound in bytes.
///
/// Cheap (no surface, no allocation): a caller that must sample a surface densely for a
/// count can refuse an absurd one before it samples.
pub fn check_budget(
    pattern: &StitchPattern,
    courses: usize,
    wales: usize,
    p: &KnitParams,
) -> Result<u64> {
    validate(p)?;
    let stitches = courses as u64 * wales as u64;
    let size = OutputSize::upper_bound(
        stitches,
        (p.samples_per_loop * YarnSkeleton::densest_sampling(pattern)) as u64,
        p.ring_segments as u64,
    );
    budget::check(&size, p.budget_bytes, stitches)?;
    Ok(size.bytes())
}

impl PreparedKnit {
    /// Validates the settings, fixes counts, radius and offsets from `surface`, lays out the
    /// lattice and checks the output against the budget (before anything large is allocated).
    pub fn new(surface: &dyn Surface, pattern: &StitchPattern, p: &KnitParams) -> Result<Self> {
        validate(p)?;
        pattern.check_knittable()?;
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
        check_budget(pattern, courses, wales, p)?;

        let cyclic_v = surface.cyclic_v();
        let domain = surface.domain();
        let cyclic = (surface.cyclic_u(), cyclic_v);
        let base = Lattice::perturbed(domain, courses, wales, cyclic.0, cyclic.1, p.kappa, p.seed)?;
        crate::cancel::check()?;
        // The mean stitch, which the default yarn follows.
        let mean = (
            len_u / wales as f32,
            if cyclic_v {
                len_v / courses as f32
            } else {
                len_v / (courses as f32 + 2.0 * ROW_OVERHANG)
            },
        );
        let yarn_width = p.stitch_size.map_or(mean.0, |s| s.0);
        let radius = p
            .yarn_radius
            .unwrap_or(DEFAULT_RADIUS_PER_STITCH_WIDTH * yarn_width / widened);
        let mut stitch_spread = None;
        let (stitch_width, stitch_height) = match p.stitch_size {
            // A stitch larger than the whole surface knits no fabric: a unit mistake.
            Some((w, h)) if w > len_u || h > len_v => {
                return Err(KnitError::Parameter(format!(
                    "stitch_size ({w} x {h}) is larger than the surface ({len_u:.4} x \
                     {len_v:.4}, scene units): give it in the surface's units"
                )))
            }
            Some(size) => size,
            None => {
                let sizes = run_in_pool(p.threads, || {
                    crate::tight_stitches::stitch_sizes(surface, &base)
                })?;
                crate::cancel::check()?;
                stitch_spread = sizes.spread;
                let (rw, rh) = sizes.tight;
                let tuned = |tight: f32, mean: f32| {
                    crate::tight_stitches::tuned_side(tight, mean, 2.0 * radius)
                };
                (tuned(mean.0 * rw, mean.0), tuned(mean.1 * rh, mean.1))
            }
        };
        // Against the mean stitch, pinned size or not: a knit rebuilt with its pinned
        // (tuned, tightest) stitch size must pass the check its first knit passed. On a
        // sphere the tightest stitches, at the poles, are a fraction of the mean.
        let (check_w, check_h) = mean;
        if 2.0 * radius > check_w.min(2.0 * check_h) {
            return Err(KnitError::Parameter(format!(
                "the yarn ({:.4} thick) is thicker than a stitch ({check_w:.4} x \
                 {check_h:.4}): use a thinner yarn or fewer stitches",
                2.0 * radius
            )));
        }
        let skeleton = YarnSkeleton::new(
            base,
            pattern,
            (stitch_width, stitch_height),
            2.0 * radius,
            SplineSampling {
                samples_per_loop: s,
                tension: p.tension,
                aspect: stitch_height / stitch_width,
            },
        )
        .with_live_loops(p.live_loops);
        // The tuning (the first knit of a pattern: seconds) stops early on request.
        crate::cancel::check()?;
        let flat_clearance = skeleton.flat_clearance();
        let lattice = skeleton.lattice();
        // Floats of stranded colourwork follow a palette chart, not an image.
        let float_colors = p.colors.as_ref().filter(|_| p.color_image.is_none());
        let bundle = BundleSettings {
            radius,
            ring_segments: m,
            fluffiness: p.fluffiness,
            color_variation: p.color_variation,
            seed: p.seed,
            plies: p.plies,
            samples_per_loop: s,
            two_intervals: true,
        };
        // Full-detail pieces first: their triangles are the figure detail is measured against.
        let (full_pieces, built, built_count, lost) = run_in_pool(p.threads, || {
            let built = skeleton.built_stitches(surface);
            let count = built.iter().filter(|b| **b).count();
            let lost = skeleton.lost_stitches(surface, &built);
            (
                skeleton.pieces(&built, &built, pattern, float_colors),
                built,
                count,
                lost,
            )
        })?;
        crate::cancel::check()?;
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
                let levels = stitch_levels(surface, lattice, &built, d, reach)?;
                let kept: Vec<bool> = levels.iter().map(|l| l.is_built()).collect();
                let pieces = skeleton.pieces(&kept, &built, pattern, float_colors);
                let spl = |level: Level| d.level_settings(level, full).samples_per_loop;
                let spans: Vec<Span> = pieces
                    .par_iter()
                    .enumerate()
                    .map(|(i, pc)| {
                        let runs = level_runs(surface, &skeleton, pattern, pc, &levels, s);
                        piece_spans(i, pc.sample_count(s), pc.closed, &runs, s, spl)
                    })
                    .flatten()
                    .collect();
                Ok((pieces, Some(levels), spans))
            })??,
        };
        crate::cancel::check()?;
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
            // Full detail keeps its radius to the bit; coarser levels widen theirs to keep
            // the knit's cover (and so its colour) as it changes level.
            let radius = match level {
                Level::Full => bundle.radius,
                _ => bundle.radius * q.cover_radius_scale(&full),
            };
            BundleSettings {
                radius,
                ring_segments: q.ring_segments,
                fluffiness: q.fluffiness,
                two_intervals: q.samples_per_loop == full.samples_per_loop,
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
        // The triangles at full quality: the yarn thick enough in the image for the
        // hidden-yarn pass to find hidden (thinner yarn it keeps wherever a renderer's
        // samples might catch it).
        let full_triangles: u64 = spans
            .iter()
            .zip(&counts)
            .filter(|(sp, _)| sp.level == Level::Full)
            .map(|(_, c)| c.triangles as u64)
            .sum();
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
            stitches_lost: lost,
            vertices: total.vertices as usize,
            triangles: total.triangles as usize,
            yarn_pieces: pieces.len(),
            in_the_round: cyclic,
            stitch_width,
            stitch_height,
            stitch_spread,
            flat_clearance,
            topology_key,
            levels: level_counts,
            triangles_full_detail,
            ..Default::default()
        };
        let mut prepared = Self {
            params: p.clone(),
            pattern: pattern.clone(),
            skeleton,
            pieces,
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
            span_profiles: Default::default(),
        };
        if let Some(d) = p.detail.as_ref().filter(|d| d.cull_hidden) {
            // The pass is skipped where the knit has too little full-quality yarn for it to
            // pay (pinned seen triangles are an earlier pass's answer and always apply).
            let runs = d.pinned_seen.is_some() || full_triangles >= d.cull_hidden_min_triangles;
            if runs {
                let start = std::time::Instant::now();
                prepared.cull_hidden(surface, d)?;
                prepared.stats.hidden_pass_seconds = start.elapsed().as_secs_f64();
            }
            prepared.stats.hidden_pass = Some(runs);
        }
        Ok(prepared)
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

    /// Triangles of every build (the same on every pose: the topology is fixed when the knit
    /// is prepared).
    pub fn triangle_count(&self) -> usize {
        self.hidden
            .as_ref()
            .map_or(self.total.triangles as usize, |h| h.subset.triangle_count())
    }

    /// The linear RGB colour of stitch (course, wale) before the random brightness
    /// variation: from the colour image, else the colour pattern, else the default yarn.
    pub fn stitch_color(&self, course: usize, wale: usize) -> [f32; 3] {
        match (&self.params.color_image, &self.params.colors) {
            (Some(img), _) => img.sample(self.skeleton.lattice().tile_center(course, wale)),
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

    /// Yarn radius of a built level, scene units: the yarn's at full detail, widened at
    /// coarser levels to keep the knit's cover ([`LevelSettings::cover_radius_scale`]).
    pub fn ring_radius(&self, level: Level) -> f32 {
        self.level_bundle[(level as usize).min(2)].radius
    }

    /// The settings this knit was prepared with.
    pub fn params(&self) -> &KnitParams {
        &self.params
    }

    /// The stitch lattice (perturbed by `kappa`), in the surface's (u,v) domain.
    pub fn lattice(&self) -> &Lattice {
        self.skeleton.lattice()
    }

    /// The (u,v) domain the knit was prepared for.
    pub fn domain(&self) -> UvRect {
        self.domain
    }
}
