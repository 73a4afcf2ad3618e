//! Camera-driven level of detail and culling (issue 7): model no more of a knit than the
//! scene's camera can see.
//!
//! Each built stitch gets a [`Level`] from its projected size in pixels, the largest over
//! every camera view given (several views cover an animation's frame range: a stitch is
//! modelled as finely as the closest frame needs, so its level never changes during the
//! animation and nothing pops):
//!
//! | level | when (stitch size on screen) | what is built |
//! |---|---|---|
//! | [`Level::Full`] | `>= full_px` | the user's samples per loop, ring segments and fluff |
//! | [`Level::Mid`] | `>= mid_px` | [`LevelQuality`] `mid`: fewer samples and segments |
//! | [`Level::Far`] | `>= texture_px` | `far`: a plain tube (no fluff), 3 segments |
//! | [`Level::Texture`] | `< texture_px` | nothing: the source wears the knitwear texture |
//! | [`Level::Culled`] | outside every view's frustum (with margin), or facing away from every view on a closed surface | nothing |
//!
//! The projected size of a stitch is the largest of the screen lengths of its tile's width
//! vector, height vector, and one stitch width along the surface normal, all placed at the
//! tile centre: it shrinks with distance but not with foreshortening (a yarn seen at a
//! grazing angle is as thick on screen as one seen face on).
//!
//! Levels never crack the yarn: a course is sampled once at full density and each run of
//! stitches of one level (a span) keeps a subset of those samples, the two spans on either
//! side of a level change sharing the sample at the stitch boundary. The centreline is the
//! same spline at every level.

use std::sync::Arc;

use glam::{Mat4, Vec2, Vec3, Vec4, Vec4Swizzles};
use rayon::prelude::*;

use crate::error::{KnitError, Result};
use crate::lattice::Lattice;
use crate::surface::Surface;

/// How finely a stitch is modelled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(u8)]
pub enum Level {
    Full = 0,
    Mid = 1,
    Far = 2,
    /// Below a few pixels: not built; the knitwear texture on the source stands in.
    Texture = 3,
    /// Not visible from any view: not built.
    Culled = 4,
}

impl Level {
    /// Every level, finest first (the order of [`crate::knit::KnitStats::levels`]).
    pub const ALL: [Level; 5] = [
        Level::Full,
        Level::Mid,
        Level::Far,
        Level::Texture,
        Level::Culled,
    ];

    /// Whether stitches of this level get yarn geometry.
    pub fn is_built(self) -> bool {
        self <= Level::Far
    }

    /// Lower-case name ("full", "mid", "far", "texture", "culled").
    pub fn name(self) -> &'static str {
        match self {
            Level::Full => "full",
            Level::Mid => "mid",
            Level::Far => "far",
            Level::Texture => "texture",
            Level::Culled => "culled",
        }
    }
}

/// One camera view of the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraView {
    /// Clip space from the surface's object space (scene units): `projection * view *
    /// world_from_object`, OpenGL conventions (a point is in the frame when
    /// `-w <= x, y <= w`, in front of the camera when `w > 0`).
    pub clip_from_object: Mat4,
    /// The eye in the surface's object space: `(position, 1)` for a perspective camera,
    /// `(unit direction towards the camera, 0)` for an orthographic one.
    pub eye: Vec4,
}

/// The surface as each camera view sees it, one per view: a deforming source's pose at the
/// frame of that view (an armature, a shape key, a modifier that animates). Empty: every view
/// sees the knit's own surface. Each pose has the knit's (u,v) layout (the same domain and
/// cyclic directions); its stitches are measured, framed and faced in that pose, so a part of
/// the surface that moves into the frame, or up to the camera, during an animation is built
/// as finely as the frame that sees it best needs.
#[derive(Clone, Default)]
pub struct ViewPoses(pub Vec<Arc<dyn Surface>>);

