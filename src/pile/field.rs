//! The pile field (roots, frames, directions, colours, sampled once) and its mesh buffers for
//! a view.

use std::time::Instant;

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::fractal_noise::{fractal_noise, rotate_z_to, NoiseField, NoiseParams};
use super::press::{bend, pressed_direction};
use super::slices::{
    write_colors, write_pile, write_topology, write_uvs, PileGeometry, SliceCounts, View,
    EDGES_PER_QUAD, TRIANGLES_PER_QUAD, VERTICES_PER_QUAD,
};
use super::{
    check_budget, pile_grid, PileColors, PileParams, DEFAULT_LENGTH_PER_STITCH_WIDTH,
    DEFAULT_PLUSH_GAUGE, DEFAULT_RADIUS_PER_PILE_SPACING,
};
use crate::error::{KnitError, Result};
use crate::output_buffer::zeroed;
use crate::parallel::run_in_pool;
use crate::surface::Surface;

/// Piles per parallel work item (keeps rayon's overhead small next to the work).
const PILES_PER_TASK: usize = 256;

/// Figures about a plush build.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PileStats {
    pub courses: usize,
    pub wales: usize,
    /// Piles built.
    pub piles: usize,
    /// Piles not built because their root has no surface (outside every UV island).
    pub piles_skipped: usize,
    /// Piles with horizontal / vertical slices for the current view.
    pub horizontal: usize,
    pub vertical: usize,
    pub slices: usize,
    pub vertices: usize,
    pub triangles: usize,
    /// Pile length and radius, scene units.
    pub pile_length: f32,
    pub pile_radius: f32,
    /// Stitch width (along u) and height (along v) measured on the surface, scene units.
    pub stitch_width: f32,
    pub stitch_height: f32,
    pub noise_width: usize,
    pub noise_height: usize,
    /// Equal keys mean identical triangles, edges, corner edges, UVs and buffer sizes: a mesh
    /// built for one key needs only new positions (and mask) for another view or build. A
    /// function of the pile count and the slices per pile, never of a view.
    pub topology_key: u64,
    /// Seconds in the core: the field and the buffers for [`plush`]; the buffers alone for
    /// [`PileField::build`]; the view alone for [`PileField::update`] and [`PileField::view`].
    pub seconds: f64,
}

/// Mesh buffers of a plush, in the dtypes Blender's `foreach_set` takes. Layout in
/// [`super::slices`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PileBuffers {
    /// `(V, 3)` object space, scene units. Depends on the view.
    pub positions: Vec<f32>,
    /// `(T, 3)` vertex indices.
    pub triangles: Vec<i32>,
    /// `(E, 2)` vertex indices, every edge once.
    pub edges: Vec<i32>,
    /// `(3T,)` the edge from corner k of each triangle to the next corner.
    pub corner_edges: Vec<i32>,
    /// `(V, 4)` linear RGBA.
    pub colors: Vec<f32>,
    /// `(V, 2)` each quad `(0,0), (1,0), (1,1), (0,1)`.
    pub uvs: Vec<f32>,
    /// `(V,)` [`super::slices::MASK_ROUND`] (horizontal) or `MASK_RECT` (vertical). Depends
    /// on the view.
    pub mask: Vec<f32>,
    /// `(P,)` 1 where the pile has horizontal slices, 0 vertical. Depends on the view.
    pub horizontal: Vec<u8>,
    pub stats: PileStats,
}

/// The view-dependent part of a plush: what [`PileField::view`] returns.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PileView {
    pub positions: Vec<f32>,
    pub mask: Vec<f32>,
    pub horizontal: Vec<u8>,
    pub horizontal_count: usize,
    pub vertical_count: usize,
    pub seconds: f64,
}

/// Pile roots, frames, directions and colours sampled once from a surface; turns into
/// mesh buffers for any view without touching the surface again.
#[derive(Debug, Clone, PartialEq)]
pub struct PileField {
    /// Per pile, in root order (pile rows along v, bottom first; within a row along u).
    pub piles: Vec<PileGeometry>,
    /// Per pile base colour, linear RGB.
    pub colors: Vec<[f32; 3]>,
    /// Per pile (u,v) of the root.
    pub root_uvs: Vec<Vec2>,
    pub pile_length: f32,
    pub pile_radius: f32,
    pub slices: usize,
    /// The fractal noise, in the noise frame (z = nominal direction).
    pub noise: NoiseField,
    /// Statistics of the field (the view-dependent counts are 0).
    pub stats: PileStats,
}

