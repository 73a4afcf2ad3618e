//! The knitwear skeleton ([Zhong 2001], section 2.3): one continuous yarn centreline per course,
//! through the six key points of every loop, offset along the surface normal and joined by a
//! cubic cardinal spline.
//!
//! The spline is built in (u, v, lambda) space (lambda: normal offset in scene units) and each
//! sample is mapped to 3D as `s(u,v) + lambda n(u,v)`. This binds every sample to the surface
//! by (u,v), so the yarn follows the surface between key points too (on a sphere it does not
//! cut chords), and a deforming surface moves the yarn without rebuilding the skeleton. On a
//! flat surface it is the paper's 3D spline exactly (cardinal splines are affine-invariant),
//! but for courses holding a loop that leans three columns or more, whose knots are spaced by
//! their chords ([`knot_spacing`]) so that the loops' heads do not curl.

pub mod bobbles;
pub mod contact;
pub mod crossings;
pub mod curvature;
mod edge_clearance;
pub mod edges;
pub mod floats;
mod key_points;
mod knot_spacing;
pub mod leaning_rows;
mod offsets;
pub mod relief;
pub mod sampling_density;
mod spline;
pub mod stitch_shape;
pub mod tuning;
pub mod tuning_store;
mod yarn_skeleton;

pub use key_points::{key_points, LoopShape, KEY_POINTS};
pub use offsets::{NormalOffsets, Shape, StraightWales, DEFAULT_SHAPE, SHAPE_COEFFICIENTS};
pub use spline::CardinalSpline;
pub use stitch_shape::stitch_key_points;
pub use yarn_skeleton::YarnSkeleton;

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::lattice::Lattice;
use crate::pattern::StitchPattern;
use crate::surface::Surface;

pub use sampling_density::sampling_density;

/// A continuous run of built stitches of one course: one piece of yarn. A course is one
/// piece unless stitches are missing (outside every UV island); a complete course round a
/// cyclic-u surface is one closed piece.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct YarnPiece {
    pub course: usize,
    /// Wale of the first stitch. With cyclic u a piece may run past the last wale and wrap;
    /// stitch `j` of the piece is at wale `(first_wale + j) % wales`.
    pub first_wale: usize,
    pub stitches: usize,
    pub closed: bool,
    /// A float of stranded colourwork behind the stitches (see [`floats`]), in this palette
    /// colour, rather than the course's own yarn.
    pub float_color: Option<u8>,
    /// A float's layer behind the fabric (0 nearest): its colour's rank among the row's.
    pub float_layer: u8,
    /// The ball of a bobble worked into stitch (course, first_wale) (see [`bobbles`]).
    pub bobble: bool,
    /// Centreline samples per loop as a multiple of the knit's samples per loop, at least 1:
    /// more on courses whose loops lean across columns ([`sampling_density`]).
    pub density: usize,
    /// The cast-on under, or the bind-off over, stitches `first_wale..` of `course` (see
    /// [`edges`]), rather than the course's own yarn.
    pub edge: Option<edges::Edge>,
}

/// Spline sampling settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SplineSampling {
    /// Centreline samples per loop (per stitch), at least 6. Default: 16.
    pub samples_per_loop: usize,
    /// Cardinal spline tension in [0, 1): 0 is Catmull-Rom. Default: 0.
    pub tension: f32,
    /// Row height over stitch width: the spline measures its chords in stitch widths.
    pub aspect: f32,
}

impl SplineSampling {
    /// The spline's chord metric on `lattice`: (u, v) to stitch widths.
    pub fn metric(&self, lattice: &Lattice) -> Vec2 {
        Vec2::new(1.0 / lattice.tile.x, self.aspect / lattice.tile.y)
    }
}

impl YarnPiece {
    /// A run of `stitches` stitches of `course`'s own yarn from `first_wale`.
    pub fn course_run(course: usize, first_wale: usize, stitches: usize, closed: bool) -> Self {
        Self {
            course,
            first_wale,
            stitches,
            closed,
            float_color: None,
            float_layer: 0,
            bobble: false,
            density: 1,
            edge: None,
        }
    }

    /// Number of centreline samples of this piece, closed form. Open pieces sample the
    /// parameter range `[0, 6n - 1]` (the last key point included); closed ones `[0, 6n)`.
    pub fn sample_count(&self, samples_per_loop: usize) -> usize {
        let s = samples_per_loop * self.density.max(1);
        if self.closed {
            self.stitches * s
        } else {
            // Parameters j * 6 / s for j = 0.. while below 6n - 1, then 6n - 1 itself.
            let t_max_scaled = (KEY_POINTS * self.stitches - 1) * s; // t_max * s
            t_max_scaled.div_ceil(KEY_POINTS) + 1
        }
    }

