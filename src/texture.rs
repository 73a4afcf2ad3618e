//! The knitwear texture ([Zhong 2001], section 3, "Knitwear Texture"): the knit drawn in the
//! surface's (u,v) domain as an image, for a material on the source surface. No silhouette,
//! self-occlusion or shadows, but the same lattice (with its `kappa` perturbation), the same
//! yarn centrelines and the same stitch colours as the 3D knit, at the cost of one image.
//!
//! Each yarn piece's centreline, in (u, v, lambda) exactly as [`PreparedKnit::build`] samples
//! it, is drawn as a stroke one yarn diameter wide. Distances are measured in scene units
//! along the fabric (u and v scaled by the stitch width and height), so the yarn is round on
//! the fabric however the (u,v) domain is stretched. Where strokes overlap, the one with the
//! larger normal offset lambda (in front of the fabric) wins and the next one shows through
//! its anti-aliased edge; each stroke is shaded by lambda (in front brighter, behind darker:
//! that is what makes knit Vs and purl bumps read) and across its width like a cylinder.
//! Pixels without yarn are transparent black.
//!
//! Rows of the image are rendered in parallel, each from the yarn segments of its band of
//! rows (bucketed once, in yarn order): every pixel is computed by one thread from data in a
//! fixed order, so the image is the same bits for any thread count.

use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::error::{KnitError, Result};
use crate::geometry::stitch_seed;
use crate::knit::{KnitParams, PreparedKnit, UvYarn};
use crate::parallel::run_in_pool;
use crate::pattern::StitchPattern;
use crate::surface::Surface;

/// Largest width or height of a texture, pixels (Blender's own image limit is far beyond a
/// useful texture; 16384 x 16384 RGBA float is 4 GiB).
pub const MAX_TEXTURE_SIZE: usize = 16384;

/// Image rows per bucket of yarn segments.
const BAND_ROWS: usize = 8;

/// Brightness of a stroke at the back of the fabric (most negative lambda) relative to one
/// at the front; in between, linear in lambda.
const BACK_BRIGHTNESS: f32 = 0.55;
/// Brightness at a stroke's edge relative to its centre line (a cylinder lit from the front).
const EDGE_BRIGHTNESS: f32 = 0.45;

/// A linear RGBA image, `height` rows of `width` pixels, row 0 at the domain's smallest v
/// (Blender's pixel order); column 0 at the smallest u.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureImage {
    pub width: usize,
    pub height: usize,
    /// `height * width * 4` linear RGBA values, straight (not premultiplied) alpha.
    pub pixels: Vec<f32>,
}

impl TextureImage {
    /// RGBA of pixel (x, y).
    pub fn pixel(&self, x: usize, y: usize) -> [f32; 4] {
        let o = 4 * (y * self.width + x);
        [
            self.pixels[o],
            self.pixels[o + 1],
            self.pixels[o + 2],
            self.pixels[o + 3],
        ]
    }
}

/// One straight piece of a yarn's centreline, in scene units on the fabric.
#[derive(Debug, Clone, Copy)]
struct Segment {
    a: Vec2,
    b: Vec2,
    lambda_a: f32,
    lambda_b: f32,
    color: [f32; 3],
}

/// What covers a pixel: the stroke's lambda there, its coverage and its shaded colour.
#[derive(Debug, Clone, Copy)]
struct Hit {
    lambda: f32,
    alpha: f32,
    color: [f32; 3],
}

const NO_HIT: Hit = Hit {
    lambda: f32::NEG_INFINITY,
    alpha: 0.0,
    color: [0.0; 3],
};