/// A plush for one view: the field (to follow a camera) and its buffers.
#[derive(Debug, Clone)]
pub struct Plush {
    pub field: PileField,
    pub buffers: PileBuffers,
}

fn positive(name: &str, v: Option<f32>) -> Result<()> {
    match v {
        Some(x) if !(x.is_finite() && x > 0.0) => Err(KnitError::Parameter(format!(
            "{name} must be a positive length, not {x}"
        ))),
        _ => Ok(()),
    }
}

fn validate(p: &PileParams) -> Result<()> {
    use crate::settings as s;
    s::PILES_PER_STITCH.check_count(p.piles_per_stitch)?;
    s::SLICES.check_count(p.slices)?;
    for (setting, n) in [(s::PLUSH_COURSES, p.courses), (s::PLUSH_WALES, p.wales)] {
        if let Some(n) = n {
            setting.check_count(n)?;
        }
    }
    if let Some((wales, courses)) = p.gauge {
        s::PLUSH_GAUGE_WALES.check(wales)?;
        s::PLUSH_GAUGE_COURSES.check(courses)?;
    }
    positive("pile length", p.pile_length)?;
    positive("pile radius", p.pile_radius)?;
    p.nominal.direction()?;
    s::PRESS_STRENGTH.check(p.press_strength)?;
    if let Some(a) = p.press_azimuth {
        if !a.is_finite() {
            return Err(KnitError::Parameter(format!(
                "press direction must be a finite angle in radians, not {a}"
            )));
        }
    }
    match &p.colors {
        PileColors::Solid(c) => check_color(c)?,
        PileColors::PerStitch(cs) => cs.iter().try_for_each(check_color)?,
        PileColors::Pattern(_) | PileColors::Image(_) => {}
    }
    Ok(())
}

fn check_color(c: &[f32; 3]) -> Result<()> {
    if c.iter().all(|x| x.is_finite() && *x >= 0.0) {
        Ok(())
    } else {
        Err(KnitError::Parameter(format!(
            "pile colours must be finite and non-negative linear RGB, not {c:?}"
        )))
    }
}

/// Stitch counts from explicit counts or the gauge and the surface's extent.
fn stitch_counts(len_u: f32, len_v: f32, p: &PileParams) -> Result<(usize, usize)> {
    let gauge = p.gauge.unwrap_or(DEFAULT_PLUSH_GAUGE);
    crate::gauge::stitch_counts((len_u, len_v), gauge, p.courses, p.wales)
}

/// Unit fabric frame (x along u, y = z x x, z = normal) at a root, from a central difference
/// along u (one-sided at an island border), falling back to the v direction and then to any
/// tangent where the surface pinches.
fn fabric_frame(surface: &dyn Surface, uv: Vec2, root: Vec3, n: Vec3, h: Vec2) -> (Vec3, Vec3) {
    let diff = |d: Vec2| -> Vec3 {
        let fwd = surface.eval(uv + d).map(|s| s.position);
        let back = surface.eval(uv - d).map(|s| s.position);
        match (fwd, back) {
            (Some(a), Some(b)) => a - b,
            (Some(a), None) => a - root,
            (None, Some(b)) => root - b,
            (None, None) => Vec3::ZERO,
        }
    };
    let tangent = |t: Vec3| (t - n * n.dot(t)).try_normalize();
    let x = tangent(diff(Vec2::new(h.x, 0.0)))
        .or_else(|| tangent(diff(Vec2::new(0.0, h.y))).map(|y| y.cross(n)))
        .and_then(Vec3::try_normalize)
        .unwrap_or_else(|| n.any_orthonormal_vector());
    (x, n.cross(x))
}

