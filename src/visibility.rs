//! Which triangles of a mesh some camera view sees: a depth-buffer rasteriser over sample
//! points, for culling the yarn that hides behind other yarn (issue 7).
//!
//! Most of a knit's triangles are never seen: the back of every fluffy bundle, the halves of
//! the loops that pass behind the fabric, the rows a grazing view hides behind nearer rows.
//! On the speed-accuracy scene 15% of the full-detail triangles are the nearest surface at
//! some sample of a 4 x 4 supersampled render. This module finds them.
//!
//! The image is covered by `supersampling x supersampling` sample points per pixel, at the
//! sample centres a renderer at that many times the resolution uses, widened by the frustum
//! margin on every side (stitches the margin keeps, for a camera that pans, keep their seen
//! yarn too). A triangle is **seen** in a view when it is the nearest at one of the samples
//! (ties go to the lower triangle index), or when it **may** be: when its nearest corner is
//! nearer than what the depth buffer holds at some sample within one sample of its bounding
//! box. The second test is what keeps culling from thinning out a render: yarn a few samples
//! wide falls between the samples of this pass but not between those of a renderer that
//! samples elsewhere in the pixel (8x anti-aliasing at 320 x 240 lost 43% of a small knit's
//! pixels to the first test alone), whereas yarn behind a solid front of yarn fails both.
//! A triangle is seen when seen in any view. A triangle is kept
//! without testing (conservatively seen) where the view cannot rasterise it: a corner that is
//! not finite, crosses the eye plane, or lies outside the depth range.
//!
//! Determinism: the frame is cut into square tiles; each tile takes its triangles in index
//! order and has its own depth buffer, so the result is the same for any thread count. Depth
//! is clip `z / w`, interpolated linearly in screen space (exact for a perspective or an
//! orthographic projection).

use glam::{Mat4, Vec4};
use rayon::prelude::*;

use crate::detail::CameraView;
use crate::error::{KnitError, Result};

/// Samples per side of a tile.
const TILE: usize = 64;

/// Clip-space `w` below which a corner counts as at (or behind) the eye.
const NEAR_W: f32 = 1e-7;

/// One vertex in a view: sample-grid position (samples, origin at the widened frame's
/// corner) and depth, or why it cannot be rasterised.
#[derive(Debug, Clone, Copy)]
enum Projected {
    /// `x, y` in samples, `z` clip depth in [-1, 1].
    At { x: f32, y: f32, z: f32 },
    /// Behind the eye plane.
    Behind,
    /// In front of the eye but outside [-1, 1] depth, or not finite.
    Unrasterisable,
}

/// The sample grid of one view: `width x height` samples.
#[derive(Debug, Clone, Copy)]
struct Grid {
    width: usize,
    height: usize,
    /// Samples of margin on the left / bottom: sample `(i, j)` has its centre at
    /// `(i + 0.5 - margin_x, j + 0.5 - margin_y)` in frame samples.
    margin_x: f32,
    margin_y: f32,
    /// Frame size in samples.
    frame_x: f32,
    frame_y: f32,
    /// Samples per pixel side.
    per_pixel: f32,
}

impl Grid {
    fn new(resolution: (u32, u32), supersampling: u32, margin: f32) -> Self {
        let s = supersampling.max(1) as usize;
        let (fw, fh) = (resolution.0 as usize * s, resolution.1 as usize * s);
        let m = margin.max(0.0);
        let mx = (m * fw as f32 / 2.0).ceil() as usize;
        let my = (m * fh as f32 / 2.0).ceil() as usize;
        Self {
            width: fw + 2 * mx,
            height: fh + 2 * my,
            margin_x: mx as f32,
            margin_y: my as f32,
            frame_x: fw as f32,
            frame_y: fh as f32,
            per_pixel: s as f32,
        }
    }

    fn tiles_x(&self) -> usize {
        self.width.div_ceil(TILE)
    }