/// The knitwear texture of `pattern` on `surface` with `params` (the settings of
/// [`crate::knit::knit`]; `ring_segments` and `fluffiness` do not show): a `width x height`
/// image of the surface's whole (u,v) domain.
///
/// Errors: a size of 0 or over [`MAX_TEXTURE_SIZE`] ([`KnitError::Parameter`]), an image
/// over `params.budget_bytes` ([`KnitError::Budget`]), and whatever
/// [`PreparedKnit::new`] refuses.
pub fn knit_texture(
    surface: &dyn Surface,
    pattern: &StitchPattern,
    params: &KnitParams,
    width: usize,
    height: usize,
) -> Result<TextureImage> {
    for (name, n) in [("width", width), ("height", height)] {
        if n == 0 || n > MAX_TEXTURE_SIZE {
            return Err(KnitError::Parameter(format!(
                "texture {name} must be 1..={MAX_TEXTURE_SIZE} pixels, not {n}"
            )));
        }
    }
    let bytes = (width as u64) * (height as u64) * 16;
    if bytes > params.budget_bytes {
        return Err(KnitError::Budget(format!(
            "a {width} x {height} texture needs {} MiB, over the budget of {} MiB: use a \
             smaller image or raise the budget",
            bytes >> 20,
            params.budget_bytes >> 20
        )));
    }
    // Taken before the knit is prepared, and fallibly: a memory limit (ulimit -v, a farm's
    // cgroup) refuses the image here instead of aborting the process.
    let mut pixels: Vec<f32> = Vec::new();
    pixels.try_reserve_exact(width * height * 4).map_err(|_| {
        KnitError::Budget(format!(
            "the system could not give the {} MiB a {width} x {height} texture needs: use \
                 a smaller image",
            bytes >> 20
        ))
    })?;
    pixels.resize(width * height * 4, 0.0);
    // The texture draws every stitch: camera-driven detail (which leaves distant stitches to
    // this very texture) does not apply.
    let all = KnitParams {
        detail: None,
        ..params.clone()
    };
    let prepared = PreparedKnit::new(surface, pattern, &all)?;
    let image = run_in_pool(params.threads, || {
        let yarns = prepared.uv_centrelines(surface)?;
        Ok(render(&prepared, surface, &yarns, width, height, pixels))
    })??;
    crate::cancel::check()?;
    Ok(image)
}

/// Scene units per (u,v) unit along u and v.
fn fabric_scale(prepared: &PreparedKnit) -> Vec2 {
    let stats = prepared.stats();
    let tile = prepared.lattice().tile;
    Vec2::new(stats.stitch_width / tile.x, stats.stitch_height / tile.y)
}

/// The colour of stitch (course, wale) with its random brightness: the factor the 3D knit
/// gives the first vertex of the stitch (the variation averages out over a 3D stitch; a
/// texture pixel is a whole stitch at the distances it is made for).
fn varied_color(prepared: &PreparedKnit, course: usize, wale: usize) -> [f32; 3] {
    let p = prepared.params();
    let c = prepared.stitch_color(course, wale);
    let mut rng = ChaCha8Rng::seed_from_u64(stitch_seed(p.seed, course, wale));
    let bits = rng.next_u32() & 0xFF_FFFF;
    let unit = bits as f32 * (1.0 / 16_777_216.0);
    let f = 1.0 + p.color_variation.clamp(0.0, 1.0) * (2.0 * unit - 1.0);
    c.map(|x| x * f)
}

/// The segments of every yarn, in scene units from the domain's corner, in yarn order.
fn segments(prepared: &PreparedKnit, yarns: &[UvYarn]) -> Vec<Segment> {
    let scale = fabric_scale(prepared);
    let min = prepared.domain().min;
    let at = |q: Vec3| (Vec2::new(q.x, q.y) - min) * scale;
    let per_yarn: Vec<Vec<Segment>> = yarns
        .par_iter()
        .map(|y| {
            let n = y.points.len();
            let mut out = Vec::with_capacity(n);
            let mut current = None;
            let mut color = [0.0; 3];
            let ends = if y.closed { n } else { n.saturating_sub(1) };
            for i in 0..ends {
                let st = y.stitches[i];
                if current != Some(st) {
                    current = Some(st);
                    color = varied_color(prepared, st.0, st.1);
                }
                let a = y.points[i];
                let b = if i + 1 < n {
                    y.points[i + 1]
                } else {
                    y.points[0] + Vec3::new(y.period_u, 0.0, 0.0)
                };
                out.push(Segment {
                    a: at(a),
                    b: at(b),
                    lambda_a: a.z,
                    lambda_b: b.z,
                    color,
                });
            }
            out
        })
        .collect();
    per_yarn.concat()
}