impl ViewPoses {
    pub fn len(&self) -> usize {
        self.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The pose view `i` sees, or `None` where views see the knit's own surface.
    pub fn of_view(&self, i: usize) -> Option<&dyn Surface> {
        self.0.get(i).map(|s| &**s)
    }
}

impl std::fmt::Debug for ViewPoses {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ViewPoses({} surfaces)", self.0.len())
    }
}

impl PartialEq for ViewPoses {
    /// The same surfaces, by identity (a surface is immutable once made).
    fn eq(&self, other: &Self) -> bool {
        self.0.len() == other.0.len()
            && self
                .0
                .iter()
                .zip(&other.0)
                .all(|(a, b)| std::ptr::addr_eq(Arc::as_ptr(a), Arc::as_ptr(b)))
    }
}

/// Ring segments, samples per loop and fluff of a coarser level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevelQuality {
    /// Centreline samples per stitch (6..=256); never more than the full level's.
    pub samples_per_loop: usize,
    /// Points per ring (3..=64); never more than the full level's.
    pub ring_segments: usize,
    /// Keep the user's fluffiness (false: a plain tube).
    pub fluff: bool,
}

/// Camera-driven detail settings. Default thresholds sit at the knee of the speed-accuracy
/// chart (`scripts/chart_speed_accuracy.py`).
#[derive(Debug, Clone, PartialEq)]
pub struct DetailParams {
    /// The views to model for, at least one (an animated camera: one per frame, or a sample
    /// of its frames).
    pub views: Vec<CameraView>,
    /// The surface in each view's pose ([`ViewPoses`]); empty: the knit's own, for every
    /// view.
    pub poses: ViewPoses,
    /// Render resolution, pixels (width, height).
    pub resolution: (u32, u32),
    /// Stitches at least this many pixels across are built at full quality. Default: 12.
    pub full_px: f32,
    /// Stitches at least this many pixels across are built at `mid` quality. Default: 5.
    pub mid_px: f32,
    /// Stitches smaller than this many pixels are left to the knitwear texture. Default: 1.
    pub texture_px: f32,
    /// Quality of [`Level::Mid`]. `None`: half the samples (at least 6) and five sixths of the
    /// ring segments (at least 3), fluff kept.
    pub mid: Option<LevelQuality>,
    /// Quality of [`Level::Far`]. `None`: 6 samples, 3 segments, no fluff.
    pub far: Option<LevelQuality>,
    /// Frustum margin: the frame is widened by this fraction of its half-width and
    /// half-height on every side before culling. Default: 0.1. Negative: no frustum culling.
    pub frustum_margin: f32,
    /// Cull stitches that face away from every view. Only right for a closed surface, whose
    /// front hides its back. Default: false.
    pub cull_back_faces: bool,
    /// Levels fixed in advance (row-major, `courses * wales`), e.g. those of an earlier
    /// knit of the same layout: the views are then not needed. An animated knit pins the
    /// levels chosen when it was knitted, so every frame (and a farm machine that opens the
    /// file at any frame) rebuilds the same topology.
    pub pinned: Option<Vec<Level>>,
    /// Cull the yarn hidden behind other yarn: keep only the triangles some view sees at a
    /// sample of its image ([`crate::visibility`]), the frame widened by `frustum_margin`.
    /// With [`poses`](Self::poses) each view looks at the knit built in its own pose.
    /// Default: false.
    pub cull_hidden: bool,
    /// Visibility samples per pixel side for `cull_hidden` (1..=16). Default: 4 (16 samples a
    /// pixel, as a well anti-aliased render takes).
    pub hidden_supersampling: u32,
    /// `cull_hidden` runs its pass only where the knit has at least this many triangles at
    /// [`Level::Full`] (the yarn thick enough in the image for the pass to find hidden; it
    /// keeps thinner yarn anyway); otherwise the knit is built whole. Pinned seen triangles
    /// apply whatever the count. Default: 0 (always).
    pub cull_hidden_min_triangles: u64,
    /// The triangles seen, fixed in advance (with `cull_hidden`): one bit per triangle of the
    /// knit before culling, triangle `i` at bit `i % 8` of byte `i / 8`, as
    /// [`crate::knit::PreparedKnit::seen_triangles`] gives them. An animated knit pins the
    /// set chosen when it was knitted, as it pins the levels.
    pub pinned_seen: Option<Vec<u8>>,
}