    /// Parameter of sample `j` on the spline through this piece's key points.
    pub fn sample_t(&self, j: usize, samples_per_loop: usize) -> f32 {
        let t = (j * KEY_POINTS) as f32 / (samples_per_loop * self.density.max(1)) as f32;
        if self.closed {
            t
        } else {
            t.min((KEY_POINTS * self.stitches - 1) as f32)
        }
    }
}

/// Which stitches have a surface under all their key points (row-major, course by wale).
pub fn built_stitches(surface: &dyn Surface, lattice: &Lattice) -> Vec<bool> {
    let (courses, wales) = (lattice.courses, lattice.wales);
    let mut built = vec![false; courses * wales];
    built
        .par_chunks_mut(wales)
        .enumerate()
        .for_each(|(r, row)| {
            for (w, b) in row.iter_mut().enumerate() {
                let mut kp = key_points(&lattice.tile(r, w), &LoopShape::PAPER);
                lattice.keep_on_fabric(&mut kp);
                *b = kp.iter().all(|uv| surface.eval(*uv).is_some());
            }
        });
    built
}

/// Of the stitches not `built` (row-major), those whose tile centre lies on the surface: fabric
/// lost where a UV island ends part-way through a stitch (its head reaches into the row above,
/// a leg past the island's side), unlike a stitch wholly in empty UV space between islands,
/// which was never fabric.
pub fn lost_stitches(surface: &dyn Surface, lattice: &Lattice, built: &[bool]) -> usize {
    let wales = lattice.wales;
    built
        .par_chunks(wales.max(1))
        .enumerate()
        .map(|(r, row)| {
            row.iter()
                .enumerate()
                .filter(|&(w, &b)| !b && surface.eval(lattice.tile_center(r, w)).is_some())
                .count()
        })
        .sum()
}

/// Splits every course into pieces of consecutive built stitches.
pub fn yarn_pieces(lattice: &Lattice, built: &[bool]) -> Vec<YarnPiece> {
    let wales = lattice.wales;
    let mut pieces = Vec::new();
    for course in 0..lattice.courses {
        let row = &built[course * wales..(course + 1) * wales];
        for (first_wale, stitches, closed) in runs(row, lattice.cyclic_u) {
            pieces.push(YarnPiece::course_run(course, first_wale, stitches, closed));
        }
    }
    pieces
}

/// The runs of consecutive `true` entries of one course's `row` as (first wale, length,
/// closed): a whole row round a cyclic u is one closed run, and a run across a cyclic seam
/// stays whole (its first wale is then past the seam's far side, and it wraps).
fn runs(row: &[bool], cyclic_u: bool) -> Vec<(usize, usize, bool)> {
    let wales = row.len();
    if wales == 0 {
        return Vec::new();
    }
    if cyclic_u && row.iter().all(|&b| b) {
        return vec![(0, wales, true)];
    }
    let mut out = Vec::new();
    // Start scanning after a missing stitch, so a run across a cyclic seam stays whole.
    let start = if cyclic_u {
        row.iter().position(|&b| !b).unwrap_or(0) + 1
    } else {
        0
    };
    let mut run_start: Option<usize> = None;
    for k in 0..=wales {
        let w = start + k;
        let is_built = k < wales && row[w % wales];
        match (is_built, run_start) {
            (true, None) => run_start = Some(w),
            (false, Some(s)) => {
                out.push((s, w - s, false));
                run_start = None;
            }
            _ => {}
        }
    }
    out
}

/// Key points of a piece in (u, v, lambda), in yarn order.
pub fn piece_key_points(
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    piece: &YarnPiece,
) -> Vec<Vec3> {
    if piece.float_color.is_some() {
        return floats::float_key_points(lattice, piece, offsets.diameter);
    }
    if let Some(edge) = piece.edge {
        return edges::edge_key_points(lattice, pattern, offsets, piece, edge);
    }
    if piece.bobble {
        // The ball stands in front of the yarn under it, however far the stitch's offsets
        // and relief bring that yarn forward: the stitch and its neighbours in its course and
        // the next (the ball reaches up into that one).
        let w = piece.first_wale;
        let wales = [w.checked_sub(1), Some(w), Some(w + 1)];
        let mut under = 0.0f32;
        for course in [piece.course, piece.course + 1] {
            if course >= lattice.courses {
                continue;
            }
            for x in wales.into_iter().flatten() {
                if !lattice.cyclic_u && x >= lattice.wales {
                    continue;
                }
                let x = if lattice.cyclic_u && x >= lattice.wales {
                    x - lattice.wales
                } else {
                    x
                };
                for p in stitch_key_points(lattice, pattern, offsets, course, x) {
                    under = under.max(p.z);
                }
            }
        }
        return bobbles::bobble_key_points(lattice, piece, offsets.diameter, under);
    }
    let mut out = Vec::with_capacity(piece.stitches * KEY_POINTS);
    for j in 0..piece.stitches {
        out.extend(stitch_key_points(
            lattice,
            pattern,
            offsets,
            piece.course,
            piece.first_wale + j,
        ));
    }
    out
}