    fn project(&self, m: &Mat4, p: [f32; 3]) -> Projected {
        let c = *m * Vec4::new(p[0], p[1], p[2], 1.0);
        if !c.is_finite() {
            return Projected::Unrasterisable;
        }
        if c.w <= NEAR_W {
            return Projected::Behind;
        }
        let z = c.z / c.w;
        if !(-1.0..=1.0).contains(&z) {
            return Projected::Unrasterisable;
        }
        Projected::At {
            x: (c.x / c.w * 0.5 + 0.5) * self.frame_x + self.margin_x,
            y: (c.y / c.w * 0.5 + 0.5) * self.frame_y + self.margin_y,
            z,
        }
    }
}

/// What one view makes of a triangle.
enum Class {
    /// Nothing of it can show (behind the eye, or between samples, or outside the grid).
    Unseen,
    /// Kept without a test.
    Kept,
    /// Rasterise over sample columns `i0..=i1`, rows `j0..=j1`.
    Raster {
        i0: usize,
        i1: usize,
        j0: usize,
        j1: usize,
    },
}

fn classify(grid: &Grid, v: [Projected; 3]) -> Class {
    let mut pts = [(0.0f32, 0.0f32); 3];
    let mut behind = 0;
    for (k, p) in v.iter().enumerate() {
        match *p {
            Projected::At { x, y, .. } => pts[k] = (x, y),
            Projected::Behind => behind += 1,
            Projected::Unrasterisable => return Class::Kept,
        }
    }
    match behind {
        0 => {}
        3 => return Class::Unseen,
        _ => return Class::Kept,
    }
    let min_x = pts[0].0.min(pts[1].0).min(pts[2].0);
    let max_x = pts[0].0.max(pts[1].0).max(pts[2].0);
    let min_y = pts[0].1.min(pts[1].1).min(pts[2].1);
    let max_y = pts[0].1.max(pts[1].1).max(pts[2].1);
    // Samples whose centre (i + 0.5) lies within one sample of [min, max]: those the
    // triangle covers, and those beside it that decide whether it may show.
    let i0 = (min_x - 1.5).ceil().max(0.0);
    let i1 = (max_x + 0.5).floor().min(grid.width as f32 - 1.0);
    let j0 = (min_y - 1.5).ceil().max(0.0);
    let j1 = (max_y + 0.5).floor().min(grid.height as f32 - 1.0);
    if i0 > i1 || j0 > j1 {
        return Class::Unseen;
    }
    Class::Raster {
        i0: i0 as usize,
        i1: i1 as usize,
        j0: j0 as usize,
        j1: j1 as usize,
    }
}