impl Default for DetailParams {
    /// The defaults of [`crate::settings`].
    fn default() -> Self {
        use crate::settings as s;
        Self {
            views: Vec::new(),
            poses: ViewPoses::default(),
            resolution: (1920, 1080),
            full_px: s::DETAIL_FULL_PX.default_f32(),
            mid_px: s::DETAIL_MID_PX.default_f32(),
            texture_px: s::DETAIL_TEXTURE_PX.default_f32(),
            mid: None,
            far: None,
            frustum_margin: s::FRUSTUM_MARGIN.default_f32(),
            cull_back_faces: s::CULL_BACK_FACES.default == Some(1.0),
            pinned: None,
            cull_hidden: s::CULL_HIDDEN.default == Some(1.0),
            hidden_supersampling: s::HIDDEN_SUPERSAMPLING.default_usize() as u32,
            cull_hidden_min_triangles: s::CULL_HIDDEN_MIN_TRIANGLES.default_usize() as u64,
            pinned_seen: None,
        }
    }
}

/// A stitch whose centre normal makes this cosine or less with the direction to the eye
/// faces away. Below zero, so that stitches near the silhouette (whose yarn stands off the
/// surface and still shows) are kept.
pub const BACK_FACE_COSINE: f32 = -0.2;

/// The quality each built level uses, for a knit of `samples_per_loop` and `ring_segments`
/// at full quality and `fluffiness`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevelSettings {
    pub samples_per_loop: usize,
    pub ring_segments: usize,
    pub fluffiness: f32,
}

/// The cover a coarser sampling of the centreline loses, as a fraction, at `1/n^2 - 1/N^2`
/// for `n` samples per loop against full detail's `N`: `(x, loss)` points joined by straight
/// lines, and continued past the last along the last segment. Measured with Workbench renders
/// of the default swatch, after the ring's shape (see [`LevelSettings::cover_radius_scale`]):
/// the default mid level (8 of 16 samples, 5 ring points) loses 6% of its cover to cut
/// corners (fitted on the 15 cm swatch of `tests/python/blender/test_detail.py`, about 8 px
/// a stitch, to cover within 1% of full detail), the far level (6) 30% (at about 5 px a
/// stitch), where its loops turn to hexagons and their heads pile over each other.
pub const SAMPLING_COVER_LOSS: [(f32, f32); 3] = [(0.0, 0.0), (0.01172, 0.06), (0.02387, 0.334)];

/// How much wider full detail's fluff makes the yarn look, per unit of fluffiness, against a
/// plain tube (the same measurements, at fluffiness 0, 0.5 and 1.5).
pub const FLUFF_COVER_PER_FLUFFINESS: f32 = 0.17;

impl LevelSettings {
    /// The factor on the yarn radius that lets a level of these settings cover as much of
    /// the image as `full` does, so a knit keeps its colour and brightness when its stitches
    /// change level (issue 16 item 5). A coarser level loses cover three ways, and the factor
    /// undoes each:
    ///
    /// - an `m`-gon tube is narrower on average over the view directions round it than an
    ///   `M`-gon one: mean widths in the ratio `m sin(pi / m)` to `M sin(pi / M)` (the
    ///   polygons' perimeters, by Cauchy's formula);
    /// - fewer samples per loop cut the loops' corners ([`SAMPLING_COVER_LOSS`]);
    /// - fluff widens the yarn by `1 + K f` ([`FLUFF_COVER_PER_FLUFFINESS`]), lost where a
    ///   level drops it.
    ///
    /// 1 exactly when the settings are `full`'s. With it a mid or far knit covers within 2%
    /// of full detail's area on a render (tests/python/blender/test_detail.py prints the
    /// figures), where it covered 8% (mid) and 23% (far) less.
    pub fn cover_radius_scale(&self, full: &LevelSettings) -> f32 {
        let width = |m: usize| {
            let m = m.max(3) as f32;
            m * crate::portable_math::sin_cos(std::f32::consts::PI / m).0
        };
        let inverse_squared = |n: usize| 1.0 / (n.max(1) as f32 * n.max(1) as f32);
        let segments = width(full.ring_segments) / width(self.ring_segments);
        let x = (inverse_squared(self.samples_per_loop) - inverse_squared(full.samples_per_loop))
            .max(0.0);
        let t = &SAMPLING_COVER_LOSS;
        let k = if x <= t[1].0 { 1 } else { 2 };
        let (a, b) = (t[k - 1], t[k]);
        let loss = a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0);
        let fluff = (1.0 + FLUFF_COVER_PER_FLUFFINESS * full.fluffiness)
            / (1.0 + FLUFF_COVER_PER_FLUFFINESS * self.fluffiness);
        segments * (1.0 + loss) * fluff
    }
}