/// Fills one piece's centreline: 3D points, the surface normal under each, and each sample's
/// stitch index within the piece. The three slices have `piece.sample_count()` elements.
///
/// Where the surface curves more tightly than a stitch's normal offsets reach, the offsets
/// of that stitch are clamped ([`curvature`]); returns how many stitches were.
#[allow(clippy::too_many_arguments)]
pub fn sample_piece(
    surface: &dyn Surface,
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    sampling: &SplineSampling,
    piece: &YarnPiece,
    points: &mut [Vec3],
    normals: &mut [Vec3],
    stitch_of_sample: &mut [u32],
) -> usize {
    let mut out = points.iter_mut().zip(normals.iter_mut());
    for_each_sample(
        surface,
        lattice,
        pattern,
        offsets,
        sampling,
        piece,
        stitch_of_sample,
        |q| {
            let (p, n) = out.next().expect("one point per sample");
            let uv = Vec2::new(q.x, q.y);
            let sp = if piece.edge.is_some() {
                edges::beyond_border(surface, uv, 0.25 * lattice.tile.y)
            } else {
                surface.eval(uv).unwrap_or_else(|| surface.eval_nearest(uv))
            };
            *p = sp.position + q.z * sp.normal;
            *n = sp.normal;
        },
    )
}

/// Like [`sample_piece`], but the centreline before it is mapped onto the surface: each
/// sample in (u, v, lambda) (lambda: the normal offset, scene units, after the same
/// curvature clamping). The knitwear texture draws these.
#[allow(clippy::too_many_arguments)]
pub fn sample_piece_uv(
    surface: &dyn Surface,
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    sampling: &SplineSampling,
    piece: &YarnPiece,
    uvl: &mut [Vec3],
    stitch_of_sample: &mut [u32],
) -> usize {
    let mut out = uvl.iter_mut();
    for_each_sample(
        surface,
        lattice,
        pattern,
        offsets,
        sampling,
        piece,
        stitch_of_sample,
        |q| *out.next().expect("one point per sample") = q,
    )
}

/// The spline samples of a piece in (u, v, lambda), in order, to `emit`; writes each
/// sample's stitch index within the piece. Returns the stitches whose offsets were clamped.
#[allow(clippy::too_many_arguments)]
fn for_each_sample(
    surface: &dyn Surface,
    lattice: &Lattice,
    pattern: &StitchPattern,
    offsets: &NormalOffsets,
    sampling: &SplineSampling,
    piece: &YarnPiece,
    stitch_of_sample: &mut [u32],
    mut emit: impl FnMut(Vec3),
) -> usize {
    let mut kp = piece_key_points(lattice, pattern, offsets, piece);
    let mut clamped = 0;
    for (j, stitch) in kp.chunks_exact_mut(KEY_POINTS).enumerate() {
        let wale = (piece.first_wale + j) % lattice.wales;
        let centre = lattice.tile_center(piece.course, wale);
        let radii = curvature::stitch_curvature_radii(surface, centre, lattice.tile);
        clamped += usize::from(curvature::clamp_offsets(stitch, radii));
    }
    // A closed course comes back to its start one domain width further on in u.
    let period = Vec3::new(lattice.tile.x * lattice.wales as f32, 0.0, 0.0);
    let metric = sampling.metric(lattice);
    let course_piece = piece.float_color.is_none() && piece.edge.is_none() && !piece.bobble;
    let spacing = (course_piece
        && knot_spacing::piece_course_leans_far(
            lattice,
            pattern,
            offsets,
            metric,
            piece.course,
            &kp,
        ))
    .then(|| knot_spacing::knot_spacing(&kp, metric, piece.closed, period));
    let spline = CardinalSpline {
        points: &kp,
        closed: piece.closed,
        tension: sampling.tension,
        period,
        spacing: spacing.as_deref(),
    };
    let owner = |t: f32| ((t / KEY_POINTS as f32) as usize).min(piece.stitches - 1) as u32;
    if piece.edge.is_none() {
        for (j, o) in stitch_of_sample.iter_mut().enumerate() {
            let t = piece.sample_t(j, sampling.samples_per_loop);
            emit(spline.eval(t));
            *o = owner(t);
        }
        return clamped;
    }
    // An edge is kept clear of the fabric it finishes, which needs all its samples at once.
    let t: Vec<f32> = (0..stitch_of_sample.len())
        .map(|j| piece.sample_t(j, sampling.samples_per_loop))
        .collect();
    let mut samples: Vec<Vec3> = t.iter().map(|&t| spline.eval(t)).collect();
    edge_clearance::keep_clear(
        surface,
        lattice,
        pattern,
        offsets,
        sampling,
        piece,
        &t,
        &mut samples,
    );
    for ((o, &t), q) in stitch_of_sample.iter_mut().zip(&t).zip(samples) {
        emit(q);
        *o = owner(t);
    }
    clamped
}