/// Marks in `seen` (one flag per triangle) every triangle `view` sees. `positions` is
/// `(V, 3)` in the view's object space, `triangles` `(T, 3)` vertex indices.
fn mark_view(
    positions: &[f32],
    triangles: &[i32],
    view: &CameraView,
    grid: &Grid,
    seen: &mut [bool],
    budget_bytes: u64,
    yarn_radius: f32,
) -> Result<()> {
    let m = view.clip_from_object;
    // Samples per object-space unit at clip w = 1, along the frame's narrower axis: a
    // length `l` at depth `w` spans about `l * unit / w` samples.
    let unit = (m.row(0).truncate().length() * grid.frame_x * 0.5)
        .min(m.row(1).truncate().length() * grid.frame_y * 0.5);
    let row_w = m.row(3);
    // The yarn's width in samples round triangle `t`: from its centroid's depth.
    let yarn_samples = |t: usize| -> f32 {
        let c = &triangles[3 * t..3 * t + 3];
        let mut centre = glam::Vec3::ZERO;
        for &k in c {
            let k = 3 * k as usize;
            centre += glam::Vec3::new(positions[k], positions[k + 1], positions[k + 2]);
        }
        let w = row_w.dot((centre / 3.0).extend(1.0));
        2.0 * yarn_radius * unit / w.max(f32::MIN_POSITIVE)
    };
    let projected: Vec<Projected> = positions
        .par_chunks_exact(3)
        .map(|p| grid.project(&m, [p[0], p[1], p[2]]))
        .collect();
    let corners = |t: usize| -> [Projected; 3] {
        let c = &triangles[3 * t..3 * t + 3];
        [
            projected[c[0] as usize],
            projected[c[1] as usize],
            projected[c[2] as usize],
        ]
    };
    let tiles_x = grid.tiles_x();
    // The keys below hold one entry per tile each triangle touches: a triangle as large as
    // the frame of a huge sample grid touches millions. Counted first, so that a camera
    // resolution or supersampling too large for the budget is refused, not an abort.
    let touched: u64 = (0..seen.len())
        .into_par_iter()
        .map(|t| match classify(grid, corners(t)) {
            Class::Raster { i0, i1, j0, j1 } => {
                ((i1 / TILE - i0 / TILE + 1) as u64) * ((j1 / TILE - j0 / TILE + 1) as u64)
            }
            _ => 0,
        })
        .reduce(|| 0, u64::saturating_add);
    // Per touched (tile, triangle): its key, at most one winner id and one tile slice.
    let per_touch = std::mem::size_of::<u64>() + std::mem::size_of::<u32>() + 16;
    let bytes = touched
        .saturating_mul(per_touch as u64)
        .saturating_add((projected.len() * std::mem::size_of::<Projected>()) as u64);
    if bytes > budget_bytes {
        return Err(KnitError::Budget(format!(
            "the hidden-yarn pass would need about {} MiB for a {} x {} sample grid, over \
             the budget of {} MiB: lower the camera resolution or hidden_supersampling, turn \
             cull_hidden off, or raise the budget",
            bytes >> 20,
            grid.width,
            grid.height,
            budget_bytes >> 20
        )));
    }
    let mut keys: Vec<u64> = Vec::new();
    keys.try_reserve_exact(touched as usize).map_err(|_| {
        KnitError::Budget(format!(
            "the hidden-yarn pass could not allocate {} MiB: lower the camera resolution or \
             hidden_supersampling",
            bytes >> 20
        ))
    })?;
    // (tile << 32 | triangle) for every tile each triangle's samples touch, sorted: each
    // tile's triangles in index order.
    keys.par_extend((0..seen.len()).into_par_iter().flat_map_iter(|t| {
        // Tile columns and rows as half-open ranges (empty when nothing is rasterised).
        let (tx, ty) = match classify(grid, corners(t)) {
            Class::Raster { i0, i1, j0, j1 } => {
                ((i0 / TILE)..(i1 / TILE + 1), (j0 / TILE)..(j1 / TILE + 1))
            }
            _ => (0..0, 0..0),
        };
        ty.flat_map(move |y| {
            tx.clone()
                .map(move |x| ((y * tiles_x + x) as u64) << 32 | t as u64)
        })
    }));
    keys.par_sort_unstable();
    let kept: Vec<usize> = (0..seen.len())
        .into_par_iter()
        .filter(|&t| matches!(classify(grid, corners(t)), Class::Kept))
        .collect();
    for t in kept {
        seen[t] = true;
    }
    let tiles: Vec<&[u64]> = keys.chunk_by(|a, b| a >> 32 == b >> 32).collect();
    let winners: Vec<Vec<u32>> = tiles
        .par_iter()
        .map(|keys| {
            if crate::cancel::requested() {
                return Vec::new();
            }
            let tile = (keys[0] >> 32) as usize;
            let (ox, oy) = ((tile % tiles_x) * TILE, (tile / tiles_x) * TILE);
            let mut depth = [f32::INFINITY; TILE * TILE];
            let mut id = [u32::MAX; TILE * TILE];
            for &key in keys.iter() {
                let t = (key & 0xffff_ffff) as usize;
                let v = corners(t);
                let Class::Raster { i0, i1, j0, j1 } = classify(grid, v) else {
                    continue;
                };
                let p = v.map(|p| match p {
                    Projected::At { x, y, z } => (x, y, z),
                    _ => (0.0, 0.0, 0.0),
                });
                rasterise(p, t as u32, (ox, oy), (i0, i1, j0, j1), &mut depth, &mut id);
            }
            let mut w: Vec<u32> = id.iter().copied().filter(|&i| i != u32::MAX).collect();
            // The triangles that may show between this pass's samples: nearer, at their
            // nearest corner, than the buffer somewhere round them.
            for &key in keys.iter() {
                let t = (key & 0xffff_ffff) as usize;
                let v = corners(t);
                let Class::Raster { i0, i1, j0, j1 } = classify(grid, v) else {
                    continue;
                };
                // Only yarn a renderer's samples can miss: under MAY_SHOW_PX pixels thick
                // there. Thicker yarn is tested at the samples its triangles cover (a wider
                // net would keep the back of every bundle whose shards reach a silhouette,
                // where the front of the bundle covers the same pixels).
                if yarn_samples(t) >= MAY_SHOW_PX * grid.per_pixel {
                    continue;
                }
                // Its bounding box grown by a sample, not its own footprint: a bundle's
                // shards are long and thin, and their footprint grown by a sample still let
                // 0.6% of a small knit's pixels thin out at 8x anti-aliasing.
                let z_near = v.iter().fold(f32::INFINITY, |m, p| match p {
                    Projected::At { z, .. } => m.min(*z),
                    _ => m,
                });
                let (a0, a1) = (i0.max(ox), i1.min(ox + TILE - 1));
                let (b0, b1) = (j0.max(oy), j1.min(oy + TILE - 1));
                let may_show = (b0..=b1).any(|j| {
                    let row = (j - oy) * TILE;
                    depth[row + a0 - ox..=row + a1 - ox]
                        .iter()
                        .any(|&d| d > z_near)
                });
                if may_show {
                    w.push(t as u32);
                }
            }
            w.sort_unstable();
            w.dedup();
            // Up to a tile of samples each before the dedup: kept whole, a million tiles
            // would hold gigabytes of repeats. After it, at most this tile's keys.
            w.shrink_to_fit();
            w
        })
        .collect();
    for w in winners {
        for t in w {
            seen[t as usize] = true;
        }
    }
    Ok(())
}