/// Most camera views one knit models for: each is rasterised once by the hidden-yarn pass
/// and projected once per stitch, so an animated camera is sampled to at most this many
/// frames (the add-on samples its frame range down to fit).
pub const MAX_VIEWS: usize = 2048;

/// Most samples a side of the hidden-yarn pass's grid (resolution times supersampling):
/// a 16K render at 4 x 4 samples a pixel (about 17 s on 2 cores); past it, its time grows
/// with the square into minutes.
pub const MAX_HIDDEN_SAMPLES: u64 = 65536;

impl DetailParams {
    /// Checks the user's detail settings (thresholds, frame margin, visibility samples, Cull
    /// From) against their ranges, camera or not: a setting out of range is refused even
    /// where no camera would use it, as every other setting is. Errors name the setting.
    pub fn validate_settings(&self) -> Result<()> {
        let t = (self.full_px, self.mid_px, self.texture_px);
        let finite = t.0.is_finite() && t.1.is_finite() && t.2.is_finite();
        if !(finite && t.0 >= t.1 && t.1 >= t.2 && t.2 >= 0.0) {
            return Err(KnitError::Parameter(format!(
                "detail thresholds must satisfy full >= mid >= texture >= 0 pixels, not \
                 {} / {} / {}",
                t.0, t.1, t.2
            )));
        }
        crate::settings::FRUSTUM_MARGIN.check(self.frustum_margin)?;
        crate::settings::HIDDEN_SUPERSAMPLING.check(self.hidden_supersampling)?;
        crate::settings::CULL_HIDDEN_MIN_TRIANGLES.check(self.cull_hidden_min_triangles as f64)
    }

