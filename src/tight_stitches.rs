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

/// The narrowest (and shortest) stitch the shapes are tuned for, in yarn diameters, never
/// more than the mean stitch. No loop shape clears a much smaller stitch: a flat patch tuned
/// at 2, 2.5 and 3 diameters wide (2.86 tall) keeps its loops 0.50, 0.66 and 0.90 diameters
/// apart, and at 1.25, 1.5, 2 and 2.5 diameters tall (4 wide) 0.59, 0.70, 0.85 and 0.88.
/// Shapes tuned for such a stitch crowd the larger ones too:
/// - a UV sphere of 42 wales at the default yarn has its 5% narrowest stitches, by its poles,
///   at 0.17 of the mean width (0.68 diameters); tuned for them, its yarn kept 1.085
///   diameters apart (1st percentile) round the equator and 0.995 at 30-60% of the way to
///   the poles; tuned 2.5 diameters wide, 1.201 and 1.072;
/// - a sheet whose rows run from 0.2 to 1.8 of the mean height (v mapped quadratically) has
///   its 5% shortest at 0.85 diameters; tuned for them, stockinette's rows of about the mean
///   height kept 0.726 apart and C4's 0.418; tuned 2.5 diameters tall, 1.041 and 0.675, and
///   the squeezed rows no closer (0.328 and 0.207, against 0.283 and 0.164).
///
/// The stitches smaller still collide either way; the report's stretch warning names them.
pub const MIN_TUNED_DIAMETERS: f32 = 2.5;

/// One side of the stitch the shapes are tuned for: the tight stitches' (`tight`), but at
/// least [`MIN_TUNED_DIAMETERS`] yarn diameters (`diameter`, scene units) and never more than
/// the `mean` stitch's.
pub fn tuned_side(tight: f32, mean: f32, diameter: f32) -> f32 {
    tight.max((MIN_TUNED_DIAMETERS * diameter).min(mean))
}

/// Most stitches measured: beyond, every k-th stitch in row-major order.
const MAX_MEASURED: usize = 16_384;

/// How far the stitches' sizes on the surface spread round their mean: the UV map's stretch.
/// One stitch grid covers the whole (u,v) domain, so where the map stretches more than its
/// mean the stitches grow, and where it stretches less they shrink; the gauge holds only on
/// average.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StitchSpread {
    /// The 5th and 95th percentiles of the stitches' widths, over the mean width.
    pub width: (f32, f32),
    /// The same of their heights.
    pub height: (f32, f32),
    /// The fraction of the stitches whose width or height is more than [`STRETCHED`] off the
    /// mean.
    pub stretched: f32,
}

/// How far off the mean a stitch's width or height may be before it counts as stretched:
/// beyond it a knitter sees the gauge change.
pub const STRETCHED: f32 = 0.15;

/// The measures of [`tight_ratios`] and [`StitchSpread`], from one pass over the stitches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StitchSizes {
    /// `(tight width / mean width, tight height / mean height)`.
    pub tight: (f32, f32),
    /// `None` where no stitch can be measured.
    pub spread: Option<StitchSpread>,
}

/// `(tight width / mean width, tight height / mean height)` of the stitches of `lattice` on
/// `surface` ([`stitch_sizes`]).
pub fn tight_ratios(surface: &dyn Surface, lattice: &Lattice) -> (f32, f32) {
    stitch_sizes(surface, lattice).tight
}

