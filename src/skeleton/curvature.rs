//! Normal offsets against tight curvature (issue 4, case 6): where the surface curves more
//! tightly than the yarn stands off it (a thin cylinder, a sharp crease), an offset towards
//! the centre of curvature would carry the yarn through the axis and out the other side, and
//! neighbouring loops would cross. The offsets of such a stitch are clamped to a fraction of
//! the local curvature radius.
//!
//! The radius is estimated from how much the surface normal turns across the stitch: for two
//! points `a`, `b` of the surface, `|s(a) - s(b)| / |n(a) - n(b)|`, which is exactly `r` for
//! any two points of a circle of radius `r` (chord `2 r sin(t/2)`, normal change
//! `2 sin(t/2)`), whatever the angle `t` between them; the centre of curvature lies on the
//! side where the normals converge. Only offsets towards that centre are clamped: on the
//! convex side offset curves spread out and never fold. Each stitch takes the smallest of the
//! estimates between its tile centre and the centres of its four half-tile neighbours
//! (`c +- w/2` along u, `c +- h/2` along v), and between each opposite pair, so a crease
//! anywhere in the stitch is seen, and so is a tube with only one or two stitches round it
//! (where the points a whole tile apart coincide).

use glam::{Vec2, Vec3};

use crate::surface::Surface;

/// Largest normal offset, as a fraction of the local curvature radius. Offsetting a curve of
/// radius `R` by `l` towards its centre leaves a curve of radius `R - l`, which collapses to a
/// point at `l = R` and folds through itself beyond; at `R / 2` the yarn keeps at least half
/// the surface's radius and its loops keep their order.
pub const MAX_OFFSET_PER_CURVATURE_RADIUS: f32 = 0.5;

/// Normals that turn by less than this (the length of their difference; radians, for small
/// angles) between two points count as parallel: no curvature to clamp for.
const PARALLEL_NORMALS: f32 = 1e-6;

/// The local curvature radii (scene units) of `surface` over the stitch centred at `centre`
/// whose tile is `tile` in (u,v), towards the front (`+normal`) and towards the back: the
/// smallest radius of the directions whose centre of curvature lies on that side.
/// `f32::INFINITY` where the surface does not curve towards that side; zero where the normal
/// turns but the positions do not move (a pole, a cone's apex).
pub fn stitch_curvature_radii(surface: &dyn Surface, centre: Vec2, tile: Vec2) -> SideRadii {
    let c = surface.eval_nearest(centre);
    let mut radii = SideRadii {
        front: f32::INFINITY,
        back: f32::INFINITY,
    };
    for step in [Vec2::new(0.5 * tile.x, 0.0), Vec2::new(0.0, 0.5 * tile.y)] {
        let a = surface.eval_nearest(centre - step);
        let b = surface.eval_nearest(centre + step);
        for (p, q) in [(a, c), (c, b), (a, b)] {
            let turn = p.normal.distance(q.normal);
            if turn.is_nan() || turn <= PARALLEL_NORMALS {
                continue;
            }
            let r = p.position.distance(q.position) / turn;
            // Normals that converge along the way (their difference against the step) meet
            // in front of the surface: the centre of curvature is on the +normal side.
            let converge = (q.normal - p.normal).dot(q.position - p.position) < 0.0;
            let side = if converge {
                &mut radii.front
            } else {
                &mut radii.back
            };
            *side = side.min(r);
        }
    }
    radii
}

/// Curvature radii of a stitch, towards each side of the surface (scene units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SideRadii {
    /// Towards `+normal`: offsets with `lambda > 0` move towards this centre of curvature.
    pub front: f32,
    pub back: f32,
}

/// Clamps the normal offsets (`z` of each key point in (u, v, lambda)) that point towards a
/// centre of curvature to [`MAX_OFFSET_PER_CURVATURE_RADIUS`] of its radius; offsets away
/// from it (the convex side, where offset curves only spread out) are left as they are, so
/// crossing yarns keep their separation on that side. Returns whether any offset changed.
pub fn clamp_offsets(key_points: &mut [Vec3], radii: SideRadii) -> bool {
    let hi = MAX_OFFSET_PER_CURVATURE_RADIUS * radii.front;
    let lo = -MAX_OFFSET_PER_CURVATURE_RADIUS * radii.back;
    let mut clamped = false;
    for k in key_points {
        if k.z > hi || k.z < lo {
            k.z = k.z.clamp(lo, hi);
            clamped = true;
        }
    }
    clamped
}