/// Yarn thinner than this many pixels may show between this pass's samples: a renderer
/// samples anywhere in a pixel, and yarn that thin can fall between this pass's samples and
/// not between its. At 1 pixel, 1% to 2% of a small knit's pixels thinned out at 8x
/// anti-aliasing; at 2, 0.3% at most with a yarn a fifth of a stitch thick, 1.08% with one a
/// quarter of a stitch thick; at 2.5, under the 0.5% the test allows.
const MAY_SHOW_PX: f32 = 2.5;

/// Writes triangle `t` (corners `p`: sample-grid x, y and depth) into one tile's buffers
/// wherever it is strictly nearer than what is there. Edges are inclusive: a sample on an
/// edge shared by two triangles counts for both (seeing a sliver too many costs nothing).
fn rasterise(
    p: [(f32, f32, f32); 3],
    t: u32,
    (ox, oy): (usize, usize),
    (i0, i1, j0, j1): (usize, usize, usize, usize),
    depth: &mut [f32; TILE * TILE],
    id: &mut [u32; TILE * TILE],
) {
    let [(x0, y0, z0), (x1, y1, z1), (x2, y2, z2)] = p;
    let area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
    if area == 0.0 || !area.is_finite() {
        return;
    }
    let inv = 1.0 / area;
    let (a0, a1) = (i0.max(ox), i1.min(ox + TILE - 1));
    let (b0, b1) = (j0.max(oy), j1.min(oy + TILE - 1));
    if a0 > a1 || b0 > b1 {
        return;
    }
    // Barycentric weights of corners 1 and 2 are affine in the sample position: step them
    // along each row (each >= 0 inside, either winding).
    let (d1x, d1y) = ((y2 - y0) * inv, -(x2 - x0) * inv);
    let (d2x, d2y) = (-(y1 - y0) * inv, (x1 - x0) * inv);
    let (sx0, sy0) = (a0 as f32 + 0.5 - x0, b0 as f32 + 0.5 - y0);
    let (d0x, d0y) = (-(d1x + d2x), -(d1y + d2y));
    // The three weights at (sx, sy) as an affine start for [`span`].
    let starts = |sx: f32, sy: f32| {
        [
            1.0 + sx * d0x + sy * d0y,
            sx * d1x + sy * d1y,
            sx * d2x + sy * d2y,
        ]
    };
    let weights = |sx: f32, sy: f32| {
        let w1 = sx * d1x + sy * d1y;
        let w2 = sx * d2x + sy * d2y;
        (1.0 - w1 - w2, w1, w2)
    };
    // Where it is inside (every weight >= 0) and strictly nearer. Branch-free, so that a
    // row runs on vector lanes; rows and columns compute the same expressions for the same
    // sample, so either way gives the same bits.
    let write = |(w0, w1, w2): (f32, f32, f32), d: &mut f32, i: &mut u32| {
        let z = z0 + w1 * (z1 - z0) + w2 * (z2 - z0);
        let nearer = (w0 >= 0.0) & (w1 >= 0.0) & (w2 >= 0.0) & (z < *d);
        *d = if nearer { z } else { *d };
        *i = if nearer { t } else { *i };
    };
    if b1 - b0 > 4 * (a1 - a0) {
        // Much taller than wide (a fibre strand running up the screen): by columns. Each
        // row sets up its span for a handful of samples, and on such a triangle that set-up
        // costs more than the samples; a column does not run on vector lanes, so rows stay
        // the way wherever they are long enough (the pass at 1080p, 2 x 2 samples, one
        // thread: rows only 310 ms; columns where taller than wide 289 ms, where four times
        // taller 251 ms).
        let steps = [d0y, d1y, d2y].map(|q| (q, if q != 0.0 { 1.0 / q } else { 0.0 }));
        for (c, i) in (a0..=a1).enumerate() {
            let sx = sx0 + c as i32 as f32;
            let Some((lo, hi)) = span(starts(sx, sy0), steps, (b1 - b0) as i32) else {
                continue;
            };
            for r in lo..=hi {
                let k = (b0 - oy + r) * TILE + (i - ox);
                write(
                    weights(sx, sy0 + r as i32 as f32),
                    &mut depth[k],
                    &mut id[k],
                );
            }
        }
        return;
    }
    let steps = [d0x, d1x, d2x].map(|q| (q, if q != 0.0 { 1.0 / q } else { 0.0 }));
    for (r, j) in (b0..=b1).enumerate() {
        let sy = sy0 + r as i32 as f32;
        let Some((lo, hi)) = span(starts(sx0, sy), steps, (a1 - a0) as i32) else {
            continue;
        };
        // Buffer index of column c: a0 >= ox, so nothing here goes below zero.
        let base = (j - oy) * TILE + (a0 - ox);
        let depths = &mut depth[base + lo..=base + hi];
        let ids = &mut id[base + lo..=base + hi];
        for (n, (d, i)) in depths.iter_mut().zip(ids.iter_mut()).enumerate() {
            write(weights(sx0 + (lo + n) as i32 as f32, sy), d, i);
        }
    }
}