    /// Checks the settings; errors name the setting.
    pub fn validate(&self) -> Result<()> {
        if self.views.is_empty() && self.pinned.is_none() {
            return Err(KnitError::Parameter(
                "camera-driven detail needs at least one camera view or pinned levels".into(),
            ));
        }
        if self.views.len() > MAX_VIEWS {
            return Err(KnitError::Parameter(format!(
                "a camera may have at most {MAX_VIEWS} views, not {}: sample an animated \
                 camera's frames more sparsely (every view is rasterised once)",
                self.views.len()
            )));
        }
        for (i, v) in self.views.iter().enumerate() {
            let finite = v
                .clip_from_object
                .to_cols_array()
                .iter()
                .all(|x| x.is_finite())
                && v.eye.is_finite();
            if !finite {
                return Err(KnitError::Parameter(format!(
                    "camera view {i} has a NaN or infinite matrix or eye"
                )));
            }
            // A projection loses one dimension only at the far plane of an infinite one;
            // a clip-from-object matrix that cannot be inverted flattens the scene (a camera
            // or an object scaled to zero), and every stitch would project to nothing.
            let det = f64::from(v.clip_from_object.determinant());
            let scale = v
                .clip_from_object
                .to_cols_array()
                .iter()
                .fold(0.0f64, |m, x| m.max(f64::from(x.abs())));
            if det.is_nan() || det.abs() <= 1e-12 * scale.powi(4) {
                return Err(KnitError::Parameter(format!(
                    "camera view {i}'s matrix is singular (determinant {det:e}): the camera or \
                     the object is scaled to zero along some axis"
                )));
            }
            if v.eye.w != 0.0 && v.eye.w != 1.0 {
                return Err(KnitError::Parameter(format!(
                    "camera view {i}'s eye has w = {}: give (x, y, z, 1) for a perspective \
                     camera or (dx, dy, dz, 0) for an orthographic one",
                    v.eye.w
                )));
            }
        }
        if !self.poses.is_empty() && self.poses.len() != self.views.len() {
            return Err(KnitError::Parameter(format!(
                "a camera with poses needs one pose per view: {} views, {} poses",
                self.views.len(),
                self.poses.len()
            )));
        }
        let (w, h) = self.resolution;
        if !(1..=65536).contains(&w) || !(1..=65536).contains(&h) {
            return Err(KnitError::Parameter(format!(
                "camera resolution must be 1..=65536 pixels each way, not {w} x {h}"
            )));
        }
        self.validate_settings()?;
        let samples = w.max(h) as u64 * u64::from(self.hidden_supersampling);
        if self.cull_hidden && !self.views.is_empty() && samples > MAX_HIDDEN_SAMPLES {
            return Err(KnitError::Parameter(format!(
                "hidden_supersampling {} at {w} x {h} pixels gives {samples} samples a side; \
                 the hidden-yarn pass takes at most {MAX_HIDDEN_SAMPLES} (its time grows with \
                 their square): lower hidden_supersampling to {} or less",
                self.hidden_supersampling,
                (MAX_HIDDEN_SAMPLES / u64::from(w.max(h))).max(1)
            )));
        }
        if self.cull_hidden && self.views.is_empty() && self.pinned_seen.is_none() {
            return Err(KnitError::Parameter(
                "culling hidden yarn needs camera views or the pinned seen triangles of an \
                 earlier knit"
                    .into(),
            ));
        }
        for (name, q) in [("mid", self.mid), ("far", self.far)] {
            if let Some(q) = q {
                if !(6..=256).contains(&q.samples_per_loop) || !(3..=64).contains(&q.ring_segments)
                {
                    return Err(KnitError::Parameter(format!(
                        "{name} detail needs 6..=256 samples per loop and 3..=64 ring \
                         segments, not {} and {}",
                        q.samples_per_loop, q.ring_segments
                    )));
                }
            }
        }
        Ok(())
    }

    /// The settings of a built `level` for a knit whose full quality is `full`. Coarser
    /// levels never exceed the full one.
    pub fn level_settings(&self, level: Level, full: LevelSettings) -> LevelSettings {
        let q = match level {
            Level::Full => return full,
            Level::Mid => self.mid.unwrap_or(LevelQuality {
                samples_per_loop: (full.samples_per_loop / 2).max(6),
                ring_segments: (5 * full.ring_segments).div_ceil(6).max(3),
                fluff: true,
            }),
            _ => self.far.unwrap_or(LevelQuality {
                samples_per_loop: 6,
                ring_segments: 3,
                fluff: false,
            }),
        };
        LevelSettings {
            samples_per_loop: q.samples_per_loop.min(full.samples_per_loop),
            ring_segments: q.ring_segments.min(full.ring_segments),
            fluffiness: if q.fluff { full.fluffiness } else { 0.0 },
        }
    }

    fn level_of_size(&self, px: f32) -> Level {
        if px >= self.full_px {
            Level::Full
        } else if px >= self.mid_px {
            Level::Mid
        } else if px >= self.texture_px {
            Level::Far
        } else {
            Level::Texture
        }
    }
}

/// Pixel position of clip-space point `c` (x right, y up, origin at the bottom-left corner).
fn to_pixels(c: Vec4, res: Vec2) -> Vec2 {
    (c.xy() / c.w * 0.5 + 0.5) * res
}

/// Clip-space w below which a point counts as at the eye: its projected size is unbounded.
const NEAR_W: f32 = 1e-6;

