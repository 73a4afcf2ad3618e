//! Bobbles: the knot of extra loops a bobble (`MB`) works into one stitch, standing off the
//! front of the fabric.
//!
//! Making a bobble works several loops into one stitch, turns and works them back and forth a
//! few times, then gathers them: a small, solid ball of yarn on the front. The stitch itself
//! is drawn as a knit stitch standing a little proud ([`super::stitch_shape`]); the ball is an
//! extra piece of yarn per bobble, coiled into a dome: [`TURNS`] turns round the stitch's
//! centre, each a yarn diameter further out than the last, their radius falling as the cosine
//! of a quarter turn, from [`RADIUS`] at the rim to nothing at the top. The turns rest on one
//! another like a coiled basket's, so from the side the ball is a solid dome, and from the
//! front solid yarn to its middle. It used to stop at half the radius: a ring with a hole
//! through it, over the stitch.

use glam::Vec3;

use super::stitch_shape::tile_at;
use super::{YarnPiece, KEY_POINTS};
use crate::lattice::Lattice;
use crate::pattern::{Form, StitchPattern};

/// Turns of yarn in a bobble's ball.
pub const TURNS: usize = 5;
/// Radius of the ball's rim, its first turn, as a fraction of the stitch width.
pub const RADIUS: f32 = 0.6;
/// How far in front of the surface the ball's rim runs, in yarn diameters (at least); each
/// turn runs one diameter further out than the one before.
pub const FIRST_TURN: f32 = 2.25;

/// One open piece per built bobble stitch of the fabric, in course then wale order.
pub fn bobble_pieces(lattice: &Lattice, built: &[bool], pattern: &StitchPattern) -> Vec<YarnPiece> {
    let wales = lattice.wales;
    let mut pieces = Vec::new();
    for course in 0..lattice.courses {
        for wale in 0..wales {
            if built[course * wales + wale] && pattern.stitch(course, wale).form == Form::Bobble {
                pieces.push(YarnPiece {
                    course,
                    first_wale: wale,
                    // Six key points a turn, counted as one "stitch" each for sampling.
                    stitches: TURNS,
                    closed: false,
                    float_color: None,
                    float_layer: 0,
                    bobble: true,
                    density: 1,
                    edge: None,
                });
            }
        }
    }
    pieces
}

/// Clearance of the ball's rim in front of the yarn under it, in yarn diameters.
pub const OVER_STITCH: f32 = 1.25;

/// Key points of a bobble's ball in (u, v, lambda): [`TURNS`] turns of six points. The rim
/// runs [`FIRST_TURN`] diameters in front of the surface, or [`OVER_STITCH`] in front of
/// `under` (the largest offset of the yarn under the ball, scene units) where that is
/// further out.
pub fn bobble_key_points(
    lattice: &Lattice,
    piece: &YarnPiece,
    diameter: f32,
    under: f32,
) -> Vec<Vec3> {
    let rim = (FIRST_TURN * diameter).max(under + OVER_STITCH * diameter);
    let t = tile_at(lattice, piece.course, piece.first_wale as isize);
    let across = t.n2 - t.n3;
    let up = t.n0 - t.n3;
    // Round in the fabric: a row is about 0.7 of a stitch width at the gauges knitters use.
    let (rx, ry) = (RADIUS, RADIUS / 0.7);
    let centre = t.n3 + 0.5 * across + 0.6 * up;
    let last = (TURNS * KEY_POINTS - 1) as f32;
    (0..TURNS * KEY_POINTS)
        .map(|j| {
            let a = std::f32::consts::TAU * j as f32 / KEY_POINTS as f32;
            // The dome: the radius falls slowly at the rim, where the turns stand on one
            // another, and fast at the top, where they close over its middle.
            let shrink = (std::f32::consts::FRAC_PI_2 * j as f32 / last).cos();
            let p = centre + shrink * (rx * a.cos() * across + ry * a.sin() * up);
            let lambda = rim + j as f32 / KEY_POINTS as f32 * diameter;
            Vec3::new(p.x, p.y, lambda)
        })
        .collect()
}