/// The stitches of `lattice` on `surface`, measured: a stitch's width is the distance on the
/// surface between the midpoints of its tile's left and right sides, its height between
/// those of its bottom and top. Stitches with a side off the surface are left out; `(1, 1)`
/// and no spread where none can be measured. Depends only on the arguments (a fixed subset,
/// sorted, summed in order).
pub fn stitch_sizes(surface: &dyn Surface, lattice: &Lattice) -> StitchSizes {
    let total = lattice.courses * lattice.wales;
    if total == 0 {
        return StitchSizes {
            tight: (1.0, 1.0),
            spread: None,
        };
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
    let spread = spread(&widths, &heights);
    StitchSizes {
        tight: (ratio(&mut widths), ratio(&mut heights)),
        spread,
    }
}

/// The spread of the measured `widths` and `heights` (same length) round their means.
fn spread(widths: &[f32], heights: &[f32]) -> Option<StitchSpread> {
    let mean = |v: &[f32]| v.iter().map(|&x| f64::from(x)).sum::<f64>() / v.len() as f64;
    if widths.is_empty() {
        return None;
    }
    let (mw, mh) = (mean(widths), mean(heights));
    let relative = |v: &[f32], m: f64| -> Vec<f32> {
        let mut r: Vec<f32> = v.iter().map(|&x| (f64::from(x) / m) as f32).collect();
        r.sort_by(f32::total_cmp);
        r
    };
    let (rw, rh) = (relative(widths, mw), relative(heights, mh));
    let off = |r: f32| (r - 1.0).abs() > STRETCHED;
    let stretched = widths
        .iter()
        .zip(heights)
        .filter(|&(&w, &h)| off((f64::from(w) / mw) as f32) || off((f64::from(h) / mh) as f32))
        .count();
    let at = |r: &[f32], q: f32| r[(q * (r.len() - 1) as f32).round() as usize];
    let finite = |x: f32| if x.is_finite() { x } else { 1.0 };
    Some(StitchSpread {
        width: (finite(at(&rw, 0.05)), finite(at(&rw, 0.95))),
        height: (finite(at(&rh, 0.05)), finite(at(&rh, 0.95))),
        stretched: stretched as f32 / widths.len() as f32,
    })
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
    fn a_stretched_map_spreads_the_stitches() {
        // A map whose u runs quadratically: stitches at one end a fifth as wide as at the
        // other.
        let (rows, cols) = (3, 65);
        let (mut p, mut n) = (Vec::new(), Vec::new());
        for i in 0..rows {
            for j in 0..cols {
                let (u, v) = (j as f32 / (cols - 1) as f32, i as f32 / (rows - 1) as f32);
                p.extend([0.1 * (0.2 * u + 0.8 * u * u), 0.1 * v, 0.0]);
                n.extend([0.0, 0.0, 1.0]);
            }
        }
        let squeezed = crate::surface::GridSurface::new(rows, cols, &p, &n, false, false).unwrap();
        let lattice = Lattice::regular(squeezed.domain(), 20, 24, false, false);
        let s = stitch_sizes(&squeezed, &lattice).spread.unwrap();
        assert!(s.width.0 < 0.4 && s.width.1 > 1.5, "{s:?}");
        assert!(
            (s.height.0 - 1.0).abs() < 1e-3 && (s.height.1 - 1.0).abs() < 1e-3,
            "{s:?}"
        );
        assert!(s.stretched > 0.6, "{s:?}");
        // An even map: none stretched.
        let plane = PlaneSurface {
            width: 0.12,
            height: 0.1,
        };
        let even = Lattice::regular(plane.domain(), 20, 24, false, false);
        assert_eq!(stitch_sizes(&plane, &even).spread.unwrap().stretched, 0.0);
    }

    #[test]
    fn the_tuned_stitch_is_never_smaller_than_a_loop_can_clear() {
        // A sphere's poles: tuned at 2.5 diameters, not at the tightest stitch.
        assert_eq!(tuned_side(0.2, 1.0, 0.25), 0.625);
        // Tight stitches large enough keep their size.
        assert_eq!(tuned_side(0.73, 1.0, 0.25), 0.73);
        // A yarn too thick for its stitch: never larger than the mean.
        assert_eq!(tuned_side(1.0, 1.0, 0.6), 1.0);
        assert_eq!(tuned_side(0.5, 1.0, 0.6), 1.0);
    }

    #[test]
    fn the_quantile_of_uneven_values() {
        let mut v: Vec<f32> = (1..=101).map(|x| x as f32).collect();
        // 5th percentile 6, mean 51.
        assert!((ratio(&mut v) - 6.0 / 51.0).abs() < 1e-6);
        assert_eq!(ratio(&mut []), 1.0);
    }
}