/// Screen length in pixels of `d` placed at `p` (clip-space `cp`); infinite at the eye.
fn projected_length(view: &CameraView, cp: Vec4, p: Vec3, d: Vec3, res: Vec2) -> f32 {
    let cq = view.clip_from_object * (p + d).extend(1.0);
    if cp.w <= NEAR_W || cq.w <= NEAR_W {
        return f32::INFINITY;
    }
    (to_pixels(cq, res) - to_pixels(cp, res)).length()
}

/// Whether a sphere (centre `p`, radius `r`) meets `view`'s frustum widened by `margin` of
/// the frame's half-size on each side (far plane ignored). Planes from the rows of the
/// clip matrix (Gribb and Hartmann).
fn in_frustum(view: &CameraView, p: Vec3, r: f32, margin: f32) -> bool {
    let m = view.clip_from_object;
    let (r0, r1, r3) = (m.row(0), m.row(1), m.row(3));
    let k = 1.0 + margin;
    let planes = [k * r3 + r0, k * r3 - r0, k * r3 + r1, k * r3 - r1, r3];
    let ph = p.extend(1.0);
    planes.iter().all(|pl| {
        let len = pl.xyz().length();
        len == 0.0 || pl.dot(ph) >= -r * len
    })
}

/// Whether a point with unit normal `n` at `p` faces away from `view`'s eye.
fn faces_away(view: &CameraView, p: Vec3, n: Vec3) -> bool {
    let to_eye = view.eye.xyz() - view.eye.w * p;
    match to_eye.try_normalize() {
        Some(d) => n.dot(d) <= BACK_FACE_COSINE,
        None => false,
    }
}

/// The level of every stitch (row-major, course by wale) for `detail`'s views, or its
/// pinned levels. Stitches not in `built` (no surface under them) are [`Level::Culled`].
/// `reach` is how far the yarn can stand off the surface (scene units): it widens each
/// stitch's bounding sphere.
pub fn stitch_levels(
    surface: &dyn Surface,
    lattice: &Lattice,
    built: &[bool],
    detail: &DetailParams,
    reach: f32,
) -> Result<Vec<Level>> {
    if let Some(pinned) = &detail.pinned {
        if pinned.len() != built.len() {
            return Err(KnitError::Parameter(format!(
                "pinned stitch levels are for {} stitches; this knit has {} ({} courses x {} \
                 wales)",
                pinned.len(),
                built.len(),
                lattice.courses,
                lattice.wales
            )));
        }
        return Ok(pinned
            .iter()
            .zip(built)
            .map(|(&l, &b)| if b { l } else { Level::Culled })
            .collect());
    }
    for (i, pose) in detail.poses.0.iter().enumerate() {
        let same = pose.domain() == surface.domain()
            && pose.cyclic_u() == surface.cyclic_u()
            && pose.cyclic_v() == surface.cyclic_v();
        if !same {
            let d = pose.domain();
            return Err(KnitError::Parameter(format!(
                "camera view {i}'s pose has another (u,v) layout than the knit's surface (UVs \
                 {:?}..{:?}, cyclic {}/{}): a pose is the same surface deformed",
                d.min.to_array(),
                d.max.to_array(),
                pose.cyclic_u(),
                pose.cyclic_v()
            )));
        }
    }
    let wales = lattice.wales;
    let res = Vec2::new(detail.resolution.0 as f32, detail.resolution.1 as f32);
    let mut levels = vec![Level::Culled; built.len()];
    levels
        .par_chunks_mut(wales)
        .enumerate()
        .for_each(|(course, row)| {
            for (wale, level) in row.iter_mut().enumerate() {
                if !built[course * wales + wale] {
                    continue;
                }
                *level = stitch_level(surface, lattice, course, wale, detail, reach, res);
            }
        });
    Ok(levels)
}

impl TryFrom<u8> for Level {
    type Error = KnitError;

    fn try_from(v: u8) -> Result<Self> {
        Level::ALL.get(v as usize).copied().ok_or_else(|| {
            KnitError::Parameter(format!("a stitch level is 0 (full) to 4 (culled), not {v}"))
        })
    }
}