impl PileField {
    /// Samples `surface`: roots, frames, noise, directions, colours. Checks the budget of the
    /// whole build (this field's buffers for one view included) before allocating anything.
    pub fn new(surface: &dyn Surface, p: &PileParams) -> Result<Self> {
        let start = Instant::now();
        validate(p)?;
        let (len_u, len_v) = surface.extent();
        if !(len_u.is_finite() && len_v.is_finite() && len_u > 0.0 && len_v > 0.0) {
            return Err(KnitError::Surface(format!(
                "the surface has no extent to grow pile on (lengths {len_u} x {len_v} along \
                 u and v)"
            )));
        }
        let domain = surface.domain();
        let dsize = domain.size();
        if !(dsize.x.is_finite() && dsize.y.is_finite() && dsize.x > 0.0 && dsize.y > 0.0) {
            return Err(KnitError::Surface(format!(
                "the surface's (u,v) domain has no area ({} x {})",
                dsize.x, dsize.y
            )));
        }
        let (courses, wales) = stitch_counts(len_u, len_v, p)?;
        let (per_u, per_v) = pile_grid(p.piles_per_stitch);
        let cols = wales.saturating_mul(per_u);
        let rows = courses.saturating_mul(per_v);
        let (noise_w, noise_h) = p.noise_size.unwrap_or((cols, rows));
        let counts = SliceCounts::of((cols as u64).saturating_mul(rows as u64), p.slices as u64);
        check_budget(
            &counts,
            (noise_w as u64).saturating_mul(noise_h as u64),
            p.budget_bytes,
        )?;
        let noise_params = NoiseParams {
            width: noise_w,
            height: noise_h,
            theta_max: p.theta_max,
            scales: p.noise_scales.clone(),
            seed: p.seed,
        };
        noise_params.validate()?;
        if let PileColors::PerStitch(cs) = &p.colors {
            if cs.len() != courses * wales {
                return Err(KnitError::Parameter(format!(
                    "per-stitch colours: {} given for {courses} courses x {wales} wales ({})",
                    cs.len(),
                    courses * wales
                )));
            }
        }

        let stitch_width = len_u / wales as f32;
        let stitch_height = len_v / courses as f32;
        let spacing = (len_u / cols as f32).min(len_v / rows as f32);
        let pile_length = p
            .pile_length
            .unwrap_or(DEFAULT_LENGTH_PER_STITCH_WIDTH * stitch_width);
        let pile_radius = p
            .pile_radius
            .unwrap_or(DEFAULT_RADIUS_PER_PILE_SPACING * spacing);
        // Plush piles are millimetres on a garment: one longer than the fabric is wide (or a
        // radius beyond that) is a unit mistake, and its geometry would dwarf the surface.
        let extent = len_u.max(len_v);
        for (name, value) in [("pile_length", pile_length), ("pile_radius", pile_radius)] {
            if value > extent {
                return Err(KnitError::Parameter(format!(
                    "{name} {value} is longer than the fabric is wide ({extent:.4}, scene \
                     units): give it in the surface's units"
                )));
            }
        }
        let t = p.nominal.direction()?;
        let pressed = pressed_direction(p.press_azimuth.unwrap_or(p.nominal.azimuth()));

        let (noise, roots) = run_in_pool(p.threads, || -> Result<_> {
            let noise = fractal_noise(&noise_params)?;
            let cell = Vec2::new(1.0 / cols as f32, 1.0 / rows as f32);
            let h = 0.25 * cell * dsize;
            let shift = dither_shift(p.seed);
            let pile = |idx: usize| -> Option<(PileGeometry, [f32; 3], Vec2)> {
                let (i, j) = (idx / cols, idx % cols);
                let draws = pile_draws(p.seed, i, j);
                let st = Vec2::new(
                    (j as f32 + 0.5 + ROOT_JITTER * (draws.x - 0.5)) * cell.x,
                    (i as f32 + 0.5 + ROOT_JITTER * (draws.y - 0.5)) * cell.y,
                );
                let uv = domain.min + st * dsize;
                let sp = surface.eval(uv)?;
                let (a, b) = fabric_frame(surface, uv, sp.position, sp.normal, h);
                let mut d = rotate_z_to(t, noise.lookup(st));
                if let Some(press) = &p.press {
                    d = bend(d, pressed, press.sample(uv) * p.press_strength);
                }
                let dir = (a * d.x + b * d.y + sp.normal * d.z)
                    .try_normalize()
                    .unwrap_or(sp.normal);
                let (course, wale) = (i / per_v, j / per_u);
                let color = match &p.colors {
                    PileColors::Solid(c) => *c,
                    PileColors::PerStitch(cs) => cs.get(course * wales + wale).copied()?,
                    PileColors::Pattern(cp) => cp.color(course, wale),
                    PileColors::Image(img) => img.sample(uv),
                };
                let geometry = PileGeometry {
                    root: sp.position,
                    a,
                    b,
                    normal: sp.normal,
                    t: dir,
                    blend: dither_threshold(i, j, shift),
                };
                Some((geometry, color, uv))
            };
            let roots: Vec<_> = (0..cols * rows)
                .into_par_iter()
                .with_min_len(PILES_PER_TASK)
                .filter_map(pile)
                .collect();
            Ok((noise, roots))
        })??;

        let n = roots.len();
        let mut piles = Vec::with_capacity(n);
        let mut colors = Vec::with_capacity(n);
        let mut root_uvs = Vec::with_capacity(n);
        for (g, c, uv) in roots {
            piles.push(g);
            colors.push(c);
            root_uvs.push(uv);
        }
        let stats = PileStats {
            courses,
            wales,
            piles: n,
            piles_skipped: cols * rows - n,
            slices: p.slices,
            pile_length,
            pile_radius,
            stitch_width,
            stitch_height,
            noise_width: noise.width,
            noise_height: noise.height,
            seconds: start.elapsed().as_secs_f64(),
            ..Default::default()
        };
        Ok(Self {
            piles,
            colors,
            root_uvs,
            pile_length,
            pile_radius,
            slices: p.slices,
            noise,
            stats,
        })
    }