/// Every pixel of the image into `pixels` (`width * height * 4` zeros, taken by the caller).
fn render(
    prepared: &PreparedKnit,
    surface: &dyn Surface,
    yarns: &[UvYarn],
    width: usize,
    height: usize,
    mut pixels: Vec<f32>,
) -> TextureImage {
    let radius = prepared.yarn_radius();
    let extent = prepared.domain().size() * fabric_scale(prepared);
    let pixel = Vec2::new(extent.x / width as f32, extent.y / height as f32);
    // Half the anti-aliasing ramp across a stroke's edge.
    let half_px = 0.5 * pixel.max_element();
    let reach = radius + half_px;
    let lambda_scale = yarns
        .iter()
        .flat_map(|y| y.points.iter().map(|p| p.z.abs()))
        .fold(0.0f32, f32::max)
        .max(1e-12);

    // Copies of every segment one period away along a cyclic direction, where they reach
    // into the image.
    let shifts_u: &[f32] = if surface.cyclic_u() {
        &[0.0, -1.0, 1.0]
    } else {
        &[0.0]
    };
    let shifts_v: &[f32] = if surface.cyclic_v() {
        &[0.0, -1.0, 1.0]
    } else {
        &[0.0]
    };
    let mut segs = Vec::new();
    for s in segments(prepared, yarns) {
        for &su in shifts_u {
            for &sv in shifts_v {
                let d = Vec2::new(su * extent.x, sv * extent.y);
                let (lo, hi) = ((s.a.min(s.b) + d), (s.a.max(s.b) + d));
                if hi.x + reach < 0.0
                    || lo.x - reach > extent.x
                    || hi.y + reach < 0.0
                    || lo.y - reach > extent.y
                {
                    continue;
                }
                segs.push(Segment {
                    a: s.a + d,
                    b: s.b + d,
                    ..s
                });
            }
        }
    }

    // Rows a segment may touch, bucketed by bands of rows, in segment order.
    let bands = height.div_ceil(BAND_ROWS);
    let row_of = |y: f32| y / pixel.y - 0.5;
    let mut band_segs: Vec<Vec<u32>> = vec![Vec::new(); bands];
    for (i, s) in segs.iter().enumerate() {
        let y0 = row_of(s.a.y.min(s.b.y) - reach).floor().max(0.0) as usize;
        let y1 = (row_of(s.a.y.max(s.b.y) + reach).ceil().max(0.0) as usize).min(height - 1);
        if y0 > y1 {
            continue;
        }
        for band in band_segs
            .iter_mut()
            .take(y1 / BAND_ROWS + 1)
            .skip(y0 / BAND_ROWS)
        {
            band.push(i as u32);
        }
    }

    pixels
        .par_chunks_mut(4 * width)
        .enumerate()
        .for_each(|(y, row)| {
            let py = (y as f32 + 0.5) * pixel.y;
            let mut front = vec![NO_HIT; width];
            let mut behind = vec![NO_HIT; width];
            for &i in &band_segs[y / BAND_ROWS] {
                let s = &segs[i as usize];
                if py < s.a.y.min(s.b.y) - reach || py > s.a.y.max(s.b.y) + reach {
                    continue;
                }
                let x0 = ((s.a.x.min(s.b.x) - reach) / pixel.x - 0.5)
                    .floor()
                    .max(0.0) as usize;
                let x1 = ((s.a.x.max(s.b.x) + reach) / pixel.x - 0.5).ceil().max(0.0) as usize;
                let ab = s.b - s.a;
                let len2 = ab.length_squared();
                for x in x0..=x1.min(width - 1) {
                    let p = Vec2::new((x as f32 + 0.5) * pixel.x, py);
                    let t = if len2 > 0.0 {
                        ((p - s.a).dot(ab) / len2).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    let d = p.distance(s.a + t * ab);
                    if d >= reach {
                        continue;
                    }
                    let alpha = ((radius - d) / (2.0 * half_px) + 0.5).clamp(0.0, 1.0);
                    if alpha <= 0.0 {
                        continue;
                    }
                    let lambda = s.lambda_a + t * (s.lambda_b - s.lambda_a);
                    let depth = (lambda / lambda_scale).clamp(-1.0, 1.0);
                    let lit = BACK_BRIGHTNESS + (1.0 - BACK_BRIGHTNESS) * 0.5 * (depth + 1.0);
                    let across = (1.0 - (d.min(radius) / radius).powi(2)).sqrt();
                    let round = EDGE_BRIGHTNESS + (1.0 - EDGE_BRIGHTNESS) * across;
                    let hit = Hit {
                        lambda,
                        alpha,
                        color: s.color.map(|c| c * lit * round),
                    };
                    if lambda > front[x].lambda {
                        behind[x] = front[x];
                        front[x] = hit;
                    } else if lambda > behind[x].lambda {
                        behind[x] = hit;
                    }
                }
            }
            for (x, px) in row.chunks_exact_mut(4).enumerate() {
                let (f, b) = (front[x], behind[x]);
                let alpha = f.alpha + b.alpha * (1.0 - f.alpha);
                if alpha <= 0.0 {
                    continue;
                }
                for (k, c) in px[..3].iter_mut().enumerate() {
                    *c = (f.color[k] * f.alpha + b.color[k] * b.alpha * (1.0 - f.alpha)) / alpha;
                }
                px[3] = alpha;
            }
        });
    TextureImage {
        width,
        height,
        pixels,
    }
}