/// The steps `0..=last` along a row or column of samples where all three barycentric
/// weights can be >= 0, each weight being `starts[e] + q * step` with `(q, 1 / q)` in
/// `steps[e]` (`1 / q` is 0 where `q` is). The span only skips work (each sample in it is
/// still tested exactly), so its ends are rounded a whole step outwards by truncation, which
/// covers the reciprocal's rounding and needs no libm floor or ceil (a tenth of the pass's
/// time); an end beyond the line saturates to the line's own end. None: no step can be.
fn span(starts: [f32; 3], steps: [(f32, f32); 3], last: i32) -> Option<(usize, usize)> {
    let (mut lo, mut hi) = (0i32, last);
    for (p, (q, inv_q)) in starts.into_iter().zip(steps) {
        let at = -p * inv_q;
        if q > 0.0 {
            if !at.is_nan() {
                lo = lo.max((at as i32).saturating_sub(1));
            }
        } else if q < 0.0 {
            if !at.is_nan() {
                hi = hi.min((at as i32).saturating_add(1));
            }
        } else if p < 0.0 || p.is_nan() {
            hi = -1;
        }
    }
    (lo <= hi).then_some((lo as usize, hi as usize))
}

/// How the hidden-yarn pass samples a view, and what bounds it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VisibilityPass {
    /// Render resolution, pixels (width, height).
    pub resolution: (u32, u32),
    /// Samples per pixel side.
    pub supersampling: u32,
    /// The frame widened by this fraction of the half-frame on every side (negative: none).
    pub margin: f32,
    /// The pass's own buffers stay within this, or it is a [`KnitError::Budget`].
    pub budget_bytes: u64,
    /// The yarn's radius (object space): where it is under [`MAY_SHOW_PX`] pixels thick the
    /// samples cannot be trusted to catch it.
    pub yarn_radius: f32,
}