    /// Distance between consecutive slices along a pile: `pile_length / slices`.
    pub fn slice_spacing(&self) -> f32 {
        self.pile_length / self.slices as f32
    }

    /// Closed-form element counts of this field's buffers.
    pub fn counts(&self) -> SliceCounts {
        SliceCounts::of(self.piles.len() as u64, self.slices as u64)
    }

    /// The mesh buffers for `view`, in a private pool of `threads` threads.
    pub fn build(
        &self,
        view: &View,
        threads: Option<usize>,
        budget_bytes: u64,
    ) -> Result<PileBuffers> {
        let start = Instant::now();
        view.validate()?;
        let counts = self.counts();
        check_budget(&counts, 0, budget_bytes)?;
        let s = self.slices;
        let (nv, nt, ne) = (
            counts.vertices as usize,
            counts.triangles as usize,
            counts.edges as usize,
        );
        let mut out = PileBuffers {
            positions: zeroed(3 * nv),
            triangles: zeroed(3 * nt),
            edges: zeroed(2 * ne),
            corner_edges: zeroed(3 * nt),
            colors: zeroed(4 * nv),
            uvs: zeroed(2 * nv),
            mask: zeroed(nv),
            horizontal: vec![0; self.piles.len()],
            stats: self.stats.clone(),
        };
        let quads_per_task = PILES_PER_TASK * s;
        run_in_pool(threads, || {
            out.triangles
                .par_chunks_mut(3 * TRIANGLES_PER_QUAD * quads_per_task)
                .zip(
                    out.corner_edges
                        .par_chunks_mut(3 * TRIANGLES_PER_QUAD * quads_per_task),
                )
                .zip(
                    out.edges
                        .par_chunks_mut(2 * EDGES_PER_QUAD * quads_per_task),
                )
                .enumerate()
                .for_each(|(task, ((tri, ce), ed))| {
                    write_topology(task * quads_per_task, tri, ce, ed);
                });
            out.colors
                .par_chunks_mut(4 * VERTICES_PER_QUAD * s)
                .zip(out.uvs.par_chunks_mut(2 * VERTICES_PER_QUAD * s))
                .zip(&self.colors)
                .with_min_len(PILES_PER_TASK)
                .for_each(|((col, uv), c)| {
                    write_colors(*c, col);
                    write_uvs(uv);
                });
        })?;
        let (h, v) = self.write_view(
            view,
            threads,
            &mut out.positions,
            &mut out.mask,
            &mut out.horizontal,
        )?;
        out.stats.horizontal = h;
        out.stats.vertical = v;
        out.stats.vertices = nv;
        out.stats.triangles = nt;
        out.stats.topology_key = topology_key(self.piles.len(), s);
        out.stats.seconds = start.elapsed().as_secs_f64();
        Ok(out)
    }

    /// Re-chooses the slices and rewrites the positions, mask and slice choice of `out` (built
    /// from this field) for a new view. Topology, UVs and colours stay as they are.
    pub fn update(&self, view: &View, out: &mut PileBuffers, threads: Option<usize>) -> Result<()> {
        let start = Instant::now();
        view.validate()?;
        let counts = self.counts();
        if out.positions.len() as u64 != 3 * counts.vertices
            || out.mask.len() as u64 != counts.vertices
            || out.horizontal.len() != self.piles.len()
        {
            return Err(KnitError::Parameter(
                "these buffers were not built from this pile field".into(),
            ));
        }
        let (h, v) = self.write_view(
            view,
            threads,
            &mut out.positions,
            &mut out.mask,
            &mut out.horizontal,
        )?;
        out.stats.horizontal = h;
        out.stats.vertical = v;
        out.stats.seconds = start.elapsed().as_secs_f64();
        Ok(())
    }