/// A stitch on one pose of the surface: its centre and normal there, the tile's width and
/// height vectors, and the radius of a sphere that holds its yarn.
struct StitchPlace {
    p: Vec3,
    n: Vec3,
    across: Vec3,
    up: Vec3,
    radius: f32,
}

impl StitchPlace {
    fn on(
        surface: &dyn Surface,
        lattice: &Lattice,
        course: usize,
        wale: usize,
        reach: f32,
    ) -> Self {
        let t = lattice.tile(course, wale);
        let at = |uv: Vec2| surface.eval_nearest(uv);
        let centre = at(lattice.tile_center(course, wale));
        let across = at(0.5 * (t.n1 + t.n2)).position - at(0.5 * (t.n0 + t.n3)).position;
        let up = at(0.5 * (t.n0 + t.n1)).position - at(0.5 * (t.n2 + t.n3)).position;
        // The tile's corners are within half its diagonal of the centre; the yarn stands off
        // by at most `reach`; loops reach a third of a row beyond the tile.
        let radius = 0.75 * (across.length() + up.length()) + reach;
        Self {
            p: centre.position,
            n: centre.normal,
            across,
            up,
            radius,
        }
    }
}

fn stitch_level(
    surface: &dyn Surface,
    lattice: &Lattice,
    course: usize,
    wale: usize,
    detail: &DetailParams,
    reach: f32,
    res: Vec2,
) -> Level {
    // On the knit's own surface, found once for the views that see it.
    let mut own: Option<StitchPlace> = None;
    let mut visible = false;
    let mut size: f32 = 0.0;
    for (i, view) in detail.views.iter().enumerate() {
        let posed;
        let place = match detail.poses.of_view(i) {
            Some(pose) => {
                posed = StitchPlace::on(pose, lattice, course, wale, reach);
                &posed
            }
            None => {
                own.get_or_insert_with(|| StitchPlace::on(surface, lattice, course, wale, reach))
            }
        };
        let StitchPlace {
            p,
            n,
            across,
            up,
            radius,
        } = *place;
        if detail.frustum_margin >= 0.0 && !in_frustum(view, p, radius, detail.frustum_margin) {
            continue;
        }
        if detail.cull_back_faces && faces_away(view, p, n) {
            continue;
        }
        visible = true;
        let cp = view.clip_from_object * p.extend(1.0);
        let width = across.length();
        for d in [across, up, width * n] {
            size = size.max(projected_length(view, cp, p, d, res));
        }
    }
    if !visible {
        return Level::Culled;
    }
    detail.level_of_size(size)
}

/// One stretch of a yarn piece built at one level: rings at a subset of the piece's
/// full-density centreline samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    /// Index of the yarn piece.
    pub piece: usize,
    /// First and last sample of the piece this span runs between (inclusive). `last` may
    /// equal the piece's sample count on a closed piece: the sample wrapped to index 0.
    pub first: usize,
    pub last: usize,
    /// Rings of the span's bundle.
    pub rings: usize,
    /// A whole closed piece at one level: the bundle closes on itself.
    pub closed: bool,
    pub level: Level,
}

impl Span {
    /// The piece sample that ring `i` sits on (`samples`: the piece's sample count).
    pub fn sample(&self, i: usize, samples: usize) -> usize {
        if self.closed {
            (i * samples + self.rings / 2) / self.rings
        } else {
            let steps = self.rings - 1;
            let len = self.last - self.first;
            (self.first + (i * len + steps / 2) / steps) % samples
        }
    }
}