/// One flag per triangle: whether any of `views` sees it, sampled as `pass` says (the
/// margin is a fraction of the half-frame, as
/// [`crate::detail::DetailParams::frustum_margin`]). `positions` `(V, 3)` and `triangles`
/// `(T, 3)` as [`crate::knit::KnitOutput`] holds them, in the views' object space. Runs in
/// the caller's rayon pool.
pub fn seen_triangles(
    positions: &[f32],
    triangles: &[i32],
    views: &[CameraView],
    pass: &VisibilityPass,
) -> Result<Vec<bool>> {
    let mut seen = vec![false; triangles.len() / 3];
    let grid = Grid::new(pass.resolution, pass.supersampling, pass.margin);
    for view in views {
        mark_view(
            positions,
            triangles,
            view,
            &grid,
            &mut seen,
            pass.budget_bytes,
            pass.yarn_radius,
        )?;
        crate::cancel::check()?;
    }
    Ok(seen)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec3, Vec4};

    fn pass(resolution: (u32, u32), supersampling: u32, margin: f32) -> VisibilityPass {
        VisibilityPass {
            resolution,
            supersampling,
            margin,
            budget_bytes: u64::MAX,
            yarn_radius: 0.0,
        }
    }

    /// A 90-degree perspective camera at the origin looking down -z (OpenGL conventions).
    fn perspective(near: f32, far: f32) -> Mat4 {
        Mat4::from_cols(
            Vec4::new(1.0, 0.0, 0.0, 0.0),
            Vec4::new(0.0, 1.0, 0.0, 0.0),
            Vec4::new(0.0, 0.0, (far + near) / (near - far), -1.0),
            Vec4::new(0.0, 0.0, 2.0 * far * near / (near - far), 0.0),
        )
    }

    /// An orthographic view down -z of the square [-1, 1]^2, depth from z = 1 (near) to
    /// z = -1 (far).
    fn ortho() -> CameraView {
        CameraView {
            clip_from_object: Mat4::from_scale(Vec3::new(1.0, 1.0, -1.0)),
            eye: Vec4::new(0.0, 0.0, 1.0, 0.0),
        }
    }

    /// Two triangles (a square) at height `z`, covering [lo, hi]^2.
    fn square(z: f32, lo: f32, hi: f32, base: i32) -> (Vec<f32>, Vec<i32>) {
        let p = vec![lo, lo, z, hi, lo, z, hi, hi, z, lo, hi, z];
        let t = vec![base, base + 1, base + 2, base, base + 2, base + 3];
        (p, t)
    }

    fn scene(squares: &[(f32, f32, f32)]) -> (Vec<f32>, Vec<i32>) {
        let (mut p, mut t) = (Vec::new(), Vec::new());
        for (k, &(z, lo, hi)) in squares.iter().enumerate() {
            let (a, b) = square(z, lo, hi, 4 * k as i32);
            p.extend(a);
            t.extend(b);
        }
        (p, t)
    }

    #[test]
    fn a_square_behind_a_larger_one_is_not_seen() {
        let (p, t) = scene(&[(0.0, -0.5, 0.5), (0.5, -0.8, 0.8)]);
        let seen = seen_triangles(&p, &t, &[ortho()], &pass((32, 32), 2, -1.0)).unwrap();
        assert_eq!(seen, vec![false, false, true, true]);
    }

    #[test]
    fn a_square_in_front_is_seen_and_so_is_what_shows_around_it() {
        let (p, t) = scene(&[(0.0, -0.8, 0.8), (0.5, -0.5, 0.5)]);
        let seen = seen_triangles(&p, &t, &[ortho()], &pass((32, 32), 2, -1.0)).unwrap();
        assert_eq!(seen, vec![true, true, true, true]);
    }

    #[test]
    fn another_view_that_sees_round_the_occluder_keeps_the_triangle() {
        let (p, t) = scene(&[(0.0, -0.5, 0.5), (0.5, -0.8, 0.8)]);
        // Looking from below (+z flipped): the first square is now in front.
        let below = CameraView {
            clip_from_object: Mat4::from_scale(Vec3::new(1.0, -1.0, 1.0)),
            eye: Vec4::new(0.0, 0.0, -1.0, 0.0),
        };
        let once = seen_triangles(&p, &t, &[ortho()], &pass((32, 32), 2, -1.0)).unwrap();
        let both = seen_triangles(&p, &t, &[ortho(), below], &pass((32, 32), 2, -1.0)).unwrap();
        assert_eq!(once, vec![false, false, true, true]);
        assert_eq!(both, vec![true, true, true, true]);
    }

    #[test]
    fn the_margin_keeps_what_lies_just_outside_the_frame() {
        // A square beyond the right edge of the frame, within a 0.5 margin.
        let (p, t) = scene(&[(0.0, 1.1, 1.3)]);
        let none = seen_triangles(&p, &t, &[ortho()], &pass((32, 32), 2, 0.0)).unwrap();
        let margin = seen_triangles(&p, &t, &[ortho()], &pass((32, 32), 2, 0.5)).unwrap();
        assert_eq!(none, vec![false, false]);
        assert_eq!(margin, vec![true, true]);
    }

    #[test]
    fn a_triangle_between_samples_may_show_unless_hidden_and_one_across_the_eye_is_kept() {
        // Far smaller than a sample, between sample centres: another renderer's samples may
        // fall on it, so it is kept...
        let p = vec![0.001, 0.001, 0.0, 0.002, 0.001, 0.0, 0.001, 0.002, 0.0];
        let t = vec![0, 1, 2];
        assert_eq!(
            seen_triangles(&p, &t, &[ortho()], &pass((4, 4), 1, -1.0)).unwrap(),
            vec![true]
        );
        // ...unless something nearer covers every sample round it.
        let (mut front, mut ft) = scene(&[(0.5, -0.9, 0.9)]);
        front.extend(&p);
        ft.extend([4, 5, 6]);
        assert_eq!(
            seen_triangles(&front, &ft, &[ortho()], &pass((4, 4), 1, -1.0)).unwrap(),
            vec![true, true, false]
        );
        let persp = CameraView {
            clip_from_object: perspective(0.1, 10.0),
            eye: Vec4::new(0.0, 0.0, 0.0, 1.0),
        };
        // One corner behind the eye: not rasterised, kept.
        let p = vec![0.0, 0.0, -1.0, 0.1, 0.0, -1.0, 0.0, 0.0, 1.0];
        assert_eq!(
            seen_triangles(&p, &t, &[persp], &pass((8, 8), 1, -1.0)).unwrap(),
            vec![true]
        );
        // All behind: never seen.
        let p = vec![0.0, 0.0, 1.0, 0.1, 0.0, 1.0, 0.0, 0.1, 1.0];
        assert_eq!(
            seen_triangles(&p, &t, &[persp], &pass((8, 8), 1, -1.0)).unwrap(),
            vec![false]
        );
        // A NaN corner: kept (the view cannot say).
        let p = vec![f32::NAN, 0.0, -1.0, 0.1, 0.0, -1.0, 0.0, 0.1, -1.0];
        assert_eq!(
            seen_triangles(&p, &t, &[persp], &pass((8, 8), 1, -1.0)).unwrap(),
            vec![true]
        );
    }

    /// Every sample of a tile, tested one by one with the same expressions as `rasterise`.
    fn brute_force(
        p: [(f32, f32, f32); 3],
        t: u32,
        depth: &mut [f32; TILE * TILE],
        id: &mut [u32; TILE * TILE],
    ) {
        let [(x0, y0, z0), (x1, y1, z1), (x2, y2, z2)] = p;
        let area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
        let inv = 1.0 / area;
        let (d1x, d1y) = ((y2 - y0) * inv, -(x2 - x0) * inv);
        let (d2x, d2y) = (-(y1 - y0) * inv, (x1 - x0) * inv);
        let (sx0, sy0) = (0.5 - x0, 0.5 - y0);
        for j in 0..TILE {
            for i in 0..TILE {
                let (sx, sy) = (sx0 + i as i32 as f32, sy0 + j as i32 as f32);
                let w1 = sx * d1x + sy * d1y;
                let w2 = sx * d2x + sy * d2y;
                let w0 = 1.0 - w1 - w2;
                let z = z0 + w1 * (z1 - z0) + w2 * (z2 - z0);
                let k = j * TILE + i;
                if w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0 && z < depth[k] {
                    depth[k] = z;
                    id[k] = t;
                }
            }
        }
    }

    #[test]
    fn rows_and_columns_write_exactly_the_samples_inside() {
        // Long thin triangles at every slant, some much taller than wide (rasterised by
        // columns), some wider (by rows), overlapping at random depths in one tile: the
        // spans may skip no sample that is inside, and write none that is not.
        let mut state = 0x9e37_79b9_u32;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state >> 8) as f32 / (1u32 << 24) as f32
        };
        let mut fast = ([f32::INFINITY; TILE * TILE], [u32::MAX; TILE * TILE]);
        let mut slow = fast;
        let mut tall = 0;
        for t in 0..2000u32 {
            let (cx, cy) = (4.0 + 56.0 * next(), 4.0 + 56.0 * next());
            let angle = std::f32::consts::TAU * next();
            let (len, width) = (5.0 + 40.0 * next(), 0.3 + 4.0 * next());
            let (dx, dy) = (angle.cos() * len, angle.sin() * len);
            let (nx, ny) = (-angle.sin() * width, angle.cos() * width);
            let p = [
                (cx - dx, cy - dy, next()),
                (cx + dx + nx, cy + dy + ny, next()),
                (cx + dx - nx, cy + dy - ny, next()),
            ];
            let min_x = p[0].0.min(p[1].0).min(p[2].0);
            let max_x = p[0].0.max(p[1].0).max(p[2].0);
            let min_y = p[0].1.min(p[1].1).min(p[2].1);
            let max_y = p[0].1.max(p[1].1).max(p[2].1);
            let clip = |v: f32| v.clamp(0.0, (TILE - 1) as f32) as usize;
            let (i0, i1) = (clip((min_x - 1.5).ceil()), clip((max_x + 0.5).floor()));
            let (j0, j1) = (clip((min_y - 1.5).ceil()), clip((max_y + 0.5).floor()));
            tall += usize::from(j1 - j0 > 4 * (i1 - i0));
            rasterise(p, t, (0, 0), (i0, i1, j0, j1), &mut fast.0, &mut fast.1);
            brute_force(p, t, &mut slow.0, &mut slow.1);
        }
        assert!(tall > 50, "{tall} triangles went by columns");
        assert_eq!(fast.1, slow.1);
        assert!(fast
            .0
            .iter()
            .zip(&slow.0)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
    }

    #[test]
    fn the_result_does_not_depend_on_threads() {
        // Many overlapping squares at random-ish depths over several tiles.
        let squares: Vec<(f32, f32, f32)> = (0..400)
            .map(|k| {
                let f = (k as f32 * 0.618_034).fract();
                let g = (k as f32 * 0.414_213_5).fract();
                (f - 0.5, g * 1.6 - 0.9, g * 1.6 - 0.9 + 0.05 + 0.2 * f)
            })
            .collect();
        let (p, t) = scene(&squares);
        let run = |n| {
            crate::parallel::run_in_pool(Some(n), || {
                seen_triangles(&p, &t, &[ortho()], &pass((200, 150), 2, 0.1)).unwrap()
            })
            .unwrap()
        };
        let one = run(1);
        assert_eq!(one, run(3));
        assert!(one.iter().any(|&s| s) && one.iter().any(|&s| !s));
    }
}