    /// The view-dependent buffers for `view`, newly allocated.
    pub fn view(&self, view: &View, threads: Option<usize>) -> Result<PileView> {
        let start = Instant::now();
        view.validate()?;
        let nv = self.counts().vertices as usize;
        let mut out = PileView {
            positions: zeroed(3 * nv),
            mask: zeroed(nv),
            horizontal: vec![0; self.piles.len()],
            ..Default::default()
        };
        let (h, v) = self.write_view(
            view,
            threads,
            &mut out.positions,
            &mut out.mask,
            &mut out.horizontal,
        )?;
        out.horizontal_count = h;
        out.vertical_count = v;
        out.seconds = start.elapsed().as_secs_f64();
        Ok(out)
    }

    /// Writes positions, mask and choice for `view`; returns (horizontal, vertical) counts.
    fn write_view(
        &self,
        view: &View,
        threads: Option<usize>,
        positions: &mut [f32],
        mask: &mut [f32],
        horizontal: &mut [u8],
    ) -> Result<(usize, usize)> {
        let s = self.slices;
        let (radius, spacing) = (self.pile_radius, self.slice_spacing());
        let n_h = run_in_pool(threads, || {
            positions
                .par_chunks_mut(3 * VERTICES_PER_QUAD * s)
                .zip(mask.par_chunks_mut(VERTICES_PER_QUAD * s))
                .zip(horizontal.par_iter_mut())
                .zip(&self.piles)
                .with_min_len(PILES_PER_TASK)
                .map(|(((pos, m), hz), pile)| {
                    let h = write_pile(pile, view, radius, spacing, pos, m);
                    *hz = h as u8;
                    h as usize
                })
                .sum::<usize>()
        })?;
        Ok((n_h, self.piles.len() - n_h))
    }
}

/// How far a root strays from its cell's centre, as a share of the cell along u and v: anywhere
/// in its cell (stratified sampling). Roots on an exact grid line up into rows and columns that
/// EEVEE draws as a regular grid across the pile; real plush has none. A uniform offset over the
/// whole cell cancels the grid's frequency and its harmonics exactly (a narrower one, 0.7 of
/// a cell, left a tenth of the grid's spectral peak).
const ROOT_JITTER: f32 = 1.0;

/// Mixed into the seed so a pile's draws differ from the noise texel's at the same `(i, j)`.
const PILE_SALT: u64 = 0x7069_6C65_5F72_6F6F; // "pile_roo"

/// Roberts' R2 sequence's steps (the plastic number's inverse powers): the most evenly spread
/// two-dimensional low-discrepancy lattice.
const R2_STEPS: (f64, f64) = (0.754_877_666_246_692_7, 0.569_840_290_998_053_2);

/// Pile `(i, j)`'s threshold across the slice band, in `[0, 1)`: the R2 sequence over the pile
/// grid, shifted by `shift` (one draw per seed, so seeds differ while every shift keeps R2's
/// even spread). In f64 so that a large grid keeps the fraction's low bits.
fn dither_threshold(i: usize, j: usize, shift: f64) -> f32 {
    (i as f64 * R2_STEPS.0 + j as f64 * R2_STEPS.1 + shift).fract() as f32
}

/// Pile `(row i, column j)`'s place in its cell, each way in `[0, 1)` (24 bits), from the seed
/// and its grid cell alone.
fn pile_draws(seed: u64, i: usize, j: usize) -> Vec2 {
    let h = crate::rng::cell_seed(seed ^ PILE_SALT, i, j);
    let unit = |bits: u64| (bits & 0xFF_FFFF) as f32 / (1u64 << 24) as f32;
    Vec2::new(unit(h >> 40), unit(h >> 16))
}

/// The seed's shift of the dither thresholds, in `[0, 1)` (53 bits).
fn dither_shift(seed: u64) -> f64 {
    (crate::rng::mix64(seed ^ PILE_SALT) >> 11) as f64 / (1u64 << 53) as f64
}

/// See [`PileStats::topology_key`]: the project's SplitMix64 mix of the two numbers that fix
/// the layout, salted apart from the knit's keys.
fn topology_key(piles: usize, slices: usize) -> u64 {
    let h = crate::pile::fractal_noise::texel_seed(0x706c_7573_685f_6b65, piles, slices);
    h ^ 0x5049_4c45 // "PILE"
}

/// Samples `surface` into a [`PileField`] and builds its buffers for `view`.
pub fn plush(surface: &dyn Surface, p: &PileParams, view: &View) -> Result<Plush> {
    let start = Instant::now();
    view.validate()?;
    let field = PileField::new(surface, p)?;
    crate::cancel::check()?;
    let mut buffers = field.build(view, p.threads, p.budget_bytes)?;
    crate::cancel::check()?;
    buffers.stats.seconds = start.elapsed().as_secs_f64();
    Ok(Plush { field, buffers })
}