/// The spans of one piece of `samples` full-density samples (`full_spl` per loop).
/// `boundaries`: `(first sample, level)` of each run of one level, in yarn order, the first
/// at sample 0 (an open piece) or anywhere (a closed one); `spl(level)` the samples per
/// loop of a level.
pub fn piece_spans(
    piece: usize,
    samples: usize,
    closed: bool,
    runs: &[(usize, Level)],
    full_spl: usize,
    spl: impl Fn(Level) -> usize,
) -> Vec<Span> {
    let rings_for = |len: usize, level: Level| -> usize {
        // Intervals at the level's density, never more than the samples there are.
        let k = (len * spl(level) + full_spl / 2) / full_spl;
        k.clamp(1, len.max(1))
    };
    if runs.len() == 1 {
        let level = runs[0].1;
        return vec![if closed {
            Span {
                piece,
                first: 0,
                last: samples,
                rings: rings_for(samples, level).max(3.min(samples)),
                closed: true,
                level,
            }
        } else {
            Span {
                piece,
                first: 0,
                last: samples - 1,
                rings: if samples < 2 {
                    samples
                } else {
                    rings_for(samples - 1, level) + 1
                },
                closed: false,
                level,
            }
        }];
    }
    let mut spans = Vec::with_capacity(runs.len());
    for (k, &(first, level)) in runs.iter().enumerate() {
        let last = match runs.get(k + 1) {
            Some(&(next, _)) if next > first => next,
            Some(&(next, _)) => next + samples,
            None if closed => runs[0].0 + samples,
            None => samples - 1,
        };
        let len = last - first;
        spans.push(Span {
            piece,
            first,
            last,
            rings: rings_for(len, level) + 1,
            closed: false,
            level,
        });
    }
    spans
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coarser_levels_widen_the_yarn_to_keep_its_cover() {
        let d = DetailParams::default();
        for fluffiness in [0.0, 0.5, 1.5] {
            let full = LevelSettings {
                samples_per_loop: 16,
                ring_segments: 6,
                fluffiness,
            };
            assert_eq!(full.cover_radius_scale(&full), 1.0);
            let mid = d.level_settings(Level::Mid, full).cover_radius_scale(&full);
            let far = d.level_settings(Level::Far, full).cover_radius_scale(&full);
            // Far loses more than mid (a triangular ring, 6 samples a loop, no fluff), and
            // more the fluffier full detail is.
            assert!(
                1.0 < mid && mid < far && far < 2.5,
                "{fluffiness}: {mid} {far}"
            );
            if fluffiness > 0.0 {
                let plain = LevelSettings {
                    fluffiness: 0.0,
                    ..full
                };
                let far_plain = d
                    .level_settings(Level::Far, plain)
                    .cover_radius_scale(&plain);
                assert!(far > far_plain);
            }
        }
    }

    #[test]
    fn full_spans_keep_every_sample() {
        let open = piece_spans(0, 95, false, &[(0, Level::Full)], 16, |_| 16);
        assert_eq!(open[0].rings, 95);
        assert!((0..95).all(|i| open[0].sample(i, 95) == i));
        let closed = piece_spans(0, 96, true, &[(0, Level::Full)], 16, |_| 16);
        assert_eq!(closed[0].rings, 96);
        assert!((0..96).all(|i| closed[0].sample(i, 96) == i));
    }

    #[test]
    fn mixed_spans_share_their_boundary_samples() {
        let spl = |l: Level| match l {
            Level::Full => 16,
            Level::Mid => 8,
            _ => 6,
        };
        let runs = [(0, Level::Far), (32, Level::Full), (64, Level::Mid)];
        let spans = piece_spans(0, 95, false, &runs, 16, spl);
        assert_eq!(spans.len(), 3);
        for w in spans.windows(2) {
            let a = w[0].sample(w[0].rings - 1, 95);
            let b = w[1].sample(0, 95);
            assert_eq!(a, b, "spans must meet at one sample");
        }
        assert_eq!(spans[2].sample(spans[2].rings - 1, 95), 94);
        assert_eq!(spans[0].rings, 13); // 2 stitches at 6 per loop, plus the end ring
                                        // Closed: the last span wraps round to the first one's start.
        let runs = [(16, Level::Full), (48, Level::Far)];
        let spans = piece_spans(0, 64, true, &runs, 16, spl);
        assert_eq!(spans[1].sample(spans[1].rings - 1, 64), 16);
        assert_eq!(spans[0].sample(spans[0].rings - 1, 64), 48);
    }
}
