//! The stitch size the loop shapes are tuned for: the tighter stitches of the surface.
//!
//! The gauge and the surface's mean extent give a knit's mean stitch; on a surface whose rows
//! are not all as long (a sphere with one stitch count for every row, a UV map stretched more
//! here than there) the stitches narrow where rows are short. Yarns come closest in the
//! tightest stitches, and stitches wider than those tuned for only have room to spare, so the
//! normal offsets and the rows of leaning loops are chosen for the stitch at the
//! [`TIGHT_QUANTILE`] of the widths (and of the heights) measured on the lattice, not for the
//! mean: measured on a sphere band whose rows shrink to 0.73 of the mean length, C4 clears
//! 0.97 rather than 0.90. On a surface whose stitches are all alike the two agree.

use glam::Vec2;

use crate::lattice::Lattice;
use crate::surface::Surface;

/// Fraction of the stitches narrower (shorter) than the one the shapes are tuned for.
pub const TIGHT_QUANTILE: f32 = 0.05;
/// Most stitches measured: beyond, every k-th stitch in row-major order.
const MAX_MEASURED: usize = 16_384;

/// `(tight width / mean width, tight height / mean height)` of the stitches of `lattice` on
/// `surface`: a stitch's width is the distance on the surface between the midpoints of its
/// tile's left and right sides, its height between those of its bottom and top. Stitches
/// with a side off the surface are left out; `(1, 1)` where none can be measured. Depends only
/// on the arguments (a fixed subset, sorted, summed in order).
pub fn tight_ratios(surface: &dyn Surface, lattice: &Lattice) -> (f32, f32) {
    let total = lattice.courses * lattice.wales;
    if total == 0 {
        return (1.0, 1.0);
    }
    let stride = total.div_ceil(MAX_MEASURED);
    let mut widths = Vec::with_capacity(total / stride + 1);
    let mut heights = Vec::with_capacity(total / stride + 1);
    let at = |uv: Vec2| surface.eval(uv).map(|p| p.position);
    for i in (0..total).step_by(stride) {
        let t = lattice.tile(i / lattice.wales, i % lattice.wales);
        let sides = [
            0.5 * (t.n0 + t.n3),
            0.5 * (t.n1 + t.n2),
            0.5 * (t.n3 + t.n2),
            0.5 * (t.n0 + t.n1),
        ];
        if let [Some(l), Some(r), Some(b), Some(top)] = sides.map(at) {
            let (w, h) = (l.distance(r), b.distance(top));
            if w.is_finite() && h.is_finite() && w > 0.0 && h > 0.0 {
                widths.push(w);
                heights.push(h);
            }
        }
    }
    (ratio(&mut widths), ratio(&mut heights))
}

/// The [`TIGHT_QUANTILE`] of `values` over their mean (1 for none).
fn ratio(values: &mut [f32]) -> f32 {
    if values.is_empty() {
        return 1.0;
    }
    let mean = values.iter().map(|&v| f64::from(v)).sum::<f64>() / values.len() as f64;
    values.sort_by(f32::total_cmp);
    let k = (TIGHT_QUANTILE * (values.len() - 1) as f32).round() as usize;
    let r = (f64::from(values[k]) / mean) as f32;
    if r.is_finite() && r > 0.0 {
        r.min(1.0)
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::PlaneSurface;

    #[test]
    fn alike_stitches_are_their_mean() {
        let plane = PlaneSurface {
            width: 0.12,
            height: 0.1,
        };
        let lattice = Lattice::regular(plane.domain(), 20, 24, false, false);
        let (w, h) = tight_ratios(&plane, &lattice);
        assert!((w - 1.0).abs() < 1e-5 && (h - 1.0).abs() < 1e-5, "{w} {h}");
    }

    #[test]
    fn the_quantile_of_uneven_values() {
        let mut v: Vec<f32> = (1..=101).map(|x| x as f32).collect();
        // 5th percentile 6, mean 51.
        assert!((ratio(&mut v) - 6.0 / 51.0).abs() < 1e-6);
        assert_eq!(ratio(&mut []), 1.0);
    }
}
