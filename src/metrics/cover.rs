//! Optical cover (docs/design.md section 7): the fraction of the fabric hidden by yarn in an
//! orthographic view along the fabric's normal, tubes only (no fluff).
//!
//! A tube of radius `r` round a centreline is a union of balls of radius `r`, and the
//! orthographic projection of a ball is a disc of the same radius, so the tube's shadow is
//! exactly the set of points within `r` of the projected centreline. The measure rasterises
//! that set over a rectangle of the view plane (x, y; the view runs along z) at pixel
//! centres, so it depends only on the centrelines, the radius and the grid, and is the same
//! on any thread count.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// Fraction in [0, 1] of the pixel centres of `resolution` x `resolution` pixels over the
/// rectangle `min..max` (x, y; scene units) that lie within `radius` of the projection along
/// z of some centreline segment. `yarns`: polylines of 3D points, each joined in order (a
/// closed one also last to first). NaN when the rectangle or radius is not positive and
/// finite or `resolution` is 0.
pub fn cover(
    yarns: &[(&[Vec3], bool)],
    radius: f32,
    min: Vec2,
    max: Vec2,
    resolution: usize,
) -> f64 {
    match cover_mask(yarns, radius, min, max, resolution) {
        Some(mask) => mask.iter().filter(|&&h| h).count() as f64 / (resolution * resolution) as f64,
        None => f64::NAN,
    }
}

/// The pixels [`cover`] counts: row by row from `min.y` (row-major, `resolution` x
/// `resolution`), true where a pixel centre lies within `radius` of a projected segment.
/// `None` where [`cover`] gives NaN.
pub fn cover_mask(
    yarns: &[(&[Vec3], bool)],
    radius: f32,
    min: Vec2,
    max: Vec2,
    resolution: usize,
) -> Option<Vec<bool>> {
    let size = max - min;
    let valid = radius.is_finite()
        && radius > 0.0
        && size.is_finite()
        && size.x > 0.0
        && size.y > 0.0
        && resolution > 0;
    if !valid {
        return None;
    }
    let px = size / resolution as f32;
    // Segments binned by the pixel rows their disc-swept box touches.
    let mut rows: Vec<Vec<(Vec2, Vec2)>> = vec![Vec::new(); resolution];
    for (points, closed) in yarns {
        let n = points.len();
        let count = if *closed { n } else { n.saturating_sub(1) };
        for j in 0..count {
            let (a, b) = (points[j].truncate(), points[(j + 1) % n].truncate());
            let lo = (a.y.min(b.y) - radius - min.y) / px.y - 0.5;
            let hi = (a.y.max(b.y) + radius - min.y) / px.y - 0.5;
            if hi < 0.0 || lo > (resolution - 1) as f32 {
                continue;
            }
            let (r0, r1) = (
                lo.ceil().max(0.0) as usize,
                (hi.floor() as usize).min(resolution - 1),
            );
            for row in rows.iter_mut().take(r1 + 1).skip(r0) {
                row.push((a, b));
            }
        }
    }
    let r2 = radius * radius;
    let mut mask = vec![false; resolution * resolution];
    mask.par_chunks_mut(resolution)
        .zip(rows.par_iter())
        .enumerate()
        .for_each(|(i, (hit, segs))| {
            let y = min.y + (i as f32 + 0.5) * px.y;
            for &(a, b) in segs {
                let x_lo = a.x.min(b.x) - radius;
                let x_hi = a.x.max(b.x) + radius;
                let c0 = ((x_lo - min.x) / px.x - 0.5).ceil().max(0.0) as usize;
                let c1f = ((x_hi - min.x) / px.x - 0.5).floor();
                if c1f < 0.0 {
                    continue;
                }
                let c1 = (c1f as usize).min(resolution - 1);
                let d = b - a;
                let len2 = d.length_squared();
                for (c, h) in hit.iter_mut().enumerate().take(c1 + 1).skip(c0) {
                    if *h {
                        continue;
                    }
                    let p = Vec2::new(min.x + (c as f32 + 0.5) * px.x, y);
                    let t = if len2 > 0.0 {
                        ((p - a).dot(d) / len2).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    *h = (a + t * d - p).length_squared() <= r2;
                }
            }
        });
    Some(mask)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_yarn_covers_its_width() {
        // A yarn of radius 0.1 across a unit square covers 0.2 of it.
        let line = [Vec3::new(-1.0, 0.5, 0.0), Vec3::new(2.0, 0.5, 3.0)];
        let c = cover(&[(&line, false)], 0.1, Vec2::ZERO, Vec2::ONE, 1000);
        assert!((c - 0.2).abs() < 0.002, "{c}");
        // Parallel yarns a diameter apart cover everything; overlapping ones count once.
        let lines: Vec<[Vec3; 2]> = (0..6)
            .map(|k| {
                let y = 0.1 + 0.2 * k as f32;
                [Vec3::new(-1.0, y, 0.0), Vec3::new(2.0, y, 0.0)]
            })
            .collect();
        let yarns: Vec<(&[Vec3], bool)> = lines.iter().map(|l| (&l[..], false)).collect();
        assert!(cover(&yarns, 0.101, Vec2::ZERO, Vec2::ONE, 500) > 0.999);
        assert!(cover(&yarns, 0.05, Vec2::ZERO, Vec2::ONE, 500) < 0.51);
        assert!(cover(&yarns, -1.0, Vec2::ZERO, Vec2::ONE, 10).is_nan());
    }
}
